"""The OGC façade as pages (conformance class ``html``) over the real app (ASGI, embedded
backend): every GET resource of /ogc/ answers an HTML 5 page to a browser (or with
``f=html``) holding its JSON document's content and every one of its links as an
``<a href>``, while JSON stays the default; the job list applies the OGC filters;
problems are pages too.
"""

from __future__ import annotations

import asyncio
import time
from collections.abc import AsyncIterator
from html.parser import HTMLParser
from pathlib import Path
from typing import Any

import httpx
import pytest

from service.app import create_app
from service.config import Settings
from service.ogc.urls import with_format

pytestmark = [pytest.mark.integration, pytest.mark.anyio]

BROWSER = "text/html,application/xhtml+xml,application/xml;q=0.9,image/avif,*/*;q=0.8"
CONF = "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/"
BASE = "http://dexlab.test"
FOURBAR = {"lengths": [2, 7, 9, 6], "ground": 1}
EXECUTE = "/ogc/processes/fourbar-grashof/execution"
#: An execute request choosing two outputs: one by value, one file by reference.
CHOSEN = {
    "inputs": FOURBAR,
    "response": "document",
    "outputs": {"classification": {}, "fourbar_motion.svg": {"transmissionMode": "reference"}},
}
#: Where a job runs long enough to be asked for its results before it ends.
SLOW = "/ogc/processes/planar3r-dexterity-map/execution"
SLOW_INPUTS = {"links": [15, 14, 8], "grid": {"points_per_axis": 301}, "plots": False}
_VOID = frozenset(
    [
        "area",
        "base",
        "br",
        "col",
        "embed",
        "hr",
        "img",
        "input",
        "link",
        "meta",
        "source",
        "track",
        "wbr",
    ]
)


class Page(HTMLParser):
    """An HTML document's anchors, images, text and unclosed or stray tags."""

    def __init__(self, text: str) -> None:
        super().__init__()
        self.doctype = ""
        self.hrefs: list[str] = []
        self.images: list[str] = []
        self.text: list[str] = []
        self.open: list[str] = []
        self.stray: list[str] = []
        self.feed(text)
        self.close()

    def handle_decl(self, decl: str) -> None:
        self.doctype = decl

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag == "a":
            self.hrefs += [v for k, v in attrs if k == "href" and v is not None]
        if tag == "img":
            self.images += [v for k, v in attrs if k == "src" and v is not None]
        if tag not in _VOID:
            self.open.append(tag)

    def handle_endtag(self, tag: str) -> None:
        if self.open and self.open[-1] == tag:
            self.open.pop()
        else:
            self.stray.append(tag)

    def handle_data(self, data: str) -> None:
        self.text.append(data)

    @property
    def all_text(self) -> str:
        return " ".join(" ".join(self.text).split())


def parse_page(r: httpx.Response) -> Page:
    assert r.status_code == 200, (r.url, r.status_code, r.text[:300])
    assert r.headers["content-type"].startswith("text/html"), r.url
    page = Page(r.text)
    assert page.doctype.lower() == "doctype html", r.url  # HTML 5
    assert not page.open and not page.stray, (r.url, page.open, page.stray)
    return page


def expected_hrefs(document: dict[str, Any]) -> list[str]:
    """Every link of a JSON document as its page must show it: the document's own
    ``self`` becomes the page's JSON ``alternate`` (``f=json``); the rest as they are,
    the links of the process summaries and status infos inside it too."""
    hrefs = [
        with_format(link["href"], "json") if link["rel"] == "self" else link["href"]
        for link in document.get("links", ())
    ]
    for inner in (*document.get("processes", ()), *document.get("jobs", ())):
        hrefs += [link["href"] for link in inner["links"]]
    return hrefs


@pytest.fixture(scope="module")
def anyio_backend() -> str:
    return "asyncio"


@pytest.fixture(scope="module")
async def client(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[httpx.AsyncClient]:
    settings = Settings(
        data_dir=Path(tmp_path_factory.mktemp("ogc-pages")), workers=1, heartbeat_seconds=0.5
    )
    app = create_app(settings)
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url=BASE) as c:
            deadline = time.monotonic() + 60
            while (await c.get("/health/ready")).status_code != 200:
                assert time.monotonic() < deadline, "the worker pool never came up"
                await asyncio.sleep(0.2)
            yield c


@pytest.fixture(scope="module")
async def job_url(client: httpx.AsyncClient) -> str:
    """A finished fourbar job whose execute request chose two outputs."""
    r = await client.post(EXECUTE, json=CHOSEN, headers={"Prefer": "respond-sync, wait=60"})
    assert r.status_code == 200, r.text
    return str(r.headers["location"])


def resources(job_url: str) -> list[str]:
    return [
        "/ogc/",
        "/ogc/conformance",
        "/ogc/processes",
        "/ogc/processes/fourbar-grashof",
        "/ogc/jobs",
        job_url,
        f"{job_url}/results",
        f"{job_url}/results/classification",
    ]


async def test_json_stays_the_default_and_pages_are_negotiated(
    client: httpx.AsyncClient, job_url: str
) -> None:
    for path in resources(job_url):
        plain = await client.get(path)
        assert plain.headers["content-type"] == "application/json", path
        assert "Accept" in plain.headers["vary"], path
        for headers, params in (({"Accept": BROWSER}, {}), ({}, {"f": "html"})):
            page = await client.get(path, headers=headers, params=params)
            assert page.headers["content-type"].startswith("text/html"), (path, headers)
        forced = await client.get(path, headers={"Accept": BROWSER}, params={"f": "json"})
        assert forced.json() == plain.json(), path
    conformance = (await client.get("/ogc/conformance")).json()["conformsTo"]
    assert CONF + "html" in conformance and CONF + "json" in conformance
    bad = await client.get("/ogc/conformance", params={"f": "xml"})
    assert bad.status_code == 400 and bad.json()["errors"][0]["field"] == "query.f"


async def test_each_page_holds_its_document_and_every_link(
    client: httpx.AsyncClient, job_url: str
) -> None:
    job_id = job_url.rsplit("/", 1)[-1]
    for path in resources(job_url)[:6]:
        document = (await client.get(path)).json()
        page = parse_page(await client.get(path, params={"f": "html"}))
        missing = [h for h in expected_hrefs(document) if h not in page.hrefs]
        assert not missing, (path, missing)
        text = page.all_text
        if path == "/ogc/":
            assert document["title"] in text and document["description"] in text
        if path == "/ogc/conformance":
            assert set(document["conformsTo"]) <= set(page.hrefs)
        if path == "/ogc/processes":
            assert all(p["id"] in text and p["version"] in text for p in document["processes"])
            assert "sync-execute, async-execute, dismiss" in text
        if path == "/ogc/processes/fourbar-grashof":
            inputs = document["inputs"].items()
            assert all(f"{name} {entry['title']}" in text for name, entry in inputs)
            assert all(
                f"{name} {entry['title']}" in text for name, entry in document["outputs"].items()
            )
            assert "sync-execute, async-execute, dismiss" in text
        if path in ("/ogc/jobs", job_url):
            assert job_id in text and "successful" in text
    # The results: the outputs the request chose, each linked where a client fetches it.
    results = (await client.get(f"{job_url}/results")).json()
    assert set(results) == {"classification", "fourbar_motion.svg"}
    page = parse_page(await client.get(f"{job_url}/results", params={"f": "html"}))
    assert results["fourbar_motion.svg"]["href"] in page.hrefs
    assert f"{job_url}/results/classification" in page.hrefs
    assert "crank-rocker" in page.all_text
    # One output: a value as a table, a file inline.
    output = parse_page(await client.get(f"{job_url}/results/classification?f=html"))
    assert "crank-rocker" in output.all_text
    svg = await client.get(f"{job_url}/results/fourbar_motion.svg", headers={"Accept": BROWSER})
    assert parse_page(svg).images == [results["fourbar_motion.svg"]["href"]]


async def test_the_job_list_page_applies_the_ogc_filters(
    client: httpx.AsyncClient, job_url: str
) -> None:
    r = await client.post(EXECUTE, json={"inputs": FOURBAR}, headers={"Prefer": "wait=60"})
    dismissed = r.headers["location"].rsplit("/", 1)[-1]
    assert (await client.delete(r.headers["location"])).json()["status"] == "dismissed"
    kept = job_url.rsplit("/", 1)[-1]

    async def listed(query: str) -> tuple[Page, str]:
        r = await client.get(f"/ogc/jobs?{query}", headers={"Accept": BROWSER})
        return parse_page(r), r.text

    page, html = await listed("status=dismissed&processID=fourbar-grashof")
    assert dismissed in page.all_text and kept not in page.all_text
    assert '<option value="dismissed" selected>' in html
    assert '<option value="fourbar-grashof" selected>' in html
    page, html = await listed("status=successful&status=dismissed")
    assert dismissed in page.all_text and kept in page.all_text
    page, html = await listed("datetime=2100-01-01T00:00:00Z/..&minDuration=0")
    assert "No jobs match these filters" in page.all_text
    # Filters the form has no field for are kept (hidden) and shown.
    assert '<input type="hidden" name="datetime" value="2100-01-01T00:00:00Z/..">' in html
    assert "datetime=2100-01-01T00:00:00Z/.." in page.all_text
    # One job a page: the pager's next page is a page too, and holds the other job.
    page, html = await listed("limit=1")
    assert dismissed in page.all_text and kept not in page.all_text  # newest first
    (following,) = [h for h in page.hrefs if "cursor=" in h and h.endswith("f=html")]
    second = parse_page(await client.get(following))
    assert kept in second.all_text and dismissed not in second.all_text
    assert f"{BASE}/ogc/jobs?limit=1&f=html" in second.hrefs  # the first page


async def test_pages_of_a_page_of_processes(client: httpx.AsyncClient) -> None:
    listing = (await client.get("/ogc/processes")).json()["processes"]
    r = await client.get("/ogc/processes", params={"limit": 4, "offset": 4, "f": "html"})
    page = parse_page(r)
    shown = [p["id"] for p in listing if f"{BASE}/ogc/processes/{p['id']}?f=html" in page.hrefs]
    assert shown == [p["id"] for p in listing[4:8]]
    assert f"{BASE}/ogc/processes?limit=4&offset=8&f=html" in page.hrefs


async def test_problems_under_ogc_are_pages(client: httpx.AsyncClient) -> None:
    cases = [
        ("/ogc/jobs/no-such-job", 404, "no-such-job"),
        ("/ogc/processes/no-such-process", 404, "no-such-process"),
        ("/ogc/jobs?status=bogus", 400, "query.status"),
        ("/ogc/jobs/no-such-job/results/x", 404, "no-such-job"),
    ]
    for path, status, shown in cases:
        r = await client.get(path, headers={"Accept": BROWSER})
        assert r.status_code == status and r.headers["content-type"].startswith("text/html")
        assert shown in r.text, path
    r = await client.post(SLOW, json={"inputs": SLOW_INPUTS}, headers={"Prefer": "respond-async"})
    pending = r.headers["location"]
    try:
        r = await client.get(f"{pending}/results", params={"f": "html"})
        assert r.status_code == 404 and r.headers["content-type"].startswith("text/html")
        assert "result-not-ready" in r.text
    finally:
        await client.delete(pending)
