"""The API docs pages and their vendored assets, over the app's ASGI interface.

The pages name no external URL, every asset they load (and every font the font CSS
loads) answers 200 with its media type, and the pages follow a proxy's root path.
What the browser then does is tests/integration/test_api_docs_browser.py.
"""

from __future__ import annotations

import re
from collections.abc import AsyncIterator
from html.parser import HTMLParser
from pathlib import Path

import httpx
import pytest

from service.api_docs import DOCS_ASSETS, REDOC_ASSETS, VENDOR_DIR, VENDOR_URL
from service.app import create_app
from service.config import Settings

pytestmark = pytest.mark.anyio

EXTERNAL_URL = re.compile(r"https?://", re.IGNORECASE)
CSS_URL = re.compile(r"url\(\s*['\"]?([^'\")]+)")
MEDIA_TYPES = {
    ".js": "text/javascript",
    ".css": "text/css",
    ".woff2": "font/woff2",
    ".png": "image/png",
}


class AssetLinks(HTMLParser):
    """The ``src`` and ``href`` of every element of a page."""

    def __init__(self) -> None:
        super().__init__()
        self.urls: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.urls += [value for name, value in attrs if name in ("src", "href") and value]


def asset_links(html: str) -> list[str]:
    parser = AssetLinks()
    parser.feed(html)
    return parser.urls


async def client_for(tmp_path: Path, root_path: str = "") -> AsyncIterator[httpx.AsyncClient]:
    app = create_app(Settings(data_dir=tmp_path, workers=0))
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app, root_path=root_path)
        async with httpx.AsyncClient(transport=transport, base_url="http://dexlab.test") as c:
            yield c


@pytest.fixture
async def client(tmp_path: Path) -> AsyncIterator[httpx.AsyncClient]:
    async for c in client_for(tmp_path):
        yield c


async def check_asset(client: httpx.AsyncClient, url: str) -> httpx.Response:
    r = await client.get(url)
    assert r.status_code == 200, (url, r.status_code)
    media = MEDIA_TYPES[Path(url).suffix]
    assert r.headers["content-type"].split(";")[0] == media, (url, r.headers["content-type"])
    assert r.headers["x-content-type-options"] == "nosniff"
    return r


@pytest.mark.parametrize(("page", "assets"), [("/docs", DOCS_ASSETS), ("/redoc", REDOC_ASSETS)])
async def test_page_names_no_external_url_and_its_assets_answer(
    client: httpx.AsyncClient, page: str, assets: tuple[str, ...]
) -> None:
    r = await client.get(page)
    assert r.status_code == 200
    assert r.headers["content-type"] == "text/html; charset=utf-8"
    assert not EXTERNAL_URL.search(r.text), EXTERNAL_URL.findall(r.text)
    links = asset_links(r.text)
    assert sorted(links) == sorted(f"{VENDOR_URL}/{a}" for a in assets)
    for url in links:
        body = await check_asset(client, url)
        if url.endswith(".css"):
            for ref in CSS_URL.findall(body.text):
                assert ref.startswith("data:") or not EXTERNAL_URL.match(ref), (url, ref)


async def test_fonts_are_local_woff2(client: httpx.AsyncClient) -> None:
    css = (await check_asset(client, f"{VENDOR_URL}/fonts/fonts.css")).text
    fonts = CSS_URL.findall(css)
    families = set(re.findall(r"font-family: '([^']+)'", css))
    assert families == {"Roboto", "Montserrat"}
    # ReDoc's default theme: Roboto (text) and Montserrat (headings), light to bold.
    for family in families:
        weights = {int(w) for w in re.findall(rf"'{family}';[^}}]*?font-weight: (\d+)", css)}
        assert weights == {300, 400, 700}, (family, weights)
    assert len(fonts) == css.count("@font-face") >= 6
    for ref in fonts:
        assert not EXTERNAL_URL.match(ref) and ref.endswith(".woff2"), ref
        body = await check_asset(client, f"{VENDOR_URL}/fonts/{ref}")
        assert body.content.startswith(b"wOF2"), ref


async def test_swagger_ui_configuration(client: httpx.AsyncClient) -> None:
    html = (await client.get("/docs")).text
    assert "url: '/openapi.json'" in html
    assert '"deepLinking": true' in html and '"validatorUrl": null' in html
    # Tags and operations keep the document's order (each family under its own tag).
    assert "tagsSorter" not in html and "operationsSorter" not in html
    assert "window.location.origin + '/docs/oauth2-redirect'" in html
    redirect = await client.get("/docs/oauth2-redirect")
    assert redirect.status_code == 200 and "swaggerUIRedirectOauth2" in redirect.text
    assert not EXTERNAL_URL.search(redirect.text)


async def test_favicon(client: httpx.AsyncClient) -> None:
    r = await client.get("/favicon.ico")
    assert r.status_code == 200 and r.headers["content-type"] == "image/png"
    assert r.content.startswith(b"\x89PNG\r\n\x1a\n")
    assert r.content == (await client.get(f"{VENDOR_URL}/swagger-ui/favicon-32x32.png")).content


async def test_assets_revalidate_by_etag(client: httpx.AsyncClient) -> None:
    url = f"{VENDOR_URL}/redoc/redoc.standalone.js"
    first = await client.get(url)
    assert first.headers["cache-control"] == "no-cache"
    again = await client.get(url, headers={"If-None-Match": first.headers["etag"]})
    assert again.status_code == 304 and again.content == b""


@pytest.mark.parametrize("path", ["/missing.js", "/../api_docs.py", "/%2e%2e/api_docs.py"])
async def test_missing_assets_are_problem_documents(client: httpx.AsyncClient, path: str) -> None:
    r = await client.get(VENDOR_URL + path)
    assert r.status_code == 404
    assert r.headers["content-type"] == "application/problem+json"


async def test_pages_follow_the_proxy_root_path(tmp_path: Path) -> None:
    async for client in client_for(tmp_path, root_path="/dexlab"):
        for page in ("/docs", "/redoc"):
            html = (await client.get(f"/dexlab{page}")).text
            assert "/dexlab/openapi.json" in html
            links = asset_links(html)
            assert links and all(u.startswith(f"/dexlab{VENDOR_URL}/") for u in links), links
            for url in links:
                await check_asset(client, url)


def test_every_vendored_project_keeps_its_licence() -> None:
    for folder in ("swagger-ui", "redoc", "fonts/roboto", "fonts/montserrat"):
        assert (VENDOR_DIR / folder / "LICENSE").stat().st_size > 500, folder
    readme = (VENDOR_DIR / "README.md").read_text()
    for package in ("swagger-ui-dist", "redoc", "@fontsource/roboto", "@fontsource/montserrat"):
        assert f"`{package}`" in readme, package
