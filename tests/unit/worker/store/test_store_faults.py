"""The stores under trouble: concurrency, locks, corruption, stale attempts, big
artifacts, ambiguous commits, and the migration of version-2 stores."""

from __future__ import annotations

import hashlib
import sqlite3
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from tests.services import postgres_schema
from worker.contract import Artifact, JobStatus
from worker.errors import StorageError, StoreUnavailable
from worker.request_hash import request_hash
from worker.store import open_store
from worker.store.base import JobStore, NewJob
from worker.store.schema import MIGRATIONS
from worker.store.sqlite import SqliteJobStore


def new_job(**kw: object) -> NewJob:
    return NewJob(process_id="p", inputs={"a": 1}, time_limit_s=60.0, max_attempts=3, **kw)  # type: ignore[arg-type]


def test_concurrent_idempotent_creates_make_one_job(store: JobStore) -> None:
    """20 simultaneous submits with one key: one job, the same answer for all, no error
    (PostgreSQL used to answer UniqueViolation for up to 19 of them)."""
    barrier = threading.Barrier(20)

    def create(_: int) -> tuple[str, bool]:
        barrier.wait()
        job, created = store.create_job(new_job(idempotency_key="k", request_hash="h"))
        return job.job_id, created

    with ThreadPoolExecutor(20) as pool:
        outcomes = list(pool.map(create, range(20)))
    assert len({job_id for job_id, _ in outcomes}) == 1
    assert sum(created for _, created in outcomes) == 1


def claim_twice(store: JobStore) -> tuple[str, str, str]:
    """A job whose first attempt lost its lease to a second: (job, stale, current)."""
    job, _ = store.create_job(new_job())
    first = store.claim_next("w1", 0.05)
    assert first is not None
    time.sleep(0.1)
    assert store.reap_expired() == [job.job_id]
    second = store.claim_next("w2", 30)
    assert second is not None and second.job.attempts == 2
    return job.job_id, first.lease_token, second.lease_token


def test_a_stale_attempt_never_replaces_committed_artifacts(store: JobStore) -> None:
    job_id, stale, current = claim_twice(store)
    assert store.complete(job_id, current, {"v": "new"}, [Artifact("a.csv", "text/csv", b"new")])
    assert not store.complete(job_id, stale, {"v": "old"}, [Artifact("a.csv", "text/csv", b"old")])
    got = store.get_artifact(job_id, "a.csv")
    assert got is not None and got.data == b"new"
    assert store.get_result(job_id) == {"v": "new"}
    if isinstance(store, SqliteJobStore):  # the stale attempt's folder is gone
        assert [p.name for p in (store.files.root / job_id).iterdir()] == ["2"]


def test_a_stale_attempt_finishing_first_leaves_nothing(store: JobStore) -> None:
    job_id, stale, current = claim_twice(store)
    assert not store.complete(job_id, stale, {"v": "old"}, [Artifact("a.csv", "text/csv", b"old")])
    assert store.complete(job_id, current, {"v": "new"}, [Artifact("a.csv", "text/csv", b"new")])
    got = store.get_artifact(job_id, "a.csv")
    assert got is not None and got.data == b"new"


def test_big_artifacts_are_chunked_and_streamed(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    claim = store.claim_next("w", 30)
    assert claim is not None
    data = bytes(range(256)) * (10 * 1024 + 7)  # 2.5 MiB and a bit
    assert store.complete(job.job_id, claim.lease_token, {}, [Artifact("big.npz", "x", data)])
    stored = store.artifact(job.job_id, "big.npz")
    assert stored is not None
    assert stored.info.size == len(data)
    assert stored.etag == hashlib.sha256(data).hexdigest()
    chunks = list(store.artifact_chunks(job.job_id, stored))
    assert len(chunks) == 3 and max(len(c) for c in chunks) == 1 << 20
    assert b"".join(chunks) == data


def test_a_retried_completion_recognises_its_own_commit(store: JobStore) -> None:
    """After an ambiguous commit (the connection dropped as it committed) the retry
    must not report the job lost."""
    job, _ = store.create_job(new_job())
    claim = store.claim_next("w", 30)
    assert claim is not None
    art = [Artifact("a.txt", "text/plain", b"x")]
    assert store.complete(job.job_id, claim.lease_token, {"x": 1}, art)
    assert store.complete(job.job_id, claim.lease_token, {"x": 1}, art)
    done = store.get_job(job.job_id)
    assert done is not None and done.status is JobStatus.SUCCESSFUL


def test_artifact_names_must_be_plain_file_names(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    claim = store.claim_next("w", 30)
    assert claim is not None
    with pytest.raises(ValueError, match="plain file name"):
        store.complete(job.job_id, claim.lease_token, {}, [Artifact("../x", "text/plain", b"")])


def test_dismissal_removes_the_artifact_bytes(store: JobStore) -> None:
    job, _ = store.create_job(new_job())
    claim = store.claim_next("w", 30)
    assert claim is not None
    store.complete(job.job_id, claim.lease_token, {}, [Artifact("a", "text/plain", b"abc")])
    store.dismiss(job.job_id)
    assert store.artifact(job.job_id, "a") is None
    if isinstance(store, SqliteJobStore):
        assert not (store.files.root / job.job_id).exists()


def hold_write_lock(path: Path, seconds: float) -> threading.Thread:
    """Another connection holds SQLite's write lock (as a backup or a stuck process
    would) for ``seconds``."""
    started = threading.Event()

    def hold() -> None:
        conn = sqlite3.connect(path, isolation_level=None)
        conn.execute("BEGIN IMMEDIATE")
        started.set()
        time.sleep(seconds)
        conn.execute("ROLLBACK")
        conn.close()

    thread = threading.Thread(target=hold, daemon=True)
    thread.start()
    started.wait(5)
    return thread


def test_a_lock_shorter_than_the_bound_is_waited_out(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'jobs.db'}", retry_s=5.0)
    holder = hold_write_lock(tmp_path / "jobs.db", 1.5)
    job, created = store.create_job(new_job())
    assert created and store.get_job(job.job_id) is not None
    holder.join()


def test_a_lock_held_past_the_bound_is_store_unavailable(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'jobs.db'}", retry_s=1.0)
    holder = hold_write_lock(tmp_path / "jobs.db", 4.0)
    started = time.monotonic()
    with pytest.raises(StoreUnavailable, match="busy or unreachable") as info:
        store.create_job(new_job())
    assert time.monotonic() - started < 3.5
    assert info.value.extra["retry_after_s"] >= 1
    with pytest.raises(StoreUnavailable):
        store.check_storage()
    holder.join()
    store.check_storage()  # and it recovers


def test_a_corrupted_file_is_a_storage_error(tmp_path: Path) -> None:
    path = tmp_path / "jobs.db"
    path.write_bytes(b"this is not a database" * 512)
    with pytest.raises(StorageError, match="cannot be used"):
        open_store(f"sqlite:///{path}", retry_s=1.0)


@pytest.mark.parametrize("dialect", ["sqlite", "postgresql"])
def test_a_version_2_store_moves_artifacts_out_and_rehashes(dialect: str, tmp_path: Path) -> None:
    """Blobs leave the job row for files (SQLite) or chunks (PostgreSQL); idempotency
    hashes are recomputed in canonical form; nothing is lost."""
    inputs = {"b": 2.0, "a": [1, 2.5]}
    if dialect == "sqlite":
        url = f"sqlite:///{tmp_path / 'old.db'}"
        conn = sqlite3.connect(tmp_path / "old.db")
        types = SqliteJobStore.ddl_types
        run = conn.execute
        blob: object = sqlite3.Binary(b"\x89PNG old blob")
        finish = conn.commit
        migrate_and_check(url, run, types, blob, finish, inputs)
        conn.close()
        return
    import psycopg

    from worker.store.postgres import PostgresJobStore

    with postgres_schema() as url, psycopg.connect(url, autocommit=True) as pg:
        migrate_and_check(
            url,
            lambda q, p=(): pg.execute(q.replace("?", "%s"), p),
            PostgresJobStore.ddl_types,
            b"\x89PNG old blob",
            lambda: None,
            inputs,
        )


def migrate_and_check(url, run, types, blob, finish, inputs) -> None:  # type: ignore[no-untyped-def]
    import json

    run("CREATE TABLE schema_version (version INTEGER NOT NULL)")
    for version, statements in MIGRATIONS[:2]:
        for statement in statements:
            run(statement.format(**types))
        run("INSERT INTO schema_version VALUES (?)", (version,))
    run(
        "INSERT INTO jobs (job_id, process_id, status, inputs, created, updated, max_attempts,"
        " time_limit_s, attempts, result, idempotency_key, request_hash) VALUES "
        "('old-job', 'p', 'successful', ?, 1, 1, 3, 60, 2, '{\"x\": 1}', 'key', 'raw-hash')",
        (json.dumps(inputs),),
    )
    run(
        "INSERT INTO artifacts (job_id, name, media_type, title, size, data, ord) "
        "VALUES ('old-job', 'plot.png', 'image/png', 'a plot', 13, ?, 0)",
        (blob,),
    )
    finish()
    store = open_store(url)
    try:
        assert store.schema_version() == len(MIGRATIONS)
        job = store.get_job("old-job")
        assert job is not None and [a.name for a in job.artifacts] == ["plot.png"]
        got = store.get_artifact("old-job", "plot.png")
        assert got is not None and got.data == b"\x89PNG old blob" and got.title == "a plot"
        # The key now matches a resubmission of the same inputs written otherwise.
        again, created = store.create_job(
            NewJob(
                "p",
                inputs,
                60,
                3,
                idempotency_key="key",
                request_hash=request_hash("p", {"a": [1.0, 2.5], "b": 2}),
            )
        )
        assert not created and again.job_id == "old-job"
    finally:
        store.close()
