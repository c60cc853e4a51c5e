"""The job page in each state a job can be in (records built here, no store)."""

from __future__ import annotations

from datetime import UTC, datetime
from functools import partial
from pathlib import Path
from typing import Any

import pytest
from starlette.requests import Request

from service.pages import Pages, PageSettings
from service.pages.views import job_page
from service.routes.process_operations import family_of, family_tags
from worker.contract import ArtifactInfo, JobRecord, JobStatus
from worker.registry import default_registry

NOW = datetime(2026, 1, 2, 3, 4, 5, 678000, tzinfo=UTC)


@pytest.fixture
def pages(tmp_path: Path) -> Pages:
    registry = default_registry()
    return Pages(
        PageSettings(docs_dir=tmp_path),
        family_tags=family_tags(registry),
        family_of=partial(family_of, registry),
    )


def page_of(pages: Pages, job: JobRecord, result: dict[str, Any] | None = None) -> str:
    request = Request(
        {
            "type": "http",
            "method": "GET",
            "path": f"/v1/jobs/{job.job_id}",
            "query_string": b"",
            "headers": [],
        }
    )
    response = job_page(request, pages, default_registry(), job, result)
    assert response.status_code == 200
    return bytes(response.body).decode()


def job(status: JobStatus, **fields: Any) -> JobRecord:
    fields.setdefault("inputs", {"lengths": [30, 17, 18, 25], "ground": 0})
    return JobRecord(
        job_id="j-1",
        process_id="fourbar-grashof",
        status=status,
        created=NOW,
        updated=NOW,
        **fields,
    )


def test_a_running_job_follows_its_progress(pages: Pages) -> None:
    html = page_of(pages, job(JobStatus.RUNNING, progress=42.4, message="classification"))
    assert 'data-events="/v1/jobs/j-1/events"' in html and "job-progress.js" in html
    assert 'value="42"' in html and "classification" in html
    assert "Cancel this job" in html and 'action="/pages/jobs/j-1/dismiss"' in html
    assert "2026-01-02 03:04:05 UTC" in html and "Results" not in html


def test_a_failed_job_shows_its_problem(pages: Pages) -> None:
    error = {
        "type": "time-limit-exceeded",
        "title": "Time limit exceeded",
        "detail": "The job ran longer than 120 s <and was stopped>.",
    }
    html = page_of(pages, job(JobStatus.FAILED, error=error, finished=NOW))
    assert 'href="/problems/time-limit-exceeded"' in html
    assert "Time limit exceeded" in html and "&lt;and was stopped&gt;" in html
    assert "data-events" not in html and "Delete the results" in html


def test_a_dismissed_job_says_so(pages: Pages) -> None:
    html = page_of(pages, job(JobStatus.DISMISSED))
    assert "/problems/job-dismissed" in html and "This job was dismissed" in html
    assert "<form" not in html


def test_the_paper_errata_stand_out(pages: Pages) -> None:
    artifacts = (
        ArtifactInfo("fourbar_motion.svg", "image/svg+xml", 2048, "Range of motion"),
        ArtifactInfo("fourbar_motion.png", "image/png", 1024, "Range of motion"),
        ArtifactInfo("data.csv", "text/csv", 3 * 1024 * 1024, "Samples"),
    )
    notes = ["A note.", "The paper prints 126; it is 136."]
    result = {"grashof": "non-grashof", "notes": notes, "paper_errata": notes[1:]}
    html = page_of(pages, job(JobStatus.SUCCESSFUL, progress=100, artifacts=artifacts), result)
    assert html.count('<li class="erratum">') == 1
    assert '<span class="erratum-tag">Paper erratum</span> The paper prints 126' in html
    assert html.count("<figure") == 1 and 'src="/v1/jobs/j-1/results/fourbar_motion.png"' in html
    assert 'href="/v1/jobs/j-1/results/data.csv" download' in html and "3.0 MB" in html
    assert '<th scope="row">grashof</th>' in html and ">notes<" not in html
    without = page_of(pages, job(JobStatus.SUCCESSFUL), {"notes": notes})  # no paper_errata
    assert "The paper prints 126" in without
    assert 'class="erratum"' not in without and "Paper erratum" not in without


def test_the_provenance_has_its_own_section(pages: Pages) -> None:
    provenance = {"backend": "local-pool/sqlite", "result_key": "k" * 64}
    result = {"grashof": "grashof", "notes": [], "provenance": provenance, "result_hash": "h" * 64}
    html = page_of(pages, job(JobStatus.SUCCESSFUL), result)
    section = html.split('id="provenance-title"', 1)[1]
    assert "local-pool/sqlite" in section and "h" * 64 in section
    assert '<th scope="row">provenance</th>' not in html
    assert 'id="provenance-title"' not in page_of(pages, job(JobStatus.SUCCESSFUL), {"notes": []})


def test_results_show_each_number_with_its_symbol_and_unit(pages: Pages) -> None:
    """Fig 3 in cm: lengths in cm (a nested object's, a list's, a table column's), its
    Grashof margin with its symbol, pure numbers without a unit, meanings on hover."""
    from tests.unit.families.conftest import RecordingContext
    from worker.families.chains import FOURBAR_GRASHOF

    inputs = {"lengths": [30, 17, 18, 25], "ground": 0, "length_unit": "cm"}
    spec = FOURBAR_GRASHOF.inputs_model.model_validate({**inputs, "plots": False})
    result = dict(FOURBAR_GRASHOF.run(spec, RecordingContext()).result)
    html = " ".join(page_of(pages, job(JobStatus.SUCCESSFUL, inputs=inputs), result).split())
    margin = html.split('<th scope="row" title="Grashof&#39;s margin', 1)[1].split("</tr>", 1)[0]
    assert '>margin <span class="symbol">p + q - (s + l)</span></th>' in margin
    assert 'class="num">-4</span> <span class="unit">cm</span></td>' in margin
    assert '<span class="inline">[30, 17, 18, 25]</span> <span class="unit">cm</span>' in html
    assert 'length <span class="symbol">L_i</span> <span class="unit">[cm]</span></th>' in html
    shortest = html.split(">shortest</th>", 1)[1].split("</tr>", 1)[0]
    assert "unit" not in shortest  # an index: a pure number


def test_result_warnings_stand_out(pages: Pages) -> None:
    """summary.warnings (issue 26: an empty map, a task point out of reach) are a box
    above the plots and tagged among the notes; a result without them has neither."""
    warning = "The map is empty: no node of the grid is reachable."
    notes = [warning, "An ordinary note."]
    result = {"summary": {"warnings": [warning], "reachable_points": 0}, "notes": notes}
    html = page_of(pages, job(JobStatus.SUCCESSFUL, progress=100), result)
    box = html[html.index('<section class="result-warnings"') :]
    assert '<h2 id="warnings-title">Warning</h2>' in box[: box.index("</section>")]
    assert warning in box[: box.index("</section>")]
    assert f'<li class="warning"><span class="warning-tag">Warning</span> {warning}' in html
    assert "<li>An ordinary note.</li>" in html
    quiet = {"summary": {"warnings": [], "reachable_points": 7}, "notes": notes[1:]}
    html = page_of(pages, job(JobStatus.SUCCESSFUL, progress=100), quiet)
    assert "result-warnings" not in html and "warning-tag" not in html
