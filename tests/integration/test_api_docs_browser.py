"""/docs and /redoc in headless Chromium against a real `dexlab serve`, offline.

Every request the pages make to a host other than 127.0.0.1 is recorded and aborted
(tests/browser.py), so a page that needed a CDN would fail here.  Screenshots go to
:func:`tests.browser.screenshot_dir` as evidence.
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any
from urllib.parse import quote, urlsplit

import pytest

from service.routes.process_operations import family_tag, operation_id
from tests.browser import open_page
from tests.integration.servers import Deployment, deployment
from worker.registry import default_registry

REGISTRY = default_registry()

pytestmark = pytest.mark.integration

#: What Swagger UI itself logs for a deep link whose operationId holds `_` (FastAPI's
#: operation IDs all do); the link still opens the operation.
DEEP_LINK_NOTICE = "Deprecated: escaping deep link whitespace with `_`"
TIMEOUT_MS = 30_000


@pytest.fixture(scope="module")
def api(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    with deployment("embedded", tmp_path_factory.mktemp("docs"), workers=0) as dep:
        yield dep


def served_from(api: Deployment, urls: list[str]) -> None:
    host = urlsplit(api.base_url).netloc
    assert urls and all(urlsplit(u).netloc == host for u in urls), urls


def test_swagger_ui_lists_every_process_offline(api: Deployment, browser: Any, shots: Path) -> None:
    document = api.client.get("/openapi.json").json()
    with open_page(browser) as offline:
        page = offline.page
        loaded: list[str] = []
        page.on("requestfinished", lambda request: loaded.append(request.url))
        page.goto(f"{api.base_url}/docs")
        page.wait_for_selector(".opblock-summary-path", timeout=TIMEOUT_MS)
        page.screenshot(path=str(shots / "docs.png"), full_page=True)

        tags = page.eval_on_selector_all("h3.opblock-tag", "els => els.map(e => e.dataset.tag)")
        assert tags == [t["name"] for t in document["tags"] if t["name"] in tags]
        for definition in default_registry():
            section = page.locator(".opblock-tag-section").filter(
                has=page.locator(f'h3.opblock-tag[data-tag="{family_tag(REGISTRY, definition)}"]')
            )
            path = section.locator(
                f'.opblock-summary-path[data-path="/v1/processes/{definition.id}/execution"]'
            )
            assert path.count() == 1, definition.id
        icon_width = page.evaluate(
            """() => new Promise(resolve => {
                const image = new Image();
                image.onload = () => resolve(image.naturalWidth);
                image.onerror = () => resolve(0);
                image.src = document.querySelector("link[rel~='icon']").href;
            })"""
        )
        assert icon_width > 0
        assert offline.external == []
        assert offline.console_errors == []
        served_from(api, loaded)


def test_try_it_out_starts_from_the_first_worked_example(
    api: Deployment, browser: Any, shots: Path
) -> None:
    """A deep link opens the operation; its example list holds the process's worked
    examples, and "Try it out" fills the body with the first."""
    definition = next(d for d in default_registry() if len(d.examples) > 1)
    described = api.client.get(f"/v1/processes/{definition.id}").json()["examples"]
    tag = family_tag(REGISTRY, definition)
    with open_page(browser) as offline:
        page = offline.page
        page.goto(f"{api.base_url}/docs#/{quote(tag)}/{operation_id(definition.id)}")
        block = page.locator(f'.opblock:has([data-path="/v1/processes/{definition.id}/execution"])')
        block.locator(".opblock-body").wait_for(timeout=TIMEOUT_MS)
        options = block.locator(".examples-select select option").all_inner_texts()
        assert len(options) == len(definition.examples)
        assert all(ex.title in text for ex, text in zip(definition.examples, options, strict=True))
        block.locator("button.try-out__btn").click()
        body = block.locator("textarea.body-param__text")
        body.wait_for(timeout=TIMEOUT_MS)
        assert json.loads(body.input_value()) == {"inputs": described[0]["inputs"]}
        page.screenshot(path=str(shots / "docs-try-it-out.png"))
        assert offline.external == []
        assert [e for e in offline.console_errors if DEEP_LINK_NOTICE not in e] == []


def test_redoc_renders_offline_with_local_fonts(api: Deployment, browser: Any, shots: Path) -> None:
    with open_page(browser) as offline:
        page = offline.page
        fonts: list[str] = []
        page.on(
            "requestfinished",
            lambda request: fonts.append(request.url) if request.resource_type == "font" else None,
        )
        page.goto(f"{api.base_url}/redoc")
        page.wait_for_selector("h1", timeout=TIMEOUT_MS)
        assert page.inner_text("h1").startswith("dexlab")
        menu = page.locator("[role=menu]").first.inner_text()
        for definition in default_registry():
            assert family_tag(REGISTRY, definition) in menu, definition.id
            summary = page.get_by_text(f"Run {definition.id}: {definition.title}", exact=True)
            assert summary.count() >= 1, definition.id
        page.evaluate("() => document.fonts.ready.then(() => true)")
        families = page.evaluate(
            "Array.from(document.fonts).filter(f => f.status === 'loaded').map(f => f.family)"
        )
        assert {"Roboto", "Montserrat"} <= {f.strip("'\"") for f in families}, families
        page.screenshot(path=str(shots / "redoc.png"))
        assert offline.external == []
        assert offline.console_errors == []
        served_from(api, fonts)
