"""The worker loop, run in-process against a real SQLite store with a toy process.

(Fault behaviour - killed processes, time limits, dismissal - is tested against the
real pool in tests/integration; so are wake-ups across processes.)
"""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import pytest
from pydantic import BaseModel, ConfigDict

from worker.contract import Artifact, JobContext, JobOutcome, JobStatus
from worker.dispatch.wake_ups import PoolWakeUps, WakeUpListener, WakeUpSender
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
    result = store.get_result(job_id)
    assert result is not None
    assert {k: result[k] for k in ("square", "notes", "paper_errata")} == {
        "square": 9.0, "notes": ["a note"], "paper_errata": [],
    }  # fmt: skip
    assert [a.name for a in job.artifacts] == ["square.csv"]


def test_a_result_says_what_computed_it(store: JobStore) -> None:
    """provenance names the process, build, libraries, backend and result key; the hash
    covers the values alone, so a second run of the same inputs hashes alike."""
    first, second = submit(store, "square", {"x": 3}), submit(store, "square", {"x": 3})
    run_one(store)
    run_one(store)
    one, two = store.get_result(first), store.get_result(second)
    assert one is not None and two is not None
    provenance = one["provenance"]
    assert provenance["process"] == {"id": "square", "version": "1.0.0"}
    assert provenance["backend"] == "local-pool/sqlite"
    assert set(provenance["libraries"]) == {"python", "numpy", "scipy"}
    assert provenance["dexlab"]["version"]
    assert len(provenance["result_key"]) == 64 and len(one["result_hash"]) == 64
    assert one["result_hash"] == two["result_hash"]
    assert provenance == two["provenance"]


def test_paper_errata_follow_the_notes_and_are_listed_apart(store: JobStore) -> None:
    job_id = submit(store, "paper-square", {"x": 3})
    run_one(store)
    result = store.get_result(job_id)
    assert result is not None
    assert {k: result[k] for k in ("square", "notes", "paper_errata")} == {
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


# -- idle: wake-up hints, the safety-net poll, heartbeats -------------------------------


@contextmanager
def running(loop: WorkerLoop) -> Iterator[threading.Thread]:
    """``loop.run()`` on a thread of its own, stopped (and joined) afterwards."""
    thread = threading.Thread(target=loop.run, daemon=True)
    thread.start()
    try:
        yield thread
    finally:
        loop.request_stop()
        thread.join(timeout=10)
        assert not thread.is_alive()


def started_after_s(store: JobStore, job_id: str, timeout_s: float = 10.0) -> float:
    """Seconds from the job's creation to its start, once it ended."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        job = store.get_job(job_id)
        assert job is not None
        if job.status is JobStatus.SUCCESSFUL:
            assert job.started is not None
            return (job.started - job.created).total_seconds()
        time.sleep(0.01)
    raise AssertionError(f"job {job_id} did not end in {timeout_s} s")


@pytest.fixture
def wake_ups(tmp_path: Path) -> Iterator[PoolWakeUps]:
    bound = PoolWakeUps.bind(tmp_path / "wake")
    assert bound is not None
    yield bound
    bound.close()


def test_an_idle_loop_starts_a_hinted_job_at_once_and_polls_without_one(
    store: JobStore, wake_ups: PoolWakeUps
) -> None:
    settings = WorkerSettings(workers=1, poll_seconds=1.0)
    loop = WorkerLoop(settings, store, registry(), wake_ups=WakeUpListener(wake_ups.sock))
    sender = WakeUpSender(wake_ups.path.parent)
    try:
        with running(loop):
            time.sleep(0.3)  # asleep, its first claim found nothing
            delays = []
            for x in range(5):
                job_id = submit(store, "square", {"x": x})
                sender.wake(1)
                delays.append(started_after_s(store, job_id))
            assert sorted(delays)[2] < 0.1 and max(delays) < 0.5, delays
            unhinted = [submit(store, "square", {"x": 7})]  # a lost hint: the poll finds it
            assert started_after_s(store, unhinted[0]) < 1.0 + 0.5
    finally:
        sender.close()


def test_a_stop_wakes_a_loop_sleeping_for_a_long_poll(
    store: JobStore, wake_ups: PoolWakeUps
) -> None:
    settings = WorkerSettings(workers=1, poll_seconds=60.0)
    loop = WorkerLoop(settings, store, registry(), wake_ups=WakeUpListener(wake_ups.sock))
    with running(loop) as thread:
        time.sleep(0.3)
        stop = time.monotonic()
        loop.request_stop()
        thread.join(timeout=10)
        assert time.monotonic() - stop < 1.0


@pytest.mark.parametrize("hinted", [True, False])
def test_an_idle_loop_beats_while_it_sleeps_for_a_long_poll(
    store: JobStore, wake_ups: PoolWakeUps, hinted: bool
) -> None:
    """Readiness and synchronous answers count the workers that beat lately: a long
    safety-net poll must not make an idle worker look dead."""
    settings = WorkerSettings(workers=1, poll_seconds=60.0, heartbeat_seconds=0.2)
    if hinted:
        loop = WorkerLoop(settings, store, registry(), wake_ups=WakeUpListener(wake_ups.sock))
    else:
        loop = WorkerLoop(settings, store, registry())
    with running(loop):
        time.sleep(1.0)
        assert [w.worker_id for w in store.live_workers(within_s=0.6)] == [loop.worker_id]
        time.sleep(0.6)
        assert [w.worker_id for w in store.live_workers(within_s=0.6)] == [loop.worker_id]
