"""Listing filters (OGC job-list parameters), request options and callback claims, on
SQLite and PostgreSQL."""

from __future__ import annotations

import random
import time
from datetime import UTC, datetime, timedelta
from typing import Any

from worker.contract import JobStatus
from worker.store.base import JobFilter, JobStore, NewJob


def new_job(process_id: str = "p") -> NewJob:
    return NewJob(process_id=process_id, inputs={"a": 1}, time_limit_s=60.0, max_attempts=3)


def set_times(store: JobStore, job_id: str, **times: Any) -> None:
    """Put known times (epoch seconds) and a status on a job row, for the filters."""
    columns = ", ".join(f"{name} = ?" for name in times)
    with store._write() as conn:  # type: ignore[attr-defined]
        store._exec(  # type: ignore[attr-defined]
            conn, f"UPDATE jobs SET {columns} WHERE job_id = ?", (*times.values(), job_id)
        )


def ids(store: JobStore, where: JobFilter) -> list[str]:
    return [j.job_id for j in store.list_jobs(limit=50, where=where).jobs]


def at(epoch: float) -> datetime:
    return datetime.fromtimestamp(epoch, tz=UTC)


def test_status_and_process_filters_take_several_values(store: JobStore) -> None:
    a = store.create_job(new_job("p"))[0].job_id
    b = store.create_job(new_job("q"))[0].job_id
    c = store.create_job(new_job("r"))[0].job_id
    set_times(store, b, status="running", started=100.0)
    set_times(store, c, status="failed", started=100.0, finished=150.0)
    both = JobFilter(statuses=frozenset({JobStatus.RUNNING, JobStatus.FAILED}))
    assert ids(store, both) == [c, b]
    assert ids(store, JobFilter(process_ids=frozenset({"p", "r"}))) == [c, a]
    assert ids(store, JobFilter(process_ids=frozenset({"p"}), statuses=both.statuses)) == []
    assert ids(store, JobFilter(statuses=frozenset())) == []
    # Today's single-valued parameters still work, alone and with a filter.
    assert [j.job_id for j in store.list_jobs(limit=9, status=JobStatus.ACCEPTED).jobs] == [a]
    assert [j.job_id for j in store.list_jobs(limit=9, process_id="q", where=both).jobs] == [b]


def test_created_bounds_are_inclusive_to_the_printed_microsecond(store: JobStore) -> None:
    jobs = [store.create_job(new_job())[0].job_id for _ in range(3)]
    for job_id, created in zip(jobs, (1000.0, 2000.1234567, 3000.0), strict=True):
        set_times(store, job_id, created=created)
    printed = datetime.fromisoformat(store.get_job(jobs[1]).created.isoformat())  # type: ignore[union-attr]
    assert printed.microsecond == 123457  # what a document shows
    assert ids(store, JobFilter(created_from=printed, created_to=printed)) == [jobs[1]]
    assert ids(store, JobFilter(created_from=at(2000))) == [jobs[2], jobs[1]]
    assert ids(store, JobFilter(created_to=at(2000))) == [jobs[0]]
    assert ids(store, JobFilter(created_from=at(1000), created_to=at(3000))) == jobs[::-1]


def test_created_bounds_match_the_printed_microsecond_of_todays_times(store: JobStore) -> None:
    """Near 1.8e9 s a float is only good to 0.24 us: a bound one microsecond before or
    after what a document prints must still exclude the job, whatever the float's
    sub-microsecond part (random times, and times a hair off each half microsecond)."""
    job_id = store.create_job(new_job())[0].job_id
    rng = random.Random(7)
    times = [rng.uniform(1.7e9, 2.0e9) for _ in range(150)]
    times += [round(t, 6) + d for t in times[:50] for d in (-5e-7, -4.9e-7, 4.9e-7, 5e-7)]
    one = timedelta(microseconds=1)
    for created in times:
        set_times(store, job_id, created=created)
        printed = store.get_job(job_id).created  # type: ignore[union-attr]
        assert ids(store, JobFilter(created_from=printed, created_to=printed)) == [job_id]
        assert ids(store, JobFilter(created_to=printed - one)) == [], created
        assert ids(store, JobFilter(created_from=printed + one)) == [], created


def test_duration_bounds_select_jobs_that_ran(store: JobStore) -> None:
    now = time.time()
    queued = store.create_job(new_job())[0].job_id
    short = store.create_job(new_job())[0].job_id
    long = store.create_job(new_job())[0].job_id
    running = store.create_job(new_job())[0].job_id
    dismissed_queued = store.create_job(new_job())[0].job_id
    set_times(store, short, status="successful", started=100.0, finished=105.0)
    set_times(store, long, status="failed", started=100.0, finished=200.0)
    set_times(store, running, status="running", started=now - 50)
    set_times(store, dismissed_queued, status="dismissed", finished=now)
    assert ids(store, JobFilter(min_duration_s=0)) == [running, long, short]
    assert ids(store, JobFilter(min_duration_s=10)) == [running, long]
    assert ids(store, JobFilter(max_duration_s=60)) == [running, short]
    assert ids(store, JobFilter(min_duration_s=5, max_duration_s=5)) == [short]
    assert queued not in ids(store, JobFilter(max_duration_s=1e9))


def test_request_options_roundtrip(store: JobStore) -> None:
    job = store.create_job(new_job())[0]
    assert store.request_options(job.job_id) == (None, None)
    presentation = {"response": "document", "outputs": {"x": {"transmissionMode": "value"}}}
    store.set_request_options(job.job_id, presentation, {"successUri": "http://h/cb"})
    assert store.request_options(job.job_id) == (presentation, {"successUri": "http://h/cb"})
    assert store.request_options("nope") == (None, None)


def test_callbacks_become_due_once_and_one_sender_claims_each(store: JobStore) -> None:
    subscriber = {
        "successUri": "http://h/ok",
        "inProgressUri": "http://h/run",
        "failedUri": "http://h/ko",
    }
    ok = store.create_job(new_job())[0].job_id
    ko = store.create_job(new_job())[0].job_id
    quiet = store.create_job(new_job())[0].job_id
    for job_id in (ok, ko):
        store.set_request_options(job_id, {"response": "document"}, subscriber)
    store.set_request_options(quiet, {"response": "document"}, None)
    assert store.claim_callbacks(30, 3, 10) == []  # nothing happened yet
    set_times(store, ok, status="running")
    first = store.claim_callbacks(30, 3, 10)
    assert [(c.job_id, c.event, c.uri, c.attempt) for c in first] == [
        (ok, "in-progress", "http://h/run", 1)
    ]
    assert store.claim_callbacks(30, 3, 10) == []  # claimed: no second sender gets it
    assert store.finish_callback(first[0], True, 1.0, 3)
    assert not store.finish_callback(first[0], True, 1.0, 3)  # the claim is spent
    set_times(store, ok, status="successful")
    set_times(store, ko, status="failed")
    set_times(store, quiet, status="successful")
    second = store.claim_callbacks(30, 3, 10)
    assert sorted((c.job_id, c.event) for c in second) == sorted([(ok, "success"), (ko, "failed")])
    for claim in second:
        assert store.finish_callback(claim, True, 1.0, 3)
    assert store.claim_callbacks(30, 3, 10) == []  # delivered callbacks never come back
    log = store.callback_log(ok)
    assert [(e["event"], e["attempts"]) for e in log] == [("in-progress", 1), ("success", 1)]
    assert all(e["delivered"] for e in log) and store.callback_log(quiet) == []


def test_failed_sends_are_retried_then_given_up(store: JobStore) -> None:
    job_id = store.create_job(new_job())[0].job_id
    store.set_request_options(job_id, {}, {"successUri": "http://h/ok"})
    set_times(store, job_id, status="successful")
    for attempt in (1, 2):
        (claim,) = store.claim_callbacks(30, 2, 10)
        assert claim.attempt == attempt
        assert store.finish_callback(claim, False, 0.0, 2)
    assert store.claim_callbacks(30, 2, 10) == []
    (entry,) = store.callback_log(job_id)
    assert entry["attempts"] == 2 and entry["gave_up"] and not entry["delivered"]


def test_an_expired_claim_passes_to_another_sender(store: JobStore) -> None:
    job_id = store.create_job(new_job())[0].job_id
    store.set_request_options(job_id, {}, {"successUri": "http://h/ok"})
    set_times(store, job_id, status="successful")
    (lost,) = store.claim_callbacks(0.05, 3, 10)
    time.sleep(0.1)
    (taken,) = store.claim_callbacks(30, 3, 10)
    assert taken.attempt == 2 and taken.token != lost.token
    assert not store.finish_callback(lost, True, 1.0, 3)  # the stale sender is fenced off
    assert store.finish_callback(taken, True, 1.0, 3)


def test_a_dismissed_job_sends_nothing(store: JobStore) -> None:
    job_id = store.create_job(new_job())[0].job_id
    store.set_request_options(job_id, {}, {"successUri": "http://h/ok", "failedUri": "http://h"})
    store.dismiss(job_id)
    assert store.claim_callbacks(30, 3, 10) == []
    assert store.callback_log(job_id) == []
