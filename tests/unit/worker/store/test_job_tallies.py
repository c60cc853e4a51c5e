"""Job tallies (worker.store.tallies): each event counted once, in its transaction, on
both stores; the queue's depth."""

from __future__ import annotations

import math
import time

import pytest
from hypothesis import given
from hypothesis import strategies as st

from worker.contract import JobStatus
from worker.store.base import JobStore, NewJob
from worker.store.tallies import (
    DURATION_BUCKETS,
    QUEUE_WAIT_BUCKETS,
    bound_label,
    bucket_label,
    label_bound,
)


def new_job(process_id: str = "p", max_attempts: int = 3, key: str | None = None) -> NewJob:
    return NewJob(process_id=process_id, inputs={"a": 1}, time_limit_s=60.0,
                  max_attempts=max_attempts, idempotency_key=key, request_hash="h")  # fmt: skip


def counts(store: JobStore) -> dict[tuple[str, str, str], int]:
    return {(t.process_id, t.tally, t.label): t.count for t in store.job_tallies()}


def histogram(store: JobStore, process_id: str, tally: str) -> tuple[int, float]:
    rows = [t for t in store.job_tallies() if (t.process_id, t.tally) == (process_id, tally)]
    return sum(t.count for t in rows), sum(t.total for t in rows)


def test_submits_count_once_per_job_not_per_idempotent_replay(store: JobStore) -> None:
    store.create_job(new_job("p", key="k"))
    _, created = store.create_job(new_job("p", key="k"))
    assert not created
    store.create_job(new_job("q"))
    tallies = counts(store)
    assert tallies[("p", "submitted", "")] == 1
    assert tallies[("q", "submitted", "")] == 1


def test_a_successful_job_counts_attempt_wait_finish_and_duration(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    claim = store.claim_next("w", 10)
    assert claim is not None
    assert store.complete(job.job_id, claim.lease_token, {"x": 1}, [])
    assert store.complete(job.job_id, claim.lease_token, {"x": 1}, [])  # a retried commit
    tallies = counts(store)
    assert tallies[("p", "attempts", "")] == 1
    assert ("p", "retries", "") not in tallies
    assert tallies[("p", "finished", "successful")] == 1
    done = store.get_job(job.job_id)
    assert done is not None and done.started is not None and done.finished is not None
    n, total = histogram(store, "p", "duration")
    assert n == 1
    assert total == pytest.approx((done.finished - done.started).total_seconds(), abs=1e-3)
    n, total = histogram(store, "p", "queue_wait")
    assert n == 1
    assert total == pytest.approx((done.started - done.created).total_seconds(), abs=1e-3)


def test_failures_count_once_and_a_lost_worker_counts_a_retry(store: JobStore) -> None:
    failing, _ = store.create_job(new_job(max_attempts=2))
    claim = store.claim_next("w1", 10)
    assert claim is not None
    error = {"type": "job-error", "title": "Job error", "detail": "boom"}
    assert store.fail(failing.job_id, claim.lease_token, error)
    assert store.fail(failing.job_id, claim.lease_token, error)  # a retried commit
    lost, _ = store.create_job(new_job(max_attempts=2))
    for attempt in (1, 2):  # each attempt's worker vanishes; its lease lapses
        claim = store.claim_next(f"w{attempt}", 0.01)
        assert claim is not None and claim.job.job_id == lost.job_id
        time.sleep(0.05)
    store.reap_expired()
    final = store.get_job(lost.job_id)
    assert final is not None and final.status is JobStatus.FAILED
    tallies = counts(store)
    assert tallies[("p", "finished", "failed")] == 2
    assert tallies[("p", "attempts", "")] == 3
    assert tallies[("p", "retries", "")] == 1
    assert histogram(store, "p", "duration")[0] == 2
    assert histogram(store, "p", "queue_wait")[0] == 2  # first claims only


def test_dismissal_counts_only_a_job_that_had_not_finished(store: JobStore) -> None:
    waiting, _ = store.create_job(new_job())
    done, _ = store.create_job(new_job())
    store.dismiss(waiting.job_id)
    store.dismiss(waiting.job_id)
    claim = store.claim_next("w", 10)
    assert claim is not None and claim.job.job_id == done.job_id
    assert store.complete(done.job_id, claim.lease_token, {}, [])
    store.dismiss(done.job_id)
    tallies = counts(store)
    assert tallies[("p", "finished", "dismissed")] == 1
    assert tallies[("p", "finished", "successful")] == 1
    assert histogram(store, "p", "duration")[0] == 1  # a dismissal has no duration


def test_queue_depth_counts_accepted_and_running_jobs_by_process(store: JobStore) -> None:
    assert store.queue_depth() == {}
    for process_id in ("p", "p", "q"):
        store.create_job(new_job(process_id))
    assert store.claim_next("w", 10) is not None
    assert store.queue_depth() == {
        ("p", JobStatus.RUNNING): 1,
        ("p", JobStatus.ACCEPTED): 1,
        ("q", JobStatus.ACCEPTED): 1,
    }


@given(st.floats(min_value=0, max_value=1e5, allow_nan=False))
def test_a_value_falls_in_the_first_bucket_whose_bound_holds_it(seconds: float) -> None:
    for bounds in (DURATION_BUCKETS, QUEUE_WAIT_BUCKETS):
        bound = label_bound(bucket_label(seconds, bounds))
        assert seconds <= bound
        below = [b for b in bounds if b < bound]
        assert not below or seconds > below[-1]


def test_bucket_labels_are_written_as_prometheus_writes_them() -> None:
    assert bound_label(0.5) == "0.5"
    assert bound_label(10) == "10.0"
    assert bound_label(math.inf) == "+Inf"
    assert bucket_label(1e9, DURATION_BUCKETS) == "+Inf"
    assert label_bound("+Inf") == math.inf
