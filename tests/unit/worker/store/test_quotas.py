"""Quotas checked with the insert (worker.store.quotas), on SQLite and PostgreSQL:
queued jobs per owner, the whole queue, submissions per minute; threads racing for
the last slot; replays and a job's own work do not count."""

from __future__ import annotations

import threading
import time
from typing import Any

import pytest

from worker.errors import QueueFull, QuotaExceeded, RateLimited
from worker.settings import WorkerSettings
from worker.store.base import JobStore, NewJob, QueueLimits
from worker.submission import queue_limits

PER_OWNER = QueueLimits(max_queued=100, max_queued_per_owner=3)


def new_job(owner: str, limits: QueueLimits, **kw: Any) -> NewJob:
    return NewJob("p", {"n": 1}, time_limit_s=60, max_attempts=3, owner=owner, limits=limits,
                  **kw)  # fmt: skip


def test_an_owner_may_queue_up_to_its_quota(store: JobStore) -> None:
    for _ in range(3):
        store.create_job(new_job("alice", PER_OWNER))
    with pytest.raises(QuotaExceeded, match="3 jobs queued") as refused:
        store.create_job(new_job("alice", PER_OWNER))
    assert not isinstance(refused.value, RateLimited)
    assert refused.value.extra["limit"] == "DEXLAB_MAX_QUEUED_PER_KEY"
    assert refused.value.extra["allowed"] == 3 and refused.value.extra["retry_after_s"] > 0
    store.create_job(new_job("bob", PER_OWNER))  # another owner's queue is its own
    claim = store.claim_next("w", 30)  # one of alice's starts: a slot frees
    assert claim is not None and claim.job.owner == "alice"
    store.create_job(new_job("alice", PER_OWNER))
    assert len(store.list_jobs(limit=100, owner="alice").jobs) == 4


def test_the_whole_queue_has_a_cap(store: JobStore) -> None:
    limits = QueueLimits(max_queued=4, max_queued_per_owner=3)
    for owner in ("alice", "alice", "alice", "bob"):
        store.create_job(new_job(owner, limits))
    with pytest.raises(QueueFull, match="4 jobs") as refused:
        store.create_job(new_job("carol", limits))
    assert refused.value.extra["limit"] == "DEXLAB_MAX_QUEUED"
    anonymous = QueueLimits(max_queued=4)  # the operator of a keyless service too
    with pytest.raises(QueueFull):
        store.create_job(new_job("", anonymous))


def test_idempotent_replays_and_a_jobs_own_work_do_not_count(store: JobStore) -> None:
    first, _ = store.create_job(new_job("alice", PER_OWNER, idempotency_key="k", request_hash="h"))
    store.create_job(new_job("alice", PER_OWNER))
    store.create_job(new_job("alice", PER_OWNER))
    replay, created = store.create_job(
        new_job("alice", PER_OWNER, idempotency_key="k", request_hash="h")
    )
    assert not created and replay.job_id == first.job_id  # at the quota, yet answered
    for _ in range(2):  # chunks of alice's first job: counted as that job
        store.create_job(new_job("alice", PER_OWNER, parent_id=first.job_id))
    with pytest.raises(QuotaExceeded):
        store.create_job(new_job("alice", PER_OWNER))


def test_submissions_per_minute_are_a_token_bucket(
    store: JobStore, monkeypatch: pytest.MonkeyPatch
) -> None:
    limits = QueueLimits(max_queued=100, max_queued_per_owner=2, submit_rate_per_min=3)
    store.create_job(new_job("alice", limits))
    store.create_job(new_job("alice", limits))
    with pytest.raises(QuotaExceeded) as full:  # refused by the queue: no token taken
        store.create_job(new_job("alice", limits))
    assert not isinstance(full.value, RateLimited)
    for job in store.list_jobs(limit=10, owner="alice").jobs:
        store.dismiss(job.job_id)
    store.create_job(new_job("alice", limits))  # the third token
    with pytest.raises(RateLimited, match="3 submissions a minute") as limited:
        store.create_job(new_job("alice", limits))
    assert limited.value.extra["limit"] == "DEXLAB_SUBMIT_RATE_PER_MIN"
    assert 19 < limited.value.extra["retry_after_s"] <= 20  # one token every 20 s
    store.create_job(new_job("bob", limits))  # bob has a bucket of his own
    real = time.time
    monkeypatch.setattr(time, "time", lambda: real() + 20.5)
    store.create_job(new_job("alice", limits))  # a token came back
    with pytest.raises(RateLimited):
        store.create_job(new_job("alice", limits))


def test_racing_submissions_cannot_both_take_the_last_slot(store: JobStore) -> None:
    limits = QueueLimits(max_queued=5, max_queued_per_owner=3)
    store.create_job(new_job("alice", limits))
    store.create_job(new_job("bob", limits))
    outcomes: list[str] = []
    lock = threading.Lock()
    start = threading.Barrier(12)

    def race(owner: str) -> None:
        start.wait()
        try:
            store.create_job(new_job(owner, limits))
            outcome = "created"
        except QuotaExceeded:
            outcome = "quota"
        except QueueFull:
            outcome = "full"
        with lock:
            outcomes.append(outcome)

    threads = [threading.Thread(target=race, args=("alice" if n % 2 else "carol",))
               for n in range(12)]  # fmt: skip
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert outcomes.count("created") == 3  # the whole queue's 5, no more
    assert len(store.list_jobs(limit=100).jobs) == 5
    assert len(store.list_jobs(limit=100, owner="alice").jobs) <= 3
    assert len(store.list_jobs(limit=100, owner="carol").jobs) <= 3


def test_keys_get_every_quota_the_anonymous_operator_only_the_queues() -> None:
    settings = WorkerSettings(max_queued=9, max_queued_per_key=4, submit_rate_per_min=7)
    assert queue_limits(settings, "alice") == QueueLimits(9, 4, 7)
    assert queue_limits(settings, "") == QueueLimits(max_queued=9)
    unlimited = WorkerSettings(submit_rate_per_min=0)
    assert queue_limits(unlimited, "alice").submit_rate_per_min is None
