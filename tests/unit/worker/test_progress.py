"""Progress reports: throttled from the claim, held back rather than lost, flushed by
the attempt's guard; against a real SQLite store."""

from __future__ import annotations

import threading
import time
from pathlib import Path

import pytest

from tests.unit.worker.test_runner import registry
from worker.contract import JobStatus
from worker.progress import StoreProgress
from worker.runner import WorkerLoop
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.store.base import Claim, JobStore, NewJob


@pytest.fixture
def store(tmp_path: Path) -> JobStore:
    return open_store(f"sqlite:///{tmp_path / 'jobs.db'}")


def claimed(store: JobStore, process_id: str = "square", x: float = 3.0) -> Claim:
    store.create_job(NewJob(process_id, {"x": x}, time_limit_s=30, max_attempts=2))
    claim = store.claim_next("w", 10)
    assert claim is not None
    return claim


def shown(store: JobStore, job_id: str) -> tuple[float, str]:
    job = store.get_job(job_id)
    assert job is not None
    return job.progress, job.message


def test_the_claim_shows_the_attempt_running_at_zero(store: JobStore) -> None:
    claim = claimed(store)
    assert shown(store, claim.job.job_id) == (0.0, "running attempt 1")


def test_reports_within_the_interval_after_the_claim_are_held_back(store: JobStore) -> None:
    claim = claimed(store)
    progress = StoreProgress(store, claim.job.job_id, claim.lease_token, min_interval_s=30)
    progress.report_progress(10, "first")
    progress.report_progress(100, "done")
    assert shown(store, claim.job.job_id) == (0.0, "running attempt 1")
    progress.flush()
    assert shown(store, claim.job.job_id) == (100.0, "done")
    progress.flush()  # nothing held back: nothing written
    assert shown(store, claim.job.job_id) == (100.0, "done")


def test_a_report_due_is_written_at_once_and_never_goes_backwards(store: JobStore) -> None:
    claim = claimed(store)
    progress = StoreProgress(store, claim.job.job_id, claim.lease_token, min_interval_s=0)
    progress.report_progress(40, "forty")
    assert shown(store, claim.job.job_id) == (40.0, "forty")
    progress.report_progress(20, "back?")
    assert shown(store, claim.job.job_id) == (40.0, "back?")
    progress.report_progress(250, "over")
    assert shown(store, claim.job.job_id) == (100.0, "over")


def test_a_report_of_another_attempt_changes_nothing(store: JobStore) -> None:
    claim = claimed(store)
    progress = StoreProgress(store, claim.job.job_id, "not-the-token", min_interval_s=0)
    progress.report_progress(50, "stale")
    assert shown(store, claim.job.job_id) == (0.0, "running attempt 1")


def test_the_guard_writes_a_held_back_step_while_the_step_runs(store: JobStore) -> None:
    """The job reports "step two" right after "step one" (held back by the throttle),
    then works for a while: the guard's next heartbeat writes it."""
    store.create_job(NewJob("steps", {"x": 0.6}, time_limit_s=30, max_attempts=2))
    loop = WorkerLoop(WorkerSettings(workers=1, heartbeat_seconds=0.2), store, registry())
    claim = store.claim_next(loop.worker_id, 10)
    assert claim is not None
    runner = threading.Thread(target=loop.execute, args=(claim,))
    runner.start()
    seen = set()
    while runner.is_alive():
        seen.add(shown(store, claim.job.job_id))
        time.sleep(0.05)
    runner.join()
    assert (60.0, "step two") in seen, seen
    job = store.get_job(claim.job.job_id)
    assert job is not None and job.status is JobStatus.SUCCESSFUL
    assert shown(store, claim.job.job_id) == (100.0, "finished")


def test_a_quick_job_makes_no_progress_write(store: JobStore) -> None:
    class Counting:
        def __init__(self, inner: JobStore) -> None:
            self.inner = inner
            self.writes = 0

        def __getattr__(self, name: str) -> object:
            if name == "report_progress":
                self.writes += 1
            return getattr(self.inner, name)

    counting = Counting(store)
    claim = claimed(store)
    loop = WorkerLoop(WorkerSettings(workers=1), counting, registry())  # type: ignore[arg-type]
    loop.execute(claim)
    assert counting.writes == 0
    assert shown(store, claim.job.job_id) == (100.0, "finished")
