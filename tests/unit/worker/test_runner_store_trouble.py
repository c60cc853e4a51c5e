"""The worker under store trouble, in-process against a real SQLite store: a store
that refuses some calls for a while (a fake wrapping the real store, not a mock)."""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Any

import pytest

from tests.unit.worker.test_runner import registry
from worker.attempt_guard import AttemptGuard
from worker.contract import Artifact, JobStatus
from worker.errors import StorageFull, StoreUnavailable
from worker.result_commit import commit_outcome
from worker.runner import WorkerLoop
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.store.base import JobStore, NewJob


class TroubledStore:
    """The real store, except that the named calls raise ``error`` until ``until``
    (a monotonic time) or for their first ``times`` calls."""

    def __init__(
        self,
        store: JobStore,
        error: Exception,
        failing: set[str],
        until: float = float("inf"),
        times: int = 10**9,
    ) -> None:
        self._store = store
        self._error = error
        self._failing = failing
        self._until = until
        self._times = times
        self.calls: dict[str, int] = {}

    def __getattr__(self, name: str) -> Any:
        method = getattr(self._store, name)
        if name not in self._failing:
            return method

        def troubled(*args: Any, **kwargs: Any) -> Any:
            self.calls[name] = self.calls.get(name, 0) + 1
            if time.monotonic() < self._until and self.calls[name] <= self._times:
                raise self._error
            return method(*args, **kwargs)

        return troubled


@pytest.fixture
def store(tmp_path: Path) -> JobStore:
    return open_store(f"sqlite:///{tmp_path / 'jobs.db'}")


def submit_square(store: JobStore, x: float = 3.0) -> str:
    job, _ = store.create_job(NewJob("square", {"x": x}, time_limit_s=30, max_attempts=2))
    return job.job_id


def test_progress_writes_that_fail_never_fail_the_job(store: JobStore) -> None:
    job, _ = store.create_job(NewJob("steps", {"x": 0.3}, time_limit_s=30, max_attempts=2))
    job_id = job.job_id
    troubled = TroubledStore(store, StoreUnavailable("locked"), {"report_progress"})
    loop = WorkerLoop(WorkerSettings(workers=1), troubled, registry())  # type: ignore[arg-type]
    claim = store.claim_next(loop.worker_id, 10)
    assert claim is not None
    loop.execute(claim)
    done = store.get_job(job_id)
    assert done is not None and done.status is JobStatus.SUCCESSFUL, done
    assert troubled.calls["report_progress"] >= 1


def test_the_guard_survives_store_errors_and_keeps_renewing(store: JobStore) -> None:
    job_id = submit_square(store)
    claim = store.claim_next("w", 1.0)
    assert claim is not None
    troubled = TroubledStore(
        store, StoreUnavailable("down"), {"heartbeat", "worker_heartbeat"}, times=3
    )
    settings = WorkerSettings(workers=1, heartbeat_seconds=0.1, lease_seconds=1.0)
    guard = AttemptGuard(troubled, settings, "w")  # type: ignore[arg-type]
    guard.watch(claim, time.time() + 60)
    try:
        time.sleep(1.5)  # > the lease: only renewals after the errors keep it alive
        assert guard.is_alive()
        assert troubled.calls["heartbeat"] > 3
        assert store.reap_expired() == []
        job = store.get_job(job_id)
        assert job is not None and job.status is JobStatus.RUNNING
    finally:
        guard.release(claim)


def test_a_commit_waits_out_a_store_outage(store: JobStore) -> None:
    job_id = submit_square(store)
    claim = store.claim_next("w", 30)
    assert claim is not None
    troubled = TroubledStore(
        store, StoreUnavailable("down"), {"complete"}, until=time.monotonic() + 1.0
    )
    stored = commit_outcome(
        troubled,
        claim,
        {"square": 9.0},  # type: ignore[arg-type]
        [Artifact("s.csv", "text/csv", b"9")],
        give_up_after_s=10,
    )
    assert stored and troubled.calls["complete"] >= 2
    done = store.get_job(job_id)
    assert done is not None and done.status is JobStatus.SUCCESSFUL


def test_a_commit_gives_up_after_the_bound_and_leaves_the_job_to_a_retry(
    store: JobStore,
) -> None:
    job_id = submit_square(store)
    claim = store.claim_next("w", 30)
    assert claim is not None
    troubled = TroubledStore(store, StoreUnavailable("down"), {"complete"})
    started = time.monotonic()
    assert not commit_outcome(troubled, claim, {}, [], give_up_after_s=1.0)  # type: ignore[arg-type]
    assert time.monotonic() - started < 3
    job = store.get_job(job_id)
    assert job is not None and job.status is JobStatus.RUNNING  # its lease will lapse


def test_a_full_disk_fails_the_job_once_with_the_cause(store: JobStore) -> None:
    job_id = submit_square(store)
    troubled = TroubledStore(store, StorageFull("No space left on device"), {"complete"})
    loop = WorkerLoop(WorkerSettings(workers=1), troubled, registry())  # type: ignore[arg-type]
    claim = store.claim_next(loop.worker_id, 10)
    assert claim is not None
    loop.execute(claim)
    done = store.get_job(job_id)
    assert done is not None and done.status is JobStatus.FAILED
    assert done.error is not None and done.error["type"] == "storage-full"
    assert "No space left" in done.error["detail"] and done.attempts == 1
    assert troubled.calls["complete"] == 1  # no recompute, no retry loop


def test_the_worker_loop_rides_out_an_unavailable_store(store: JobStore) -> None:
    job_id = submit_square(store)
    troubled = TroubledStore(
        store, StoreUnavailable("locked"), {"claim_next"}, until=time.monotonic() + 1.0
    )
    loop = WorkerLoop(WorkerSettings(workers=1, poll_seconds=0.05), troubled, registry())  # type: ignore[arg-type]
    runner = threading.Thread(target=loop.run, daemon=True)
    runner.start()
    deadline = time.monotonic() + 15
    while time.monotonic() < deadline:
        job = store.get_job(job_id)
        if job is not None and job.status is JobStatus.SUCCESSFUL:
            break
        time.sleep(0.05)
    loop.request_stop()
    runner.join(10)
    job = store.get_job(job_id)
    assert job is not None and job.status is JobStatus.SUCCESSFUL
    assert troubled.calls["claim_next"] >= 2


class SlowCommits:
    """The real store, whose commits take ``delay_s`` (a slow disk)."""

    def __init__(self, store: JobStore, delay_s: float) -> None:
        self._store = store
        self._delay_s = delay_s
        self.committing = threading.Event()

    def __getattr__(self, name: str) -> Any:
        return getattr(self._store, name)

    def complete(self, *args: Any, **kwargs: Any) -> bool:
        self.committing.set()
        time.sleep(self._delay_s)
        return bool(self._store.complete(*args, **kwargs))


def test_a_commit_behind_keeps_the_lease_and_overlaps_the_next_claim(
    store: JobStore,
) -> None:
    """With ``commit_behind`` (Celery) execute returns before the commit; the lease is
    renewed meanwhile; the next job is claimed and run while the commit goes on, and
    its own commit waits for the first."""
    first, second = submit_square(store, 2.0), submit_square(store, 3.0)
    slow = SlowCommits(store, delay_s=2.5)
    settings = WorkerSettings(workers=1, heartbeat_seconds=0.1, lease_seconds=1.0)
    loop = WorkerLoop(settings, slow, registry(), commit_behind=True)  # type: ignore[arg-type]
    claim = loop.claim()
    assert claim is not None and claim.job.job_id == first
    started = time.monotonic()
    loop.execute(claim)
    assert time.monotonic() - started < 2.0  # returned while the commit runs
    assert slow.committing.wait(5)
    following = loop.claim()  # does not wait for the commit
    assert following is not None and following.job.job_id == second
    loop.execute(following)  # computed beside the commit; its commit waits for the first
    assert time.monotonic() - started >= 2.4
    time.sleep(1.3)  # past the lease: only renewals keep the second job
    assert store.reap_expired() == []
    done = store.get_job(first)
    assert done is not None and done.status is JobStatus.SUCCESSFUL
    loop.settle()
    result = store.get_result(second)
    assert result is not None and result["square"] == 9.0 and result["notes"] == ["a note"]


def test_a_claim_held_back_by_the_commit_in_flight_waits_for_it(store: JobStore) -> None:
    """Under a running cap of one, the job being committed still counts as running: a
    claim that finds nothing settles the commit and looks again."""
    ids = [
        store.create_job(
            NewJob("square", {"x": x}, time_limit_s=30, max_attempts=2, owner="alice")
        )[0].job_id
        for x in (2.0, 3.0)
    ]
    slow = SlowCommits(store, delay_s=0.5)
    settings = WorkerSettings(workers=1, lease_seconds=5.0, max_running_per_key=1)
    loop = WorkerLoop(settings, slow, registry(), commit_behind=True)  # type: ignore[arg-type]
    claim = loop.claim()
    assert claim is not None and claim.job.job_id == ids[0]
    loop.execute(claim)
    following = loop.claim()
    assert following is not None and following.job.job_id == ids[1]
    done = store.get_job(ids[0])
    assert done is not None and done.status is JobStatus.SUCCESSFUL
    loop.execute(following)
    loop.settle()


def test_a_commit_behind_that_fails_is_logged_and_leaves_the_job_to_a_retry(
    store: JobStore, caplog: pytest.LogCaptureFixture
) -> None:
    job_id = submit_square(store)
    troubled = TroubledStore(store, RuntimeError("the disk went away"), {"complete"})
    settings = WorkerSettings(workers=1, lease_seconds=1.0)
    loop = WorkerLoop(settings, troubled, registry(), commit_behind=True)  # type: ignore[arg-type]
    claim = loop.claim()
    assert claim is not None
    loop.execute(claim)
    loop.settle()  # does not raise
    assert "could not be committed" in caplog.text
    job = store.get_job(job_id)
    assert job is not None and job.status is JobStatus.RUNNING  # its lease will lapse
    time.sleep(1.2)
    assert store.reap_expired() == [job_id]
