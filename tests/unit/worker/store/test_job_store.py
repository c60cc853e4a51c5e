"""The job stores (SQLite and PostgreSQL): claims, leases, fencing, idempotency,
listing, dismissal, migrations."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from worker.contract import Artifact, JobStatus
from worker.errors import IdempotencyConflict
from worker.store import open_store
from worker.store.base import JobStore, NewJob
from worker.store.sql import decode_cursor, encode_cursor


def new_job(process_id: str = "p", max_attempts: int = 3, **kw: object) -> NewJob:
    return NewJob(
        process_id=process_id, inputs={"a": 1}, time_limit_s=60.0, max_attempts=max_attempts, **kw
    )  # type: ignore[arg-type]


def test_create_then_get_roundtrips(store: JobStore) -> None:
    job, created = store.create_job(new_job())
    assert created
    got = store.get_job(job.job_id)
    assert got is not None
    assert got.status is JobStatus.ACCEPTED
    assert got.inputs == {"a": 1}
    assert got.created.tzinfo is not None
    assert store.get_job("nope") is None


def test_initialise_is_idempotent_and_keeps_jobs(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    store.initialise()
    assert store.schema_version() == 9
    assert store.get_job(job.job_id) is not None


def test_claim_takes_oldest_and_only_once(store: JobStore) -> None:
    first, _ = store.create_job(new_job())
    second, _ = store.create_job(new_job())
    c1 = store.claim_next("w1", 10)
    c2 = store.claim_next("w2", 10)
    assert c1 is not None and c2 is not None
    assert c1.job.job_id == first.job_id
    assert c2.job.job_id == second.job_id
    assert c1.job.status is JobStatus.RUNNING and c1.job.attempts == 1
    assert store.claim_next("w3", 10) is None


def test_complete_stores_result_and_artifacts_then_flips(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    claim = store.claim_next("w", 10)
    assert claim is not None
    art = Artifact("a.png", "image/png", b"\x89PNG data", "plot")
    assert store.complete(job.job_id, claim.lease_token, {"x": 1.5}, [art])
    done = store.get_job(job.job_id)
    assert done is not None and done.status is JobStatus.SUCCESSFUL
    assert done.progress == 100
    assert [a.name for a in done.artifacts] == ["a.png"]
    assert store.get_result(job.job_id) == {"x": 1.5}
    got = store.get_artifact(job.job_id, "a.png")
    assert got is not None and got.data == b"\x89PNG data" and got.media_type == "image/png"


def test_stale_lease_cannot_write(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    old = store.claim_next("w-old", 10)
    assert old is not None
    assert store.expire_leases_of("w-old") == 1
    new = store.claim_next("w-new", 10)  # reaps the expired lease, then claims again
    assert new is not None and new.job.job_id == job.job_id and new.job.attempts == 2
    assert not store.report_progress(job.job_id, old.lease_token, 50, "stale")
    assert not store.complete(job.job_id, old.lease_token, {"stale": True}, [])
    assert not store.fail(job.job_id, old.lease_token, {"detail": "stale"})
    assert not store.heartbeat(job.job_id, old.lease_token, 10).owner
    assert store.complete(job.job_id, new.lease_token, {"fresh": True}, [])
    assert store.get_result(job.job_id) == {"fresh": True}


def test_expired_lease_requeues_then_fails_after_max_attempts(store: JobStore) -> None:
    job, _ = store.create_job(new_job(max_attempts=2))
    for attempt in (1, 2):
        claim = store.claim_next(f"w{attempt}", 0.01)
        assert claim is not None and claim.job.attempts == attempt
        time.sleep(0.02)
    assert store.claim_next("w3", 10) is None
    failed = store.get_job(job.job_id)
    assert failed is not None and failed.status is JobStatus.FAILED
    assert failed.error is not None and failed.error["type"] == "worker-lost"
    assert "2 allowed" in failed.error["detail"]


def test_heartbeat_extends_lease_and_reports_dismissal(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    claim = store.claim_next("w", 0.05)
    assert claim is not None
    assert store.heartbeat(job.job_id, claim.lease_token, 10).owner
    time.sleep(0.1)
    assert store.claim_next("w2", 10) is None  # lease was extended, nothing to reap
    store.dismiss(job.job_id)
    ack = store.heartbeat(job.job_id, claim.lease_token, 10)
    assert not ack.owner and ack.status is JobStatus.DISMISSED
    assert not store.complete(job.job_id, claim.lease_token, {"late": 1}, [])


def test_progress_is_fenced_and_clamped(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    claim = store.claim_next("w", 10)
    assert claim is not None
    assert store.report_progress(job.job_id, claim.lease_token, 140, "over")
    got = store.get_job(job.job_id)
    assert got is not None and got.progress == 100 and got.message == "over"


def test_idempotency_same_body_same_job_other_body_conflict(store: JobStore) -> None:
    a, created_a = store.create_job(new_job(idempotency_key="k", request_hash="h1"))
    b, created_b = store.create_job(new_job(idempotency_key="k", request_hash="h1"))
    assert created_a and not created_b and a.job_id == b.job_id
    with pytest.raises(IdempotencyConflict, match="different request body"):
        store.create_job(new_job(idempotency_key="k", request_hash="h2"))


def test_list_newest_first_with_cursor_and_filters(store: JobStore) -> None:
    ids = [store.create_job(new_job("p" if i % 2 else "q"))[0].job_id for i in range(5)]
    page = store.list_jobs(limit=2)
    assert [j.job_id for j in page.jobs] == ids[::-1][:2]
    assert page.next_cursor is not None
    page2 = store.list_jobs(limit=2, cursor=page.next_cursor)
    assert [j.job_id for j in page2.jobs] == ids[::-1][2:4]
    last = store.list_jobs(limit=2, cursor=page2.next_cursor)
    assert [j.job_id for j in last.jobs] == ids[:1] and last.next_cursor is None
    only_p = store.list_jobs(limit=10, process_id="p")
    assert {j.process_id for j in only_p.jobs} == {"p"} and len(only_p.jobs) == 2
    claim = store.claim_next("w", 10)
    assert claim is not None
    running = store.list_jobs(limit=10, status=JobStatus.RUNNING)
    assert [j.job_id for j in running.jobs] == [claim.job.job_id]


def test_cursor_roundtrip_and_garbage() -> None:
    assert decode_cursor(encode_cursor(42)) == 42
    with pytest.raises(ValueError, match="'cursor' parameter"):
        decode_cursor("not-a-cursor")


def test_dismiss_finished_job_drops_results(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    claim = store.claim_next("w", 10)
    assert claim is not None
    store.complete(job.job_id, claim.lease_token, {"x": 1}, [Artifact("a", "text/csv", b"1")])
    dismissed = store.dismiss(job.job_id)
    assert dismissed is not None and dismissed.status is JobStatus.DISMISSED
    assert store.get_result(job.job_id) is None
    assert store.get_artifact(job.job_id, "a") is None
    assert store.dismiss("unknown") is None


def test_worker_registry(store: JobStore) -> None:
    store.register_worker("h:1", "h", 1)
    assert [w.worker_id for w in store.live_workers(5)] == ["h:1"]
    store.unregister_worker("h:1")
    assert store.live_workers(5) == []


def test_result_with_nan_is_refused(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    claim = store.claim_next("w", 10)
    assert claim is not None
    with pytest.raises(ValueError):
        store.complete(job.job_id, claim.lease_token, {"x": float("nan")}, [])
    got = store.get_job(job.job_id)
    assert got is not None and got.status is JobStatus.RUNNING


def test_claim_job_by_id(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    first = store.claim_job(job.job_id, "w1", 10)
    assert first.claim is not None and first.claim.job.attempts == 1
    held = store.claim_job(job.job_id, "w2", 10)
    assert held.claim is None and held.status is JobStatus.RUNNING
    assert held.retry_after_s is not None and 9 < held.retry_after_s <= 10
    store.expire_leases_of("w1")
    second = store.claim_job(job.job_id, "w2", 10)
    assert second.claim is not None and second.claim.job.attempts == 2
    store.complete(job.job_id, second.claim.lease_token, {"ok": 1}, [])
    done = store.claim_job(job.job_id, "w3", 10)
    assert done.claim is None and done.status is JobStatus.SUCCESSFUL
    unknown = store.claim_job("nope", "w3", 10)
    assert unknown.claim is None and unknown.status is None


def test_claim_job_fails_a_job_out_of_attempts(store: JobStore) -> None:
    job, _ = store.create_job(new_job(max_attempts=1))
    assert store.claim_job(job.job_id, "w1", 10).claim is not None
    store.expire_leases_of("w1")
    attempt = store.claim_job(job.job_id, "w2", 10)
    assert attempt.claim is None and attempt.status is JobStatus.FAILED


def test_dispatch_bookkeeping_and_reaping(store: JobStore) -> None:
    a, _ = store.create_job(new_job())
    b, _ = store.create_job(new_job())
    time.sleep(0.3)
    assert store.undispatched(0.2) == [a.job_id, b.job_id]
    assert store.undispatched(60.0) == []
    store.mark_dispatched(a.job_id)
    assert store.undispatched(0.2) == [b.job_id]
    assert store.accepted_count(10) == 2 and store.accepted_count(1) == 1
    claim = store.claim_job(a.job_id, "w", 10).claim
    assert claim is not None
    assert store.accepted_count(10) == 1
    assert store.reap_expired() == []
    store.expire_leases_of("w")
    assert store.reap_expired() == [a.job_id]
    assert a.job_id in store.undispatched(60.0)  # requeued jobs need a new dispatch


def test_overdue_jobs_are_taken_for_a_resend_once(store: JobStore) -> None:
    """``take_overdue`` marks the jobs it returns dispatched: asked again at once, or by
    several sweepers at the same instant, it gives each job out once."""
    import threading

    a, b, c = (store.create_job(new_job())[0].job_id for _ in range(3))
    time.sleep(0.3)
    store.mark_dispatched(c)  # just sent: not overdue
    assert store.take_overdue([a, b, c], 0.2) == [a, b]
    assert store.take_overdue([a, b, c], 0.2) == []  # marked just now
    time.sleep(0.3)
    assert store.claim_job(a, "w", 10).claim is not None  # running: never re-sent
    assert store.take_overdue([a, b, c], 0.2) == [b, c]

    ids = [store.create_job(new_job())[0].job_id for _ in range(20)]
    time.sleep(0.3)
    taken: list[list[str]] = []
    sweepers = [
        threading.Thread(target=lambda: taken.append(store.take_overdue(ids, 0.2)))
        for _ in range(4)
    ]
    for t in sweepers:
        t.start()
    for t in sweepers:
        t.join()
    assert sorted(job_id for share in taken for job_id in share) == sorted(ids)


def test_concurrent_claims_never_share_a_job(store: JobStore) -> None:
    import threading

    ids = {store.create_job(new_job())[0].job_id for _ in range(20)}
    claimed: list[str] = []
    lock = threading.Lock()

    def grab(worker: str) -> None:
        while (claim := store.claim_next(worker, 10)) is not None:
            with lock:
                claimed.append(claim.job.job_id)

    threads = [threading.Thread(target=grab, args=(f"w{i}",)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert sorted(claimed) == sorted(ids)


def test_a_store_from_schema_version_1_is_migrated_forward(tmp_path: Path) -> None:
    """An older store keeps its jobs and gains the new columns (never drop-and-recreate)."""
    import sqlite3

    from worker.store.schema import MIGRATIONS
    from worker.store.sqlite import SqliteJobStore

    path = tmp_path / "old.db"
    conn = sqlite3.connect(path)
    conn.execute("CREATE TABLE schema_version (version INTEGER NOT NULL)")
    for statement in MIGRATIONS[0][1]:
        conn.execute(statement.format(**SqliteJobStore.ddl_types))
    conn.execute("INSERT INTO schema_version VALUES (1)")
    conn.execute(
        "INSERT INTO jobs (job_id, process_id, status, inputs, created, updated, max_attempts,"
        " time_limit_s) VALUES ('old-job', 'p', 'accepted', '{}', 1, 1, 3, 60)"
    )
    conn.commit()
    conn.close()
    store = open_store(f"sqlite:///{path}")
    assert store.schema_version() == len(MIGRATIONS)
    assert store.get_job("old-job") is not None
    assert store.undispatched(1.0) == ["old-job"]  # the column migration 2 added works
