"""Retention (worker.store.retention and the sweeper), on SQLite and PostgreSQL: a
finished job expires after its retention, its row, index, callbacks and bytes (files,
chunk rows) are deleted in batches, and a tombstone answers for its grace period."""

from __future__ import annotations

import time
from typing import Any

from worker.contract import Artifact, JobStatus
from worker.retention import RetentionSweeper
from worker.settings import WorkerSettings
from worker.store.base import JobStore, NewJob
from worker.store.postgres import PostgresJobStore
from worker.store.sqlite import SqliteJobStore


def finished_job(store: JobStore, owner: str = "", retention_s: float = 0.3) -> str:
    job, _ = store.create_job(
        NewJob("p", {}, time_limit_s=60, max_attempts=3, owner=owner, retention_s=retention_s)
    )
    claim = store.claim_next("w", 30)
    assert claim is not None and claim.job.job_id == job.job_id
    artifacts = [
        Artifact("a.png", "image/png", b"\x89PNG" * 1000),
        Artifact("b.csv", "text/csv", b"x,y\n"),
    ]
    assert store.complete(job.job_id, claim.lease_token, {"ok": True}, artifacts)
    return job.job_id


def stored_bytes(store: JobStore, job_id: str) -> int:
    """How many artifact files (SQLite) or chunk rows (PostgreSQL) the job has."""
    if isinstance(store, SqliteJobStore):
        folder = store.files.root / job_id
        return sum(1 for p in folder.rglob("*") if p.is_file()) if folder.exists() else 0
    assert isinstance(store, PostgresJobStore)
    row: Any = store._one(
        store._conn(), "SELECT COUNT(*) AS n FROM artifact_chunks WHERE job_id = ?", (job_id,)
    )
    return int(row["n"])


def rows_of(store: Any, table: str, job_id: str) -> int:
    query = f"SELECT COUNT(*) AS n FROM {table} WHERE job_id = ?"
    return int(store._one(store._conn(), query, (job_id,))["n"])


def test_a_finished_job_carries_when_it_expires(store: JobStore) -> None:
    job_id = finished_job(store, retention_s=3600)
    job = store.get_job(job_id)
    assert job is not None and job.finished is not None and job.expires is not None
    assert (job.expires - job.finished).total_seconds() == 3600
    waiting, _ = store.create_job(NewJob("p", {}, time_limit_s=60, max_attempts=3))
    assert waiting.expires is None  # unfinished jobs never expire
    dismissed = store.dismiss(waiting.job_id)
    assert dismissed is not None and dismissed.expires is not None


def test_expired_jobs_go_with_their_files_and_leave_a_tombstone(store: JobStore) -> None:
    job_id = finished_job(store, owner="alice", retention_s=0.3)
    store.set_request_options(job_id, {"response": "document"}, {"successUri": "http://x/"})
    keep = finished_job(store, owner="alice", retention_s=3600)
    assert stored_bytes(store, job_id) == 2 and rows_of(store, "artifact_index", job_id) == 2
    assert store.expire_jobs(10) == []  # not yet
    time.sleep(0.35)
    assert store.expire_jobs(10) == [job_id]
    assert store.get_job(job_id) is None and store.get_result(job_id) is None
    assert stored_bytes(store, job_id) == 0
    assert rows_of(store, "artifact_index", job_id) == 0
    assert rows_of(store, "callbacks", job_id) == 0
    expired = store.expired_at(job_id)
    assert expired is not None and abs(expired.timestamp() - time.time()) < 5
    assert store.expired_at(job_id, owner="alice") == expired
    assert store.expired_at(job_id, owner="bob") is None  # another owner learns nothing
    kept = store.get_job(keep)
    assert kept is not None and kept.status is JobStatus.SUCCESSFUL
    assert stored_bytes(store, keep) == 2
    # The tombstone stays as long as the job was kept, then the ID is unknown.
    assert store.forget_expired(10) == 0
    time.sleep(0.35)
    assert store.forget_expired(10) == 1
    assert store.expired_at(job_id) is None


def test_the_sweeper_deletes_in_batches(store: JobStore, monkeypatch: Any) -> None:
    import worker.retention as retention

    monkeypatch.setattr(retention, "BATCH", 2)
    job_ids = [finished_job(store, retention_s=0.1) for _ in range(5)]
    time.sleep(0.15)
    batches: list[int] = []
    expire = store.expire_jobs

    def counted(limit: int) -> list[str]:
        done = expire(limit)
        batches.append(len(done))
        return done

    monkeypatch.setattr(store, "expire_jobs", counted)
    sweeper = RetentionSweeper(WorkerSettings(), store)
    assert sweeper.sweep() == 5 and batches == [2, 2, 1]
    assert all(store.get_job(j) is None and stored_bytes(store, j) == 0 for j in job_ids)
