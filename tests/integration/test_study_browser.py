"""A design study of 10,000 designs explored in headless Chromium against a real
`dexlab serve`: the designs table sorts, filters and pages (fetching
/v1/jobs/{jobID}/designs with JavaScript, by links without), and one design opens as
a job of its own.  Nothing may leave 127.0.0.1 (tests/browser.py)."""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from playwright.sync_api import expect

from tests.browser import open_page
from tests.integration.servers import Deployment, deployment
from tests.integration.test_workflow_browser import TIMEOUT_MS, finished, submit

pytestmark = pytest.mark.integration

#: 100 x 100 designs; links[0] <= 0 (a fifth of them) is refused.
STUDY: dict[str, Any] = {
    "process": "planar3r-dexterity-map",
    "fixed": {"links": [15, 14, 8], "task_points": [[14, 14]], "grid": {"points_per_axis": 5}},
    "vary": {"links[0]": [-5, 20, 100], "links[2]": [2, 10, 100]},
    "objectives": {"task_points[].d_z|min": "max", "links|sum": "min"},
    "plots": False,
}  # fmt: skip


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    with deployment("embedded", tmp_path_factory.mktemp("study"), workers=2) as dep:
        yield dep


@pytest.fixture(scope="module")
def study(server: Deployment) -> str:
    job_id = submit(server, "design-study", STUDY)
    assert finished(server, job_id, timeout=300)["status"] == "successful"
    return job_id


def indices(page: Any) -> list[int]:
    return [int(i) for i in page.locator("#designs-table tbody tr").evaluate_all(
        "rows => rows.map(r => r.dataset.index)")]  # fmt: skip


def first_value(page: Any, column: int) -> float:
    text = page.locator("#designs-table tbody tr").first.locator("td").nth(column).inner_text()
    return float(text)


@pytest.mark.parametrize("javascript", [True, False], ids=["js", "no-js"])
def test_ten_thousand_designs_sort_filter_page_and_open(
    server: Deployment, study: str, browser: Any, shots: Path, javascript: bool
) -> None:
    with open_page(browser, javascript=javascript) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/v1/jobs/{study}")
        if javascript:
            page.wait_for_selector("#designs[data-loaded]")
            page.wait_for_selector("#study-scatter[data-drawn]")  # Plotly, under the CSP
            page.locator("#designs").screenshot(path=str(shots / "study-explorer.png"))
        assert "10,000 designs" in page.locator("#designs-count").inner_text()
        first = indices(page)
        assert len(first) == 25 and first == sorted(first)
        # sort by the sum of the links, shortest first: the shortest arm leads
        page.locator('#designs-table thead a[data-sort="links_sum"]').click()
        expect(page.locator('th[aria-sort] a[data-sort="links_sum"]')).to_have_count(1)
        assert first_value(page, 3) == pytest.approx(-5 + 20 * 25 / 99 + 14 + 2, abs=1e-3)
        # the infeasible designs only
        page.locator("#filter-feasible").select_option("false")
        if not javascript:
            page.get_by_role("button", name="Filter").click()
        expect(page.locator("#designs-count")).to_contain_text("2,000 of 10,000")
        assert "refused" in page.locator("#designs-table tbody tr").first.inner_text()
        # the next page
        shown = indices(page)
        page.locator("#designs-next").click()
        expect(page.locator(f'#designs-table tbody tr[data-index="{shown[0]}"]')).to_have_count(0)
        assert not set(indices(page)) & set(shown)
        page.screenshot(path=str(shots / f"study-explorer-{'js' if javascript else 'no-js'}.png"))
        # back to every design; open the first one as a job
        page.locator("#filter-feasible").select_option("true")
        if not javascript:
            page.get_by_role("button", name="Filter").click()
        expect(page.locator("#designs-count")).to_contain_text("8,000 of 10,000")
        design = indices(page)[0]
        page.locator("#designs-table tbody tr").first.get_by_role(
            "button", name="Open as a job"
        ).click()
        page.wait_for_url(re.compile(r".*/v1/jobs/[0-9a-f-]+$"), timeout=TIMEOUT_MS)
        job_id = page.url.rsplit("/", 1)[-1]
        assert job_id != study
        done = finished(server, job_id)
        assert done["status"] == "successful" and done["processID"] == "planar3r-dexterity-map"
        inputs = server.client.get(f"/v1/jobs/{study}/designs",
                                   params={"range": f"index:{design}:{design}"}).json()  # fmt: skip
        assert inputs["designs"][0]["index"] == design
