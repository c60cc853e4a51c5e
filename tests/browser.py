"""A real headless browser for page tests: Debian's Chromium driven by Playwright.

Playwright is used through ``executable_path`` on the system Chromium (never
``playwright install``, which downloads a browser).  Where Chromium is missing the tests
skip with the reason, or fail under ``DEXLAB_REQUIRE_SERVICES`` (CI installs it).

Every page opened through :func:`open_page` records the requests that tried to leave
127.0.0.1 and aborts them, so a test can assert that a page works offline.
"""

from __future__ import annotations

import os
import shutil
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

from tests.services import require_packages, unavailable

#: Flags for a closed network: no background traffic to Google's hosts.
CHROMIUM_ARGS = [
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-default-apps",
    "--disable-extensions",
]

LOCAL_HOSTS = frozenset({"127.0.0.1", "localhost", "::1", "[::1]"})


def chromium_path() -> str:
    """The system Chromium, or a skip (a failure in CI) naming what is missing."""
    require_packages("playwright")
    path = os.environ.get("DEXLAB_CHROMIUM") or shutil.which("chromium") or ""
    if not path or not Path(path).exists():
        unavailable("needs Debian's chromium (apt-get install chromium)")
    return path


@contextmanager
def chromium() -> Iterator[Any]:
    """A headless Chromium browser (Playwright's sync API)."""
    from playwright.sync_api import sync_playwright

    executable = chromium_path()
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(
            executable_path=executable, args=CHROMIUM_ARGS, headless=True
        )
        try:
            yield browser
        finally:
            browser.close()


@dataclass
class OfflinePage:
    """A page whose requests to hosts other than 127.0.0.1 are recorded and aborted."""

    page: Any
    external: list[str] = field(default_factory=list)
    console_errors: list[str] = field(default_factory=list)


@contextmanager
def open_page(
    browser: Any, *, width: int = 1280, height: int = 900, javascript: bool = True
) -> Iterator[OfflinePage]:
    """A fresh browser context and page at ``width`` x ``height`` CSS pixels (with
    JavaScript off if ``javascript`` is false)."""
    context = browser.new_context(
        viewport={"width": width, "height": height}, java_script_enabled=javascript
    )
    page = context.new_page()
    offline = OfflinePage(page)

    def route(route: Any) -> None:
        host = urlsplit(route.request.url).hostname or ""
        scheme = urlsplit(route.request.url).scheme
        if scheme in ("data", "blob") or host in LOCAL_HOSTS:
            route.continue_()
        else:
            offline.external.append(route.request.url)
            route.abort()

    page.route("**/*", route)
    page.on(
        "console",
        lambda msg: offline.console_errors.append(msg.text) if msg.type == "error" else None,
    )
    try:
        yield offline
    finally:
        context.close()


def screenshot_dir(tmp_root: Path) -> Path:
    """Where screenshots go as CI evidence: ``DEXLAB_SCREENSHOT_DIR`` or a temp dir."""
    target = Path(os.environ.get("DEXLAB_SCREENSHOT_DIR") or tmp_root / "screenshots")
    target.mkdir(parents=True, exist_ok=True)
    return target
