"""The worker loop, run in-process against a real SQLite store with a toy process.

(Fault behaviour - killed processes, time limits, dismissal - is tested against the
real pool in tests/integration.)
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import pytest
from pydantic import BaseModel, ConfigDict

from worker.contract import Artifact, JobContext, JobOutcome, JobStatus
from worker.processes import ProcessDefinition, ProcessRegistry
from worker.runner import WorkerLoop
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.store.base import JobStore, NewJob


class SquareInputs(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)
    x: float


def run_square(inputs: SquareInputs, ctx: JobContext) -> JobOutcome:
    if inputs.x < 0:
        raise ValueError("x must be non-negative")
    ctx.report_progress(50, "half way")
    return JobOutcome(
        result={"square": inputs.x**2},
        artifacts=(Artifact("square.csv", "text/csv", b"x,square\n"),),
        notes=("a note",),
    )


def run_square_against_a_paper(inputs: SquareInputs, ctx: JobContext) -> JobOutcome:
    return JobOutcome(
        result={"square": inputs.x**2},
        notes=("a note", "another note"),
        errata=("the paper prints 10; it is 9",),
    )


def run_steps(inputs: SquareInputs, ctx: JobContext) -> JobOutcome:
    """Two steps of ``x`` seconds each, reported as they start (a long-running job)."""
    time.sleep(inputs.x)
    ctx.report_progress(30, "step one")
    ctx.report_progress(60, "step two")  # within the throttle: held back
    time.sleep(inputs.x)
    return JobOutcome(result={"square": inputs.x**2})


def registry() -> ProcessRegistry:
    return ProcessRegistry(
        (
            ProcessDefinition(
                id="square",
                title="Square",
                description="x squared",
                inputs_model=SquareInputs,
                run=run_square,
                examples=(),
                outputs={"square": "x**2"},
                cost=lambda _: 1,
                cost_limit=10,
            ),
            ProcessDefinition(
                id="steps",
                title="Two timed steps",
                description="sleeps x seconds twice, reporting each step",
                inputs_model=SquareInputs,
                run=run_steps,
                examples=(),
                outputs={"square": "x**2"},
                cost=lambda _: 1,
                cost_limit=10,
            ),
            ProcessDefinition(
                id="paper-square",
                title="Square, against a paper",
                description="x squared",
                inputs_model=SquareInputs,
                run=run_square_against_a_paper,
                examples=(),
                outputs={"square": "x**2"},
                cost=lambda _: 1,
                cost_limit=10,
            ),
        )
    )


@pytest.fixture
def store(tmp_path: Path) -> JobStore:
    return open_store(f"sqlite:///{tmp_path / 'jobs.db'}")


def submit(store: JobStore, process_id: str, inputs: dict[str, Any]) -> str:
    job, _ = store.create_job(NewJob(process_id, inputs, time_limit_s=30, max_attempts=2))
    return job.job_id


def run_one(store: JobStore) -> None:
    loop = WorkerLoop(WorkerSettings(workers=1), store, registry())
    claim = store.claim_next(loop.worker_id, 10)
    assert claim is not None
    loop.execute(claim)


def test_successful_job_stores_result_notes_and_artifacts(store: JobStore) -> None:
    job_id = submit(store, "square", {"x": 3})
    run_one(store)
    job = store.get_job(job_id)
    assert job is not None and job.status is JobStatus.SUCCESSFUL
    assert store.get_result(job_id) == {"square": 9.0, "notes": ["a note"], "paper_errata": []}
    assert [a.name for a in job.artifacts] == ["square.csv"]


def test_paper_errata_follow_the_notes_and_are_listed_apart(store: JobStore) -> None:
    job_id = submit(store, "paper-square", {"x": 3})
    run_one(store)
    assert store.get_result(job_id) == {
        "square": 9.0,
        "notes": ["a note", "another note", "the paper prints 10; it is 9"],
        "paper_errata": ["the paper prints 10; it is 9"],
    }


def test_raising_job_fails_with_reason(store: JobStore) -> None:
    job_id = submit(store, "square", {"x": -1})
    run_one(store)
    job = store.get_job(job_id)
    assert job is not None and job.status is JobStatus.FAILED
    assert job.error is not None and job.error["type"] == "job-error"
    assert "x must be non-negative" in job.error["detail"]


def test_unknown_process_fails_cleanly(store: JobStore) -> None:
    job_id = submit(store, "cube", {"x": 1})
    run_one(store)
    job = store.get_job(job_id)
    assert job is not None and job.status is JobStatus.FAILED
    assert job.error is not None and "cube" in job.error["detail"]


def test_inputs_that_no_longer_validate_fail_with_reason(store: JobStore) -> None:
    job_id = submit(store, "square", {"x": "not a number"})
    run_one(store)
    job = store.get_job(job_id)
    assert job is not None and job.status is JobStatus.FAILED
    assert job.error is not None and "ValidationError" in job.error["detail"]
