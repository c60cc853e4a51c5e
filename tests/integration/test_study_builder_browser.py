"""The study builder in headless Chromium against a real `dexlab serve`: a designer
builds a three-design study of the SPM conditioning map step by step (with JavaScript,
the step selects submit themselves; without it, each step's button does), runs it and
sees it succeed on its job page.  Nothing may leave 127.0.0.1 (tests/browser.py)."""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.browser import open_page
from tests.integration.servers import Deployment, deployment
from tests.integration.test_workflow_browser import finished

pytestmark = pytest.mark.integration

TIMEOUT_MS = 60_000
OBJECTIVE = "indices.rms_inverse_condition"


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    with deployment("embedded", tmp_path_factory.mktemp("builder"), workers=2) as dep:
        yield dep


def choose(page: Any, select: str, value: str, button: str, javascript: bool) -> None:
    """Pick ``value`` in a step's select; the page comes back with the next step."""
    with page.expect_navigation(timeout=TIMEOUT_MS):
        page.select_option(select, value)
        if not javascript:
            page.get_by_role("button", name=button).click()


@pytest.mark.parametrize("javascript", [True, False], ids=["js", "no-js"])
def test_a_designer_builds_and_runs_a_study_without_writing_json(
    server: Deployment, browser: Any, shots: Path, javascript: bool
) -> None:
    with open_page(browser, javascript=javascript) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/v1/processes/design-study")
        assert page.get_by_role("button", name="Choose this process").is_visible() != javascript
        choose(page, "#builder-process", "spm-conditioning-map", "Choose this process",
               javascript)  # fmt: skip
        assert "process=spm-conditioning-map" in page.url
        choose(page, "#builder-example", "0", "Start from this example", javascript)
        page.check('input[name="vary.alpha1_deg"]')
        page.fill('input[name="from.alpha1_deg"]', "55")
        page.fill('input[name="to.alpha1_deg"]', "65")
        page.fill('input[name="count.alpha1_deg"]', "3")
        with page.expect_navigation(timeout=TIMEOUT_MS):
            page.get_by_role("button", name="Next: the objectives").click()
        summary = page.locator("#builder-summary").inner_text()
        assert "alpha1_deg from 55 to 65 (3 values) deg" in summary
        page.check(f'input[name="objective.{OBJECTIVE}"]')
        page.select_option(f'select[name="goal.{OBJECTIVE}"]', "max")
        page.screenshot(path=str(shots / f"study-builder-{'js' if javascript else 'no-js'}.png"),
                        full_page=True)  # fmt: skip
        page.get_by_role("button", name="Run the study").click()
        page.wait_for_url(re.compile(r".*/v1/jobs/[0-9a-f-]+$"), timeout=TIMEOUT_MS)
        job_id = page.url.rsplit("/", 1)[-1]
        assert finished(server, job_id)["status"] == "successful"
        page.goto(f"{server.base_url}/v1/jobs/{job_id}")
        assert page.locator(".status-successful").first.is_visible()
        status = server.client.get(f"/v1/jobs/{job_id}").json()
        assert status["processID"] == "design-study"
        assert offline.external == []
        assert offline.console_errors == []


def test_the_builder_fits_a_phone(server: Deployment, browser: Any) -> None:
    """At 390 px every step shows without the page scrolling sideways (the tables scroll
    in their own box)."""
    query = ("process=planar3r-dexterity-map&example=1&vary.links%5B0%5D=on"
             "&step=objectives")  # fmt: skip
    with open_page(browser, width=390, height=800) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/v1/processes/design-study?{query}")
        assert page.locator("#builder-step-4").is_visible()
        width = page.evaluate("document.documentElement.scrollWidth")
        assert width <= 390, f"the builder is {width} px wide at 390 px"
