"""The web layer says everything once: each JSON route declares its response model.

A route that answers JSON declares the pydantic model of its document as its
``response_model``; FastAPI publishes that model in ``/openapi.json`` and serializes
the answer with it, so the document and its description cannot drift.  A page shares
its URL with a JSON route but is a route of its own (an ``HtmlRoute``, matched only
when the client asks for HTML).  The routes whose answer is not one JSON document
(files, streams, pages, redirects) return a ``Response`` and are listed here by name.
"""

from __future__ import annotations

import typing
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi import FastAPI
from fastapi.routing import APIRoute, iter_route_contexts
from pydantic import BaseModel
from starlette.responses import Response

from service.app import create_app
from service.config import Settings
from service.pages.html_route import HtmlRoute

ROOT = Path(__file__).resolve().parents[1]

#: The routes whose answer is not one JSON document, and what they answer instead.
NOT_A_DOCUMENT: dict[tuple[str, str], str] = {
    ("GET", "/v1/jobs/{job_id}/results/{name}"): "an artifact's bytes",
    ("HEAD", "/v1/jobs/{job_id}/results/{name}"): "an artifact's headers",
    ("GET", "/v1/jobs/{job_id}/events"): "a server-sent event stream",
    ("GET", "/ogc/jobs/{jobID}/results"): "the results in the form the execute request chose",
    ("GET", "/ogc/jobs/{jobID}/results/{outputID}"): "one output: JSON of any shape or bytes",
    ("HEAD", "/ogc/jobs/{jobID}/results/{outputID}"): "one output's headers",
    ("GET", "/metrics"): "the Prometheus text format",
    ("GET", "/docs"): "the API documentation page",
    ("GET", "/docs/oauth2-redirect"): "the API documentation's sign-in page",
    ("GET", "/redoc"): "the API reference page",
    ("GET", "/favicon.ico"): "an icon",
    ("GET", "/methods"): "a page",
    ("GET", "/methods/{slug}"): "a page",
    ("GET", "/login"): "a page",
    ("POST", "/login"): "a redirect or a page",
    ("POST", "/logout"): "a redirect",
    ("POST", "/pages/processes/{process_id}/run"): "a redirect or a page",
    ("POST", "/pages/processes/design-study/build"): "a redirect or the study builder page",
    ("POST", "/pages/jobs/{job_id}/dismiss"): "a redirect",
    ("GET", "/pages/jobs/{job_id}/edit"): "a page (the process form, pre-filled)",
    ("GET", "/pages/jobs/{job_id}/dismiss"): "a page asking to confirm, or a redirect",
    ("GET", "/pages/compare"): "a page",
    ("GET", "/pages/processes/{process_id}/explore"): "a page (the live explorer)",
    ("POST", "/pages/jobs/{job_id}/designs/{index}/run"): "a redirect or a page",
    ("GET", "/pages/jobs/{job_id}/designs/{index}/edit"): "a page (the process form, pre-filled)",
    ("GET", "/queue"): "a page",
}


def _app() -> FastAPI:
    return create_app(Settings(metrics=True))


def _routes(app: FastAPI) -> Iterator[tuple[str, str, APIRoute, Any]]:
    """``(method, path, route, context)`` of every API route, routers included."""
    for context in iter_route_contexts(app.routes):
        route = context.original_route
        if isinstance(route, APIRoute):
            for method in sorted(context.methods or ()):
                yield method, str(context.path), route, context


def _returns_response(route: APIRoute) -> bool:
    annotation = typing.get_type_hints(route.endpoint).get("return")
    return isinstance(annotation, type) and issubclass(annotation, Response)


def _json_routes(app: FastAPI) -> list[tuple[str, str, Any]]:
    return [
        (method, path, context)
        for method, path, route, context in _routes(app)
        if not isinstance(route, HtmlRoute) and (method, path) not in NOT_A_DOCUMENT
    ]


def test_no_route_says_response_model_none() -> None:
    sources = [
        p for p in (ROOT / "service").rglob("*.py") if "response_model=None" in p.read_text()
    ]
    assert not sources, f"a JSON route declares its model; pages return a Response: {sources}"


def test_every_json_route_declares_its_document_model() -> None:
    app = _app()
    routes = _json_routes(app)
    assert len(routes) > 20, "the walk found the routers' routes"
    missing = [
        f"{method} {path}"
        for method, path, context in routes
        if not (isinstance(context.response_model, type)
                and issubclass(context.response_model, BaseModel))
    ]  # fmt: skip
    assert not missing, f"JSON routes without a response model: {missing}"


def test_the_routes_that_answer_no_document_are_the_listed_ones() -> None:
    """A route returning a bare Response is one of NOT_A_DOCUMENT, and each of those
    exists and returns a Response: a new JSON route cannot slip out of its model."""
    app = _app()
    raw = {
        (method, path)
        for method, path, route, _ in _routes(app)
        if not isinstance(route, HtmlRoute) and _returns_response(route)
    }
    assert raw == set(NOT_A_DOCUMENT)


def test_each_page_shares_its_url_with_a_json_route_and_stays_out_of_the_document() -> None:
    app = _app()
    routes = list(_routes(app))
    others = {(m, p) for m, p, route, _ in routes if not isinstance(route, HtmlRoute)}
    pages = [(m, p, c) for m, p, route, c in routes if isinstance(route, HtmlRoute)]
    assert len(pages) >= 16
    assert [(m, p) for m, p, _ in pages if (m, p) not in others] == []
    assert [(m, p) for m, p, context in pages if context.include_in_schema] == []


@pytest.mark.parametrize("module", ["service/routes", "service/ogc/routes.py",
                                    "service/ogc/jobs/routes.py"])  # fmt: skip
def test_json_handlers_never_negotiate(module: str) -> None:
    """Pages have their own routes: no JSON handler asks whether the client wants HTML."""
    path = ROOT / module
    files = sorted(path.rglob("*.py")) if path.is_dir() else [path]
    negotiating = [str(p.relative_to(ROOT)) for p in files if "wants_html" in p.read_text()]
    assert not negotiating


def test_each_documented_success_is_the_route_model() -> None:
    """The 200/201 schema /openapi.json publishes is the route's model: its members and
    required members, as pydantic reads the model."""
    app = _app()
    document = app.openapi()
    schemas = document["components"]["schemas"]
    checked = 0
    for method, path, context in _json_routes(app):
        if not context.include_in_schema:
            continue
        model: type[BaseModel] = context.response_model
        status = str(context.status_code or 200)
        response = document["paths"][path][method.lower()]["responses"][status]
        schema = response["content"]["application/json"]["schema"]
        assert schema == {"$ref": f"#/components/schemas/{model.__name__}"}, (method, path)
        published = schemas[model.__name__]
        own = model.model_json_schema(mode="serialization")
        assert set(published["properties"]) == set(own["properties"]), (method, path)
        assert set(published.get("required", [])) == set(own.get("required", [])), (method, path)
        checked += 1
    assert checked > 20
