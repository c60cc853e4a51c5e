"""``/`` and ``/v1``: the landing document, its links, and its page (ASGI, embedded)."""

from __future__ import annotations

import httpx
import pytest

pytestmark = [pytest.mark.integration, pytest.mark.anyio]

BROWSER = "text/html,application/xhtml+xml,application/xml;q=0.9,*/*;q=0.8"


@pytest.fixture
def backend() -> str:
    """The landing page is the same on every backend."""
    return "embedded"


async def test_root_and_v1_answer_the_same_landing_document(
    asgi_client: httpx.AsyncClient,
) -> None:
    root = await asgi_client.get("/")
    v1 = await asgi_client.get("/v1")
    assert root.status_code == v1.status_code == 200
    assert root.headers["content-type"] == "application/json"
    assert root.json() == v1.json()
    rels = {link["rel"] for link in root.json()["links"]}
    assert {"processes", "jobs", "service-doc", "service-desc", "alternate"} <= rels


async def test_the_service_description_link_names_the_served_openapi_version(
    asgi_client: httpx.AsyncClient,
) -> None:
    links = {link["rel"]: link for link in (await asgi_client.get("/v1")).json()["links"]}
    served = (await asgi_client.get("/openapi.json")).json()["openapi"]
    major_minor = ".".join(served.split(".")[:2])
    assert links["service-desc"]["type"].endswith(f"version={major_minor}")


async def test_every_landing_link_resolves_in_its_media_type(
    asgi_client: httpx.AsyncClient,
) -> None:
    for link in (await asgi_client.get("/")).json()["links"]:
        accept = BROWSER if link["type"] == "text/html" else "application/json"
        answer = await asgi_client.get(link["href"], headers={"Accept": accept})
        assert answer.status_code == 200, link
        expected = "text/html" if link["type"] == "text/html" else "json"
        assert expected in answer.headers["content-type"], link


async def test_a_browser_gets_the_landing_page_at_both_paths(
    asgi_client: httpx.AsyncClient,
) -> None:
    for path in ("/", "/v1", "/v1?f=html"):
        page = await asgi_client.get(path, headers={"Accept": BROWSER})
        assert page.status_code == 200
        assert page.headers["content-type"].startswith("text/html")
        assert 'href="/v1/processes' in page.text and 'href="/v1/jobs' in page.text
