"""The live explorer in headless Chromium against a real `dexlab serve`: a slider
change redraws the heat map and the indices with no Content-Security-Policy
violation and nothing loaded from outside; "Run as a job" and "Add to comparison"
submit the current design; without JavaScript the page says what it needs."""

from __future__ import annotations

import json
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.browser import open_page
from tests.integration.servers import Deployment, deployment

pytestmark = pytest.mark.integration

TIMEOUT_MS = 60_000
#: Records every CSP violation of the page (before any of its scripts run).
WATCH_CSP = """
window.cspViolations = [];
document.addEventListener("securitypolicyviolation", function (e) {
  window.cspViolations.push(e.violatedDirective + " " + e.blockedURI + " " + e.sourceFile +
                            ":" + e.lineNumber);
});
"""


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    with deployment("embedded", tmp_path_factory.mktemp("explorer"), workers=1) as dep:
        yield dep


def drawn(page: Any, change: int) -> None:
    page.wait_for_selector(f"#explorer[data-drawn='{change}']", state="attached",
                           timeout=TIMEOUT_MS)  # fmt: skip


def index_text(page: Any, name: str) -> str:
    return str(page.locator(f"#explorer-indices td[data-name='{name}']").inner_text())


def finished_result(server: Deployment, job_id: str, timeout: float = 120) -> dict[str, Any]:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        status = server.client.get(f"/v1/jobs/{job_id}").json()["status"]
        if status == "successful":
            result: dict[str, Any] = server.client.get(f"/v1/jobs/{job_id}/results").json()
            return result
        assert status in ("accepted", "running"), status
        time.sleep(0.2)
    raise AssertionError(f"job {job_id} did not finish in {timeout} s")


def slide(page: Any, path: str, value: float) -> None:
    """Move a slider as a user does: set its value, fire its input event."""
    page.evaluate(
        """([path, value]) => {
          const range = document.querySelector(`input[type=range][data-path='${path}']`);
          range.value = String(value);
          range.dispatchEvent(new Event("input", {bubbles: true}));
        }""",
        [path, value],
    )


@pytest.mark.parametrize(
    ("process_id", "path", "value", "index"),
    [
        ("planar3r-dexterity-map", "links.2", 12.0, "d_z_mean_reachable"),
        ("spm-conditioning-map", "alpha1_deg", 70.0, "gci"),
        ("planar2dof-conditioning-map", "l2", 2.0, "mean_inverse_condition"),
    ],
)
def test_the_explorer_redraws_after_a_slider_change_within_the_csp(
    server: Deployment, browser: Any, shots: Path, process_id: str, path: str, value: float,
    index: str,
) -> None:  # fmt: skip
    with open_page(browser) as offline:
        page = offline.page
        page.add_init_script(WATCH_CSP)
        page.goto(f"{server.base_url}/v1/processes/{process_id}")
        page.locator("#explorer-link").click()
        page.wait_for_url(f"**/pages/processes/{process_id}/explore")
        drawn(page, 1)
        before = index_text(page, index)
        assert page.locator(".explorer-chart .main-svg").count() >= 1  # Plotly drew
        slide(page, path, value)
        drawn(page, 2)
        assert page.locator(f"input[type=number][data-path='{path}']").input_value() == f"{value:g}"
        assert index_text(page, index) != before
        assert page.locator("#explorer").get_attribute("data-state") == "drawn"
        assert page.locator(".explorer-chart .modebar-btn").count() > 0  # zoom, export
        page.screenshot(path=str(shots / f"explorer-{process_id}.png"), full_page=True)
        assert page.evaluate("window.cspViolations") == []
        assert offline.external == []
        assert [e for e in offline.console_errors if "favicon" not in e] == []


def test_a_refused_design_says_why(server: Deployment, browser: Any) -> None:
    with open_page(browser) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/pages/processes/planar2dof-conditioning-map/explore")
        drawn(page, 1)
        page.locator("input[type=number][data-path='l2']").fill("0.5")  # isotropic: l2 >= l1
        drawn(page, 2)
        assert page.locator("#explorer").get_attribute("data-state") == "refused"
        assert "l2" in page.locator("#explorer-status").inner_text()


def test_run_as_a_job_and_add_to_comparison(server: Deployment, browser: Any) -> None:
    with open_page(browser) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/pages/processes/planar3r-dexterity-map/explore")
        drawn(page, 1)
        page.get_by_role("button", name="Add to comparison").click()
        page.locator("#explorer-status", has_text="Added job").wait_for(timeout=TIMEOUT_MS)
        slide(page, "links.0", 16.0)
        drawn(page, 2)
        page.get_by_role("button", name="Add to comparison").click()
        link = page.get_by_role("link", name="Compare 2 designs")
        link.wait_for(timeout=TIMEOUT_MS)
        href = link.get_attribute("href")
        assert href is not None and href.count("jobs=") == 2
        slide(page, "links.1", 13.0)
        drawn(page, 3)
        page.get_by_role("button", name="Run as a job").click()
        page.wait_for_url("**/v1/jobs/*", timeout=TIMEOUT_MS)
        job_id = page.url.rsplit("/", 1)[-1]
        document = finished_result(server, job_id)
        assert document["result"]["links"] == [16.0, 13.0, 8.0]
        assert "heatmap.png" in json.dumps(document["artifacts"])  # a job draws its plots
        page.goto(f"{server.base_url}{href}")
        page.wait_for_url("**/pages/compare?jobs=*")
        page.locator("h1", has_text="Compare 2 jobs").wait_for(timeout=TIMEOUT_MS)


def test_without_javascript_the_page_says_the_explorer_needs_it(
    server: Deployment, browser: Any
) -> None:
    with open_page(browser, javascript=False) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/pages/processes/spm-conditioning-map/explore")
        note = page.locator("#explorer-nojs")
        assert note.is_visible()
        assert "needs JavaScript" in note.inner_text()
        note.get_by_role("link").click()
        page.wait_for_url("**/v1/processes/spm-conditioning-map#examples")


@pytest.mark.parametrize("javascript", [True, False], ids=["js", "no-js"])
def test_a_map_job_page_draws_its_own_data_as_a_heat_map(
    server: Deployment, browser: Any, javascript: bool
) -> None:
    inputs = {"links": [15, 14, 8], "grid": {"points_per_axis": 41}}
    r = server.client.post("/v1/processes/planar3r-dexterity-map/execution",
                           json={"inputs": inputs})  # fmt: skip
    assert r.status_code == 201, r.text
    job_id = r.json()["jobID"]
    finished_result(server, job_id)
    with open_page(browser, javascript=javascript) as offline:
        page = offline.page
        page.add_init_script(WATCH_CSP)
        page.goto(f"{server.base_url}/v1/jobs/{job_id}")
        assert page.locator("figure.plot img").count() >= 1  # the PNGs stay
        if not javascript:
            assert not page.locator("#job-chart").is_visible()
            return
        page.wait_for_selector("#job-chart[data-drawn='1']", state="attached",
                               timeout=TIMEOUT_MS)  # fmt: skip
        assert page.locator("#job-chart .main-svg").count() >= 1
        page.locator("#job-chart .nsewdrag").first.hover()
        hover = page.locator("#job-chart .hovertext")
        hover.first.wait_for(timeout=TIMEOUT_MS)
        assert "units" in (hover.first.text_content() or "")  # x and y with their unit
        assert page.evaluate("window.cspViolations") == []
        assert offline.external == []


def test_at_a_phone_width_the_explorer_does_not_scroll_sideways(
    server: Deployment, browser: Any
) -> None:
    with open_page(browser, width=390, height=800) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/pages/processes/spm-conditioning-map/explore")
        drawn(page, 1)
        width, viewport = page.evaluate("[document.documentElement.scrollWidth, innerWidth]")
        assert width <= viewport


#: 10 x 10 designs of the 3R arm, two objectives: a small study for its scatter.
SMALL_STUDY: dict[str, Any] = {
    "process": "planar3r-dexterity-map",
    "fixed": {"links": [15, 14, 8], "task_points": [[14, 14]], "grid": {"points_per_axis": 5}},
    "vary": {"links[0]": [10, 20, 10], "links[2]": [2, 10, 10]},
    "objectives": {"task_points[].d_z|min": "max", "links|sum": "min"},
    "plots": False,
}  # fmt: skip


def test_a_study_page_draws_its_objective_scatter_within_the_csp(
    server: Deployment, browser: Any
) -> None:
    r = server.client.post("/v1/processes/design-study/execution", json={"inputs": SMALL_STUDY})
    assert r.status_code == 201, r.text
    job_id = r.json()["jobID"]
    finished_result(server, job_id, timeout=300)
    with open_page(browser) as offline:
        page = offline.page
        page.add_init_script(WATCH_CSP)
        page.goto(f"{server.base_url}/v1/jobs/{job_id}")
        page.locator("#study-scatter .main-svg").first.wait_for(timeout=TIMEOUT_MS)
        assert page.locator("#study-scatter .modebar-btn").count() > 0
        assert page.evaluate("window.cspViolations") == []
        assert offline.external == []
