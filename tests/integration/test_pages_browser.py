"""The pages in headless Chromium against a real `dexlab serve`, offline: a newcomer
starts at `/`, finds a process, runs the paper's example, watches it and reads the plot.

Every request to a host other than 127.0.0.1 is recorded and aborted
(tests/browser.py); screenshots go to :func:`tests.browser.screenshot_dir`.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import pytest

from tests.browser import LOCAL_HOSTS, open_page
from tests.integration.servers import Deployment, deployment
from worker.registry import default_registry

pytestmark = pytest.mark.integration

TIMEOUT_MS = 60_000
#: A worked example with plots that runs for a few seconds: long enough to be watched.
PROCESS = "planar2dof-conditioning-map"


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    with deployment("embedded", tmp_path_factory.mktemp("pages"), workers=2) as dep:
        yield dep


@pytest.fixture(scope="module")
def job_url(server: Deployment, browser: Any, shots: Path) -> str:
    """The URL of the job the newcomer's scenario ran (set by the first test)."""
    return _run_the_example(server, browser, shots)


def _run_the_example(server: Deployment, browser: Any, shots: Path) -> str:
    definition = default_registry().get(PROCESS)
    assert definition is not None
    with open_page(browser, width=1280, height=900) as offline:
        page = offline.page
        requests: list[str] = []
        page.on("request", lambda request: requests.append(request.url))
        page.goto(f"{server.base_url}/")
        page.get_by_role("link", name=definition.title).first.click()
        page.wait_for_url(f"**/v1/processes/{PROCESS}")
        page.screenshot(path=str(shots / "process-page.png"), full_page=True)
        example = page.locator("#example-0")
        assert definition.examples[0].title in example.inner_text()
        example.get_by_role("button", name="Run this example").click()
        page.wait_for_url("**/v1/jobs/*", timeout=TIMEOUT_MS)
        job_url = page.url
        # The progress bar follows the job live (Server-Sent Events), and the page
        # reloads itself once the job has ended; the test only waits.
        page.wait_for_selector("#job-progress[value='100']", timeout=TIMEOUT_MS)
        page.wait_for_selector("figure.plot img", timeout=TIMEOUT_MS)
        page.wait_for_load_state("networkidle")
        assert any(urlsplit(u).path.endswith("/events") for u in requests), requests
        assert page.locator("#job-status-value .badge").inner_text() == "successful"
        widths = page.locator("figure.plot img").evaluate_all(
            "images => images.map(image => image.complete ? image.naturalWidth : 0)"
        )
        assert widths and all(w > 0 for w in widths), widths
        captions = page.locator("figure.plot figcaption").all_inner_texts()
        assert all(captions), captions
        assert page.locator("section.job-status dd").first.inner_text() in job_url
        page.screenshot(path=str(shots / "job-page.png"), full_page=True)

        page.get_by_role("navigation", name="Main").get_by_role("link", name="Jobs").click()
        page.wait_for_url("**/v1/jobs")
        job_id = urlsplit(job_url).path.rsplit("/", 1)[-1]
        assert page.locator(f'a[href="/v1/jobs/{job_id}"]').count() == 1
        page.screenshot(path=str(shots / "jobs-page.png"), full_page=True)
        assert not offline.external, offline.external
        assert not offline.console_errors, offline.console_errors
    return job_url


def test_a_newcomer_runs_an_example_and_reads_the_plots(job_url: str, server: Deployment) -> None:
    status = server.client.get(urlsplit(job_url).path).json()
    assert status["status"] == "successful" and status["processID"] == PROCESS


@contextmanager
def no_script_page(browser: Any, width: int) -> Iterator[tuple[Any, list[str]]]:
    """A page with JavaScript off; requests leaving 127.0.0.1 are recorded and aborted."""
    context = browser.new_context(
        viewport={"width": width, "height": 800}, java_script_enabled=False
    )
    external: list[str] = []

    def route(route: Any) -> None:
        if (urlsplit(route.request.url).hostname or "") in LOCAL_HOSTS:
            route.continue_()
        else:
            external.append(route.request.url)
            route.abort()

    page = context.new_page()
    page.route("**/*", route)
    try:
        yield page, external
    finally:
        context.close()


def test_pages_fit_a_phone_and_read_without_javascript(
    job_url: str, server: Deployment, browser: Any, shots: Path
) -> None:
    paths = [
        "/",
        "/v1/processes",
        f"/v1/processes/{PROCESS}",
        "/v1/jobs",
        urlsplit(job_url).path,
        "/methods",
        "/methods/planar-parallel",
    ]
    with open_page(browser, width=375, height=800) as offline:
        page = offline.page
        for path in paths:
            page.goto(server.base_url + path)
            page.wait_for_load_state("networkidle")
            overflow = page.evaluate(
                "document.documentElement.scrollWidth - document.documentElement.clientWidth"
            )
            assert overflow <= 0, (path, overflow)
        page.goto(job_url)
        page.screenshot(path=str(shots / "job-page-phone.png"), full_page=True)
        assert not offline.external and not offline.console_errors, offline
    with no_script_page(browser, 1280) as (page, external):
        page.goto(server.base_url + f"/v1/processes/{PROCESS}")
        assert page.locator("table.inputs tbody tr").count() >= 10
        assert page.get_by_role("button", name="Run this example").count() >= 1
        page.goto(job_url)
        assert page.locator("#job-progress").get_attribute("value") == "100"
        assert page.locator("figure.plot img").count() >= 1
        assert page.locator("section[aria-labelledby='result-title'] table").count() >= 1
        page.goto(server.base_url + "/methods/planar-parallel")
        assert page.locator("article.prose math").count() > 0
        page.screenshot(path=str(shots / "method-page-no-js.png"))
        assert not external, external


def test_the_ogc_pages_lead_to_working_pages(
    job_url: str, server: Deployment, browser: Any, shots: Path
) -> None:
    """/ogc/ as a page: every link of it answers; the OGC job list leads to the job's
    page with its plot; the pages fit a phone; nothing leaves 127.0.0.1."""
    job_id = urlsplit(job_url).path.rsplit("/", 1)[-1]
    with open_page(browser, width=1280, height=900) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/ogc/?f=html")
        assert page.locator("h1").inner_text() == server.client.get("/ogc/").json()["title"]
        page.screenshot(path=str(shots / "ogc-landing.png"), full_page=True)
        hrefs = page.locator("main a").evaluate_all("anchors => anchors.map(a => a.href)")
        assert len(hrefs) >= 8, hrefs
        for href in hrefs:
            response = page.goto(href)
            assert response is not None and response.ok, href
        page.goto(f"{server.base_url}/ogc/jobs?f=html")
        page.locator(f'a[href$="/ogc/jobs/{job_id}?f=html"]').first.click()
        page.wait_for_selector("figure.plot img", timeout=TIMEOUT_MS)
        assert page.locator("section[aria-labelledby='links-title'] a").count() >= 5
        page.screenshot(path=str(shots / "ogc-job-page.png"), full_page=True)
        assert not offline.external and not offline.console_errors, offline
    with open_page(browser, width=375, height=800) as offline:
        for path in (
            "/ogc/",
            "/ogc/conformance",
            "/ogc/processes",
            f"/ogc/processes/{PROCESS}",
            "/ogc/jobs",
            f"/ogc/jobs/{job_id}",
            f"/ogc/jobs/{job_id}/results",
        ):
            offline.page.goto(f"{server.base_url}{path}?f=html")
            overflow = offline.page.evaluate(
                "document.documentElement.scrollWidth - document.documentElement.clientWidth"
            )
            assert overflow <= 0, (path, overflow)
        assert not offline.external and not offline.console_errors, offline
