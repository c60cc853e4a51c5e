"""The links of the façade's pages: one ``f`` per URL, and a JSON document's links as
its HTML representation has them."""

from __future__ import annotations

from service.ogc.pages import page_links
from service.ogc.urls import self_and_alternate, with_format


def test_with_format_sets_exactly_one_f() -> None:
    assert with_format("http://h/ogc/", "html") == "http://h/ogc/?f=html"
    assert with_format("http://h/ogc/jobs?limit=2&f=json", "html") == (
        "http://h/ogc/jobs?limit=2&f=html"
    )
    assert with_format("http://h/ogc/jobs?status=a&format=x&f=html", "json") == (
        "http://h/ogc/jobs?status=a&format=x&f=json"
    )


def test_a_page_is_self_and_its_json_the_alternate() -> None:
    up = {"href": "http://h/ogc/jobs", "rel": "up", "type": "application/json"}
    document_links = [*self_and_alternate("http://h/ogc/jobs/j1", "this status"), up]
    assert [(x["rel"], x["type"]) for x in document_links[:2]] == [
        ("self", "application/json"),
        ("alternate", "text/html"),
    ]
    assert page_links(document_links) == [
        {
            "href": "http://h/ogc/jobs/j1?f=html",
            "rel": "self",
            "type": "text/html",
            "title": "this status as HTML",
        },
        {
            "href": "http://h/ogc/jobs/j1?f=json",
            "rel": "alternate",
            "type": "application/json",
            "title": "this status as JSON",
        },
        up,
    ]
