"""The loop's one guard thread, in-process against a real SQLite store: it renews the
attempt it watches, serves attempt after attempt, stops renewing once released, and
never stops the process over a job whose outcome is being committed.  (Stopping the
process on dismissal or at the time limit is tested against real processes in
tests/integration/test_faults.py.)"""

from __future__ import annotations

import threading
import time
from pathlib import Path

import pytest

from worker.attempt_guard import AttemptGuard
from worker.contract import JobStatus
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.store.base import Claim, JobStore, NewJob

SETTINGS = WorkerSettings(workers=1, heartbeat_seconds=0.05, lease_seconds=1.0)


@pytest.fixture
def store(tmp_path: Path) -> JobStore:
    return open_store(f"sqlite:///{tmp_path / 'jobs.db'}")


def claim_one(store: JobStore) -> Claim:
    store.create_job(NewJob("square", {"x": 1}, time_limit_s=30, max_attempts=2))
    claim = store.claim_next("w", SETTINGS.lease_seconds)
    assert claim is not None
    return claim


def lease_expires(store: JobStore, claim: Claim) -> float:
    row = store._one(  # type: ignore[attr-defined]
        store._conn(),  # type: ignore[attr-defined]
        "SELECT lease_expires FROM jobs WHERE job_id = ?",
        (claim.job.job_id,),
    )
    return float(row["lease_expires"])


def test_one_guard_renews_attempt_after_attempt(store: JobStore) -> None:
    guard = AttemptGuard(store, SETTINGS, "w")
    for _ in range(3):
        claim = claim_one(store)
        guard.watch(claim, time.time() + 60)
        time.sleep(1.5)  # past the lease: only renewals keep it
        assert store.reap_expired() == []
        guard.release(claim)
        assert store.complete(claim.job.job_id, claim.lease_token, {}, [])
    assert threading.active_count() >= 2 and guard.is_alive()


def test_a_released_attempt_is_no_longer_renewed(store: JobStore) -> None:
    guard = AttemptGuard(store, SETTINGS, "w")
    claim = claim_one(store)
    guard.watch(claim, time.time() + 60)
    time.sleep(0.2)
    guard.release(claim)
    last = lease_expires(store, claim)
    time.sleep(0.3)
    assert lease_expires(store, claim) == last
    time.sleep(max(0.0, last - time.time()) + 0.1)
    assert store.reap_expired() == [claim.job.job_id]


def test_a_committed_job_does_not_stop_the_process(store: JobStore) -> None:
    """The attempt's own commit ends the lease while the guard still holds it: its next
    heartbeat finds the job no longer running, and must not stop the process."""
    guard = AttemptGuard(store, SETTINGS, "w")
    claim = claim_one(store)
    guard.watch(claim, time.time() + 60)
    guard.committing(claim)
    assert store.complete(claim.job.job_id, claim.lease_token, {"ok": 1}, [])
    time.sleep(0.3)  # several heartbeats see a successful job (os._exit would end pytest)
    guard.release(claim)
    job = store.get_job(claim.job.job_id)
    assert job is not None and job.status is JobStatus.SUCCESSFUL


def test_the_time_limit_is_not_applied_to_a_commit(store: JobStore) -> None:
    guard = AttemptGuard(store, SETTINGS, "w")
    claim = claim_one(store)
    guard.watch(claim, time.time() + 0.1)
    guard.committing(claim)
    time.sleep(0.4)  # past the limit: a computing attempt would be failed and stopped
    guard.release(claim)
    job = store.get_job(claim.job.job_id)
    assert job is not None and job.status is JobStatus.RUNNING


def test_a_committing_attempt_and_the_next_one_are_both_renewed(store: JobStore) -> None:
    guard = AttemptGuard(store, SETTINGS, "w")
    first = claim_one(store)
    guard.watch(first, time.time() + 60)
    guard.committing(first)  # its outcome is being committed on another thread...
    second = claim_one(store)
    guard.watch(second, time.time() + 60)  # ...while the next attempt computes
    time.sleep(1.5)  # past the lease: only renewals keep them
    assert store.reap_expired() == []
    guard.release(first)
    last = lease_expires(store, first)
    time.sleep(1.2)
    assert lease_expires(store, first) == last  # released: no longer renewed
    assert store.reap_expired() == [first.job.job_id]  # the other one still is
    guard.release(second)


class ExitRecorder:
    """Stands in for the ``os`` module in :mod:`worker.attempt_guard`, so that the
    guard's ``os._exit`` is recorded (and its daemon thread parked for good) instead of
    ending pytest."""

    def __init__(self) -> None:
        self.codes: list[int] = []
        self.called = threading.Event()

    def _exit(self, code: int) -> None:
        self.codes.append(code)
        self.called.set()
        threading.Event().wait()


def test_a_time_limit_shorter_than_the_heartbeat_wakes_a_sleeping_guard(
    store: JobStore, monkeypatch: pytest.MonkeyPatch
) -> None:
    import worker.attempt_guard as attempt_guard

    recorder = ExitRecorder()
    monkeypatch.setattr(attempt_guard, "os", recorder)
    slow = WorkerSettings(workers=1, heartbeat_seconds=30, lease_seconds=60)
    guard = AttemptGuard(store, slow, "w")
    first = claim_one(store)
    guard.watch(first, time.time() + 60)
    time.sleep(0.1)  # the guard sleeps until the first heartbeat, 30 s away
    guard.release(first)
    second = claim_one(store)
    guard.watch(second, time.time() + 0.3)
    assert recorder.called.wait(5), "the guard slept through the time limit"
    assert recorder.codes == [attempt_guard.EXIT_TIME_LIMIT]
    job = store.get_job(second.job.job_id)
    assert job is not None and job.status is JobStatus.FAILED
    assert job.error is not None and job.error["type"] == "time-limit-exceeded"


def test_a_stop_waits_for_the_outcome_being_committed(
    store: JobStore, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The next attempt passes its time limit while the previous outcome is still being
    committed: the process stops only once that commit has ended."""
    import worker.attempt_guard as attempt_guard

    recorder = ExitRecorder()
    monkeypatch.setattr(attempt_guard, "os", recorder)
    guard = AttemptGuard(store, SETTINGS, "w")
    first = claim_one(store)
    guard.watch(first, time.time() + 60)
    guard.committing(first)
    second = claim_one(store)
    guard.watch(second, time.time() + 0.1)
    time.sleep(0.6)
    assert not recorder.called.is_set()  # the time limit passed, but a commit is on
    job = store.get_job(second.job.job_id)
    assert job is not None and job.status is JobStatus.FAILED  # already recorded
    assert store.complete(first.job.job_id, first.lease_token, {"ok": 1}, [])
    guard.release(first)
    assert recorder.called.wait(5)
    assert recorder.codes == [attempt_guard.EXIT_TIME_LIMIT]
    done = store.get_job(first.job.job_id)
    assert done is not None and done.status is JobStatus.SUCCESSFUL
