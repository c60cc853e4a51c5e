"""The everyday tools of the pages in headless Chromium against a real `dexlab serve`:
"Edit and run again", the question before a dismissal (a dialog with JavaScript, a
page without), the jobs list that keeps itself current, job times, and every page
type at a 390-pixel phone width.  Nothing may leave 127.0.0.1 (tests/browser.py)."""

from __future__ import annotations

import re
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.browser import open_page
from tests.integration.servers import Deployment, deployment
from worker.registry import default_registry

pytestmark = pytest.mark.integration

TIMEOUT_MS = 60_000
PHONE = 390
FOURBAR = {"lengths": [30, 17, 18, 25], "ground": 0, "length_unit": "cm"}
#: A job that runs for many seconds (its progress moves): the 3R map on a fine grid.
LONG_MAP = {
    "links": [15, 14, 8],
    "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
    "grid": {"points_per_axis": 801},
    "orientation_step_deg": 0.5,
    "method": "orientation-sampling",
}


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    with deployment("embedded", tmp_path_factory.mktemp("workflow"), workers=2) as dep:
        yield dep


def submit(server: Deployment, process_id: str, inputs: dict[str, Any]) -> str:
    r = server.client.post(f"/v1/processes/{process_id}/execution", json={"inputs": inputs})
    assert r.status_code == 201, r.text
    return str(r.json()["jobID"])


def finished(server: Deployment, job_id: str, timeout: float = 120) -> dict[str, Any]:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        status: dict[str, Any] = server.client.get(f"/v1/jobs/{job_id}").json()
        if status["status"] in ("successful", "failed", "dismissed"):
            return status
        time.sleep(0.2)
    raise AssertionError(f"job {job_id} did not finish in {timeout} s")


def status_of(server: Deployment, job_id: str) -> str:
    return str(server.client.get(f"/v1/jobs/{job_id}").json()["status"])


@pytest.mark.parametrize("javascript", [True, False], ids=["js", "no-js"])
def test_edit_and_run_again(
    server: Deployment, browser: Any, shots: Path, javascript: bool
) -> None:
    job_id = submit(server, "fourbar-grashof", FOURBAR)
    assert finished(server, job_id)["status"] == "successful"
    with open_page(browser, javascript=javascript) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/v1/jobs/{job_id}")
        page.get_by_role("link", name="Edit and run again").click()
        page.wait_for_url(f"**/pages/jobs/{job_id}/edit")
        box = page.locator("#inputs-0")
        assert '"lengths": [30, 17, 18, 25]' in box.input_value()
        box.fill(box.input_value().replace("[30, 17, 18, 25]", "[30, 17, 18, 40]"))
        page.get_by_role("button", name="Run as a new job").click()
        page.wait_for_url("**/v1/jobs/*", timeout=TIMEOUT_MS)
        new_id = page.url.rsplit("/", 1)[-1]
        assert new_id != job_id
        assert finished(server, new_id)["status"] == "successful"
        page.goto(f"{server.base_url}/v1/jobs/{new_id}")
        ran_with = page.locator("pre.json").last.inner_text()  # after the provenance block
        assert "40.0" in ran_with and "25.0" not in ran_with
        if javascript:
            page.screenshot(path=str(shots / "job-page-rerun.png"), full_page=True)
        assert not offline.external and not offline.console_errors, offline


def test_dismissing_asks_in_a_dialog_with_javascript(server: Deployment, browser: Any) -> None:
    job_id = submit(server, "fourbar-grashof", FOURBAR)
    assert finished(server, job_id)["status"] == "successful"
    with open_page(browser) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/v1/jobs/{job_id}")
        questions: list[str] = []

        def answer(dialog: Any, accept: bool) -> None:
            questions.append(dialog.message)
            dialog.accept() if accept else dialog.dismiss()

        page.once("dialog", lambda d: answer(d, False))
        page.get_by_role("button", name="Delete the results").click()
        page.wait_for_timeout(300)
        assert questions and questions[0].startswith("Delete the results of this job?")
        assert page.url.endswith(f"/v1/jobs/{job_id}") and status_of(server, job_id) == "successful"
        page.once("dialog", lambda d: answer(d, True))
        page.get_by_role("button", name="Delete the results").click()
        page.wait_for_selector("#job-status-value .status-dismissed", timeout=TIMEOUT_MS)
        assert status_of(server, job_id) == "dismissed" and len(questions) == 2
        assert not offline.external and not offline.console_errors, offline


def test_dismissing_asks_on_a_page_without_javascript(
    server: Deployment, browser: Any, shots: Path
) -> None:
    job_id = submit(server, "fourbar-grashof", FOURBAR)
    assert finished(server, job_id)["status"] == "successful"
    with open_page(browser, javascript=False) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/v1/jobs/{job_id}")
        page.get_by_role("button", name="Delete the results").click()
        page.wait_for_url(f"**/pages/jobs/{job_id}/dismiss*")
        assert "deleted for good" in page.locator("#confirm-question").inner_text()
        page.screenshot(path=str(shots / "dismiss-question.png"), full_page=True)
        page.get_by_role("link", name="No, keep it").click()
        page.wait_for_url(f"**/v1/jobs/{job_id}")
        assert status_of(server, job_id) == "successful"
        page.get_by_role("button", name="Delete the results").click()
        page.get_by_role("button", name="Yes: delete the results").click()
        page.wait_for_url(f"**/v1/jobs/{job_id}")
        assert page.locator("#job-status-value .badge").inner_text() == "dismissed"
        assert status_of(server, job_id) == "dismissed"
        assert not offline.external, offline.external


def test_a_running_job_shows_its_times_and_the_list_follows_it(
    server: Deployment, browser: Any, shots: Path
) -> None:
    from playwright.sync_api import expect  # optional: only with the browser tests' extra

    job_id = submit(server, "planar3r-dexterity-map", LONG_MAP)
    try:
        with open_page(browser) as offline:
            page = offline.page
            page.goto(f"{server.base_url}/v1/jobs?processID=planar3r-dexterity-map")
            row = page.locator(f'tr:has(a[href="/v1/jobs/{job_id}"])')
            page.locator("#jobs-listing[data-refreshed-at]").wait_for(timeout=TIMEOUT_MS)
            # the list swaps itself in: the job is running there without a reload
            row.locator(".status-running").wait_for(timeout=TIMEOUT_MS)
            assert row.locator("td.num").last.inner_text().endswith("s")
            page.goto(f"{server.base_url}/v1/jobs/{job_id}")
            expect(page.locator("#job-eta")).to_have_text(re.compile("^about "), timeout=TIMEOUT_MS)
            assert page.locator("#job-duration").inner_text().endswith("so far")
            page.screenshot(path=str(shots / "job-page-running.png"), full_page=True)
            assert not offline.external and not offline.console_errors, offline
    finally:
        server.client.delete(f"/v1/jobs/{job_id}")


def _page_paths(server: Deployment) -> list[str]:
    """One page of every type: landing, lists, every process and method page, a job of
    every process (its first worked example), a dismissed job, the job actions, OGC pages,
    the login and a problem page."""
    registry = default_registry()
    jobs = {d.id: submit(server, d.id, dict(d.examples[0].inputs)) for d in registry}
    dismissed = submit(server, "planar3r-dexterity-map", LONG_MAP)  # its page: a problem box
    server.client.delete(f"/v1/jobs/{dismissed}")
    for job_id in jobs.values():
        assert finished(server, job_id, timeout=600)["status"] == "successful", job_id
    spm = registry.require("spm-conditioning-map").examples[1].inputs
    again = submit(server, "spm-conditioning-map", dict(spm))  # to compare with the first
    assert finished(server, again, timeout=600)["status"] == "successful"
    methods = {d.method_doc for d in registry if d.method_doc}
    study = jobs["design-study"]
    chunks = server.client.get("/v1/jobs", params={"parent": study}).json()["jobs"]
    return [
        "/", "/v1/processes", "/v1/jobs", "/queue", "/methods", "/login", "/v1/jobs/no-such-job",
        *(f"/v1/processes/{p}" for p in jobs),
        *(f"/v1/jobs/{j}" for j in [*jobs.values(), dismissed]),
        *(f"/v1/jobs/{c['jobID']}" for c in chunks[:1]),
        *(f"/methods/{m}" for m in sorted(methods)),
        f"/pages/jobs/{study}/edit", f"/pages/jobs/{jobs['fourbar-grashof']}/dismiss",
        f"/pages/compare?jobs={jobs['spm-conditioning-map']}&jobs={again}",
        "/ogc/?f=html", "/ogc/conformance?f=html", "/ogc/processes?f=html",
        "/ogc/processes/fourbar-grashof?f=html", "/ogc/jobs?f=html", "/docs", "/redoc",
        f"/ogc/jobs/{study}?f=html", f"/ogc/jobs/{study}/results?f=html",
    ]  # fmt: skip


def test_no_page_is_wider_than_a_phone(server: Deployment, browser: Any, shots: Path) -> None:
    paths = _page_paths(server)
    wide: dict[str, int] = {}
    with open_page(browser, width=PHONE, height=844) as offline:
        page = offline.page
        for path in paths:
            page.goto(server.base_url + path)
            page.wait_for_load_state("load")
            width = int(page.evaluate("document.documentElement.scrollWidth"))
            if width > PHONE:
                wide[path] = width
                page.screenshot(path=str(shots / f"too-wide-{len(wide)}.png"), full_page=True)
        assert not wide, wide
        page.goto(f"{server.base_url}/v1/jobs/{paths[-1].split('/')[3]}")  # a study's page
        page.screenshot(path=str(shots / "study-page-phone.png"), full_page=True)
        # the only console error: the problem page's own 404
        assert offline.console_errors == [
            "Failed to load resource: the server responded with a status of 404 (Not Found)"
        ], offline.console_errors
        assert not offline.external, offline.external


def test_a_process_description_is_folded_to_its_first_sentence(
    server: Deployment, browser: Any
) -> None:
    definition = default_registry().get("planar3r-dexterity-map")
    assert definition is not None
    with open_page(browser, width=PHONE, height=844, javascript=False) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/v1/processes/{definition.id}")
        folded = page.locator("main details.description").first
        summary = folded.locator("summary")
        rest = folded.locator("p")
        assert definition.description.startswith(summary.inner_text().removesuffix(" More…"))
        assert len(summary.inner_text()) < len(definition.description) / 2
        assert summary.is_visible() and not rest.is_visible()
        summary.click()
        assert rest.is_visible() and rest.inner_text()[:40] in definition.description
        page.goto(f"{server.base_url}/v1/processes")
        assert page.locator("ul.processes details.description").count() == len(
            default_registry().ids()
        )
        assert not offline.external, offline.external


def test_the_queue_page_shows_running_work_workers_and_throughput(
    server: Deployment, browser: Any, shots: Path
) -> None:
    done = submit(server, "fourbar-grashof", FOURBAR)
    assert finished(server, done)["status"] == "successful"
    job_id = submit(server, "planar3r-dexterity-map", LONG_MAP)
    try:
        with open_page(browser) as offline:
            page = offline.page
            page.goto(f"{server.base_url}/")
            page.get_by_role("navigation", name="Main").get_by_role("link", name="Queue").click()
            page.wait_for_url("**/queue")
            # the page follows the queue by itself until the job runs
            page.locator(
                f'#queue-listing tr:has(a[href="/v1/jobs/{job_id}"]) .status-running'
            ).wait_for(timeout=TIMEOUT_MS)
            row = page.locator('table.queue tr:has(a[href="/v1/processes/planar3r-dexterity-map"])')
            assert row.locator("td").nth(1).inner_text() == "1"  # running
            beats = page.locator("table.workers tbody tr").all_inner_texts()
            assert beats and all(" ago)" in b for b in beats), beats
            finished_lately = page.locator("#throughput strong").first.inner_text()
            assert int(finished_lately) >= 1
            page.screenshot(path=str(shots / "queue-page.png"), full_page=True)
            assert not offline.external and not offline.console_errors, offline
    finally:
        server.client.delete(f"/v1/jobs/{job_id}")


@pytest.mark.parametrize("javascript", [True, False], ids=["js", "no-js"])
def test_compare_two_jobs_from_the_jobs_list(
    server: Deployment, browser: Any, shots: Path, javascript: bool
) -> None:
    first = submit(server, "fourbar-grashof", FOURBAR)
    second = submit(server, "fourbar-grashof", {**FOURBAR, "lengths": [30, 17, 18, 40]})
    for job_id in (first, second):
        assert finished(server, job_id)["status"] == "successful"
    with open_page(browser, javascript=javascript) as offline:
        page = offline.page
        page.goto(f"{server.base_url}/v1/jobs/{first}")
        page.get_by_role("link", name="Compare with other jobs").click()
        page.wait_for_url("**/v1/jobs?processID=fourbar-grashof")
        page.get_by_label(f"Compare job {first[:8]}").check()
        page.get_by_label(f"Compare job {second[:8]}").check()
        if javascript:  # a refresh of the list keeps what was ticked
            page.locator("#jobs-listing[data-refreshed-at]").wait_for(timeout=TIMEOUT_MS)
            assert page.get_by_label(f"Compare job {first[:8]}").is_checked()
        page.get_by_role("button", name="Compare the selected jobs").click()
        page.wait_for_url("**/pages/compare?*")
        differs = page.locator("table.compare tr.differs th code").all_inner_texts()
        assert "lengths" in differs and "ground" not in differs
        assert page.locator(".compare-plots img").count() >= 2
        if javascript:
            page.screenshot(path=str(shots / "compare-page.png"), full_page=True)
        assert not offline.external and not offline.console_errors, offline
