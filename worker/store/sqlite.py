"""The embedded job store: one SQLite file (WAL mode), safe across processes.

Writes run in ``BEGIN IMMEDIATE`` transactions, so claims are serialised by SQLite's
write lock; each thread keeps its own connection.
"""

from __future__ import annotations

import base64
import json
import sqlite3
import threading
import time
import uuid
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from worker.contract import Artifact, ArtifactInfo, JobRecord, JobStatus
from worker.errors import IdempotencyConflict, StoreUnavailable
from worker.store.base import Claim, HeartbeatAck, JobPage, NewJob, WorkerInfo
from worker.store.schema import MIGRATIONS

__all__ = ["SqliteJobStore"]

_ACTIVE = (JobStatus.ACCEPTED.value, JobStatus.RUNNING.value)


def _ts(value: float | None) -> datetime | None:
    return None if value is None else datetime.fromtimestamp(value, tz=UTC)


def encode_cursor(seq: int) -> str:
    return base64.urlsafe_b64encode(f"seq:{seq}".encode()).decode().rstrip("=")


def decode_cursor(cursor: str) -> int:
    try:
        padded = cursor + "=" * (-len(cursor) % 4)
        text = base64.urlsafe_b64decode(padded.encode()).decode()
        prefix, _, number = text.partition(":")
        if prefix != "seq":
            raise ValueError(cursor)
        return int(number)
    except (ValueError, UnicodeDecodeError) as exc:
        raise ValueError(
            f"The 'cursor' parameter is not a cursor this service issued: {cursor!r}"
        ) from exc


class SqliteJobStore:
    """A :class:`worker.store.base.JobStore` on a SQLite file."""

    def __init__(self, path: Path | str) -> None:
        self.path = Path(path)
        self._local = threading.local()

    @classmethod
    def from_url(cls, url: str) -> SqliteJobStore:
        prefix = "sqlite:///"
        if not url.startswith(prefix):
            raise ValueError(f"The 'store_url' must start with {prefix!r}. Got {url!r} instead.")
        return cls(Path(url[len(prefix) :]))

    # -- connections ----------------------------------------------------------------
    def _conn(self) -> sqlite3.Connection:
        conn: sqlite3.Connection | None = getattr(self._local, "conn", None)
        if conn is None:
            try:
                self.path.parent.mkdir(parents=True, exist_ok=True)
                conn = sqlite3.connect(self.path, timeout=30.0, isolation_level=None)
                conn.row_factory = sqlite3.Row
                conn.execute("PRAGMA journal_mode=WAL")
                conn.execute("PRAGMA synchronous=NORMAL")
                conn.execute("PRAGMA foreign_keys=ON")
            except (sqlite3.Error, OSError) as exc:
                raise StoreUnavailable(f"Cannot open the job store at {self.path}: {exc}") from exc
            self._local.conn = conn
        return conn

    @contextmanager
    def _write(self) -> Iterator[sqlite3.Connection]:
        conn = self._conn()
        conn.execute("BEGIN IMMEDIATE")
        try:
            yield conn
        except BaseException:
            conn.execute("ROLLBACK")
            raise
        else:
            conn.execute("COMMIT")

    def close(self) -> None:
        conn = getattr(self._local, "conn", None)
        if conn is not None:
            conn.close()
            self._local.conn = None

    # -- schema ---------------------------------------------------------------------
    def initialise(self) -> None:
        with self._write() as conn:
            conn.execute("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)")
            row = conn.execute("SELECT MAX(version) AS v FROM schema_version").fetchone()
            current = row["v"] or 0
            for version, statements in MIGRATIONS:
                if version <= current:
                    continue
                for statement in statements:
                    conn.execute(statement)
                conn.execute("INSERT INTO schema_version (version) VALUES (?)", (version,))

    def ping(self) -> None:
        try:
            self._conn().execute("SELECT 1 FROM jobs LIMIT 1").fetchall()
        except sqlite3.Error as exc:
            raise StoreUnavailable(f"The job store at {self.path} does not answer: {exc}") from exc

    # -- records --------------------------------------------------------------------
    def _artifact_infos(self, conn: sqlite3.Connection, job_id: str) -> tuple[ArtifactInfo, ...]:
        rows = conn.execute(
            "SELECT name, media_type, size, title FROM artifacts WHERE job_id = ? ORDER BY ord",
            (job_id,),
        ).fetchall()
        return tuple(ArtifactInfo(r["name"], r["media_type"], r["size"], r["title"]) for r in rows)

    def _record(self, conn: sqlite3.Connection, row: sqlite3.Row) -> JobRecord:
        status = JobStatus(row["status"])
        artifacts = (
            self._artifact_infos(conn, row["job_id"]) if status is JobStatus.SUCCESSFUL else ()
        )
        created = _ts(row["created"])
        updated = _ts(row["updated"])
        assert created is not None and updated is not None
        return JobRecord(
            job_id=row["job_id"],
            process_id=row["process_id"],
            status=status,
            inputs=json.loads(row["inputs"]),
            created=created,
            updated=updated,
            progress=row["progress"],
            message=row["message"],
            started=_ts(row["started"]),
            finished=_ts(row["finished"]),
            attempts=row["attempts"],
            max_attempts=row["max_attempts"],
            time_limit_s=row["time_limit_s"],
            error=json.loads(row["error"]) if row["error"] else None,
            worker_id=row["worker_id"],
            artifacts=artifacts,
        )

    def create_job(self, new: NewJob) -> tuple[JobRecord, bool]:
        now = time.time()
        with self._write() as conn:
            if new.idempotency_key is not None:
                row = conn.execute(
                    "SELECT * FROM jobs WHERE idempotency_key = ?", (new.idempotency_key,)
                ).fetchone()
                if row is not None:
                    if row["request_hash"] != new.request_hash:
                        raise IdempotencyConflict(
                            "This Idempotency-Key was already used with a different request "
                            f"body (job {row['job_id']}); use a new key for a new request."
                        )
                    return self._record(conn, row), False
            job_id = str(uuid.uuid4())
            conn.execute(
                """INSERT INTO jobs (job_id, process_id, status, inputs, created, updated,
                       max_attempts, time_limit_s, idempotency_key, request_hash, message)
                   VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)""",
                (
                    job_id,
                    new.process_id,
                    JobStatus.ACCEPTED.value,
                    json.dumps(dict(new.inputs)),
                    now,
                    now,
                    new.max_attempts,
                    new.time_limit_s,
                    new.idempotency_key,
                    new.request_hash,
                    "queued",
                ),
            )
            row = conn.execute("SELECT * FROM jobs WHERE job_id = ?", (job_id,)).fetchone()
            return self._record(conn, row), True

    def get_job(self, job_id: str) -> JobRecord | None:
        conn = self._conn()
        row = conn.execute("SELECT * FROM jobs WHERE job_id = ?", (job_id,)).fetchone()
        return None if row is None else self._record(conn, row)

    def list_jobs(
        self,
        *,
        limit: int,
        cursor: str | None = None,
        status: JobStatus | None = None,
        process_id: str | None = None,
    ) -> JobPage:
        clauses: list[str] = []
        params: list[Any] = []
        if cursor is not None:
            clauses.append("seq < ?")
            params.append(decode_cursor(cursor))
        if status is not None:
            clauses.append("status = ?")
            params.append(status.value)
        if process_id is not None:
            clauses.append("process_id = ?")
            params.append(process_id)
        where = f"WHERE {' AND '.join(clauses)}" if clauses else ""
        conn = self._conn()
        rows = conn.execute(
            f"SELECT * FROM jobs {where} ORDER BY seq DESC LIMIT ?", (*params, limit + 1)
        ).fetchall()
        more = len(rows) > limit
        rows = rows[:limit]
        next_cursor = encode_cursor(rows[-1]["seq"]) if more and rows else None
        return JobPage([self._record(conn, r) for r in rows], next_cursor)

    # -- the worker's side ----------------------------------------------------------
    def _reap_expired(self, conn: sqlite3.Connection, now: float) -> None:
        """Requeue running jobs whose lease expired; fail those out of attempts."""
        expired = conn.execute(
            "SELECT job_id, attempts, max_attempts, worker_id FROM jobs "
            "WHERE status = ? AND lease_expires < ?",
            (JobStatus.RUNNING.value, now),
        ).fetchall()
        for row in expired:
            lost = f"worker {row['worker_id']} was lost during attempt {row['attempts']}"
            if row["attempts"] >= row["max_attempts"]:
                error = {
                    "type": "worker-lost",
                    "title": "Worker lost",
                    "detail": f"{lost}; no attempts left ({row['max_attempts']} allowed).",
                }
                conn.execute(
                    "UPDATE jobs SET status = ?, error = ?, finished = ?, updated = ?, "
                    "lease_token = NULL, lease_expires = NULL, message = ? WHERE job_id = ?",
                    (JobStatus.FAILED.value, json.dumps(error), now, now, error["detail"],
                     row["job_id"]),
                )
            else:
                conn.execute(
                    "UPDATE jobs SET status = ?, updated = ?, lease_token = NULL, "
                    "lease_expires = NULL, progress = 0, message = ? WHERE job_id = ?",
                    (JobStatus.ACCEPTED.value, now, f"{lost}; queued for a retry",
                     row["job_id"]),
                )

    def claim_next(self, worker_id: str, lease_s: float) -> Claim | None:
        now = time.time()
        token = uuid.uuid4().hex
        with self._write() as conn:
            self._reap_expired(conn, now)
            row = conn.execute(
                "SELECT job_id FROM jobs WHERE status = ? ORDER BY seq LIMIT 1",
                (JobStatus.ACCEPTED.value,),
            ).fetchone()
            if row is None:
                return None
            conn.execute(
                """UPDATE jobs SET status = ?, lease_token = ?, lease_expires = ?,
                       worker_id = ?, attempts = attempts + 1, attempt_started = ?,
                       started = COALESCE(started, ?), updated = ?, progress = 0,
                       message = 'running attempt ' || (attempts + 1)
                   WHERE job_id = ?""",
                (JobStatus.RUNNING.value, token, now + lease_s, worker_id, now, now, now,
                 row["job_id"]),
            )
            full = conn.execute("SELECT * FROM jobs WHERE job_id = ?", (row["job_id"],)).fetchone()
            return Claim(self._record(conn, full), token)

    def heartbeat(self, job_id: str, lease_token: str, lease_s: float) -> HeartbeatAck:
        now = time.time()
        with self._write() as conn:
            row = conn.execute(
                "SELECT status, lease_token FROM jobs WHERE job_id = ?", (job_id,)
            ).fetchone()
            if row is None:
                return HeartbeatAck(False, None)
            status = JobStatus(row["status"])
            owner = row["lease_token"] == lease_token and status is JobStatus.RUNNING
            if owner:
                conn.execute(
                    "UPDATE jobs SET lease_expires = ? WHERE job_id = ?", (now + lease_s, job_id)
                )
            return HeartbeatAck(owner, status)

    def report_progress(self, job_id: str, lease_token: str, percent: float, message: str) -> bool:
        with self._write() as conn:
            cur = conn.execute(
                "UPDATE jobs SET progress = ?, message = ?, updated = ? "
                "WHERE job_id = ? AND lease_token = ? AND status = ?",
                (max(0.0, min(100.0, percent)), message, time.time(), job_id, lease_token,
                 JobStatus.RUNNING.value),
            )
            return cur.rowcount == 1

    def complete(
        self,
        job_id: str,
        lease_token: str,
        result: Mapping[str, Any],
        artifacts: Sequence[Artifact],
    ) -> bool:
        now = time.time()
        payload = json.dumps(result, allow_nan=False)
        with self._write() as conn:
            row = conn.execute(
                "SELECT 1 FROM jobs WHERE job_id = ? AND lease_token = ? AND status = ?",
                (job_id, lease_token, JobStatus.RUNNING.value),
            ).fetchone()
            if row is None:
                return False
            conn.execute("DELETE FROM artifacts WHERE job_id = ?", (job_id,))
            conn.executemany(
                "INSERT INTO artifacts (job_id, name, media_type, title, size, data, ord) "
                "VALUES (?, ?, ?, ?, ?, ?, ?)",
                [
                    (job_id, a.name, a.media_type, a.title, len(a.data), a.data, i)
                    for i, a in enumerate(artifacts)
                ],
            )
            conn.execute(
                "UPDATE jobs SET result = ?, status = ?, progress = 100, finished = ?, "
                "updated = ?, message = 'finished', lease_token = NULL, lease_expires = NULL "
                "WHERE job_id = ?",
                (payload, JobStatus.SUCCESSFUL.value, now, now, job_id),
            )
            return True

    def fail(self, job_id: str, lease_token: str, error: Mapping[str, Any]) -> bool:
        now = time.time()
        with self._write() as conn:
            cur = conn.execute(
                "UPDATE jobs SET status = ?, error = ?, finished = ?, updated = ?, message = ?, "
                "lease_token = NULL, lease_expires = NULL "
                "WHERE job_id = ? AND lease_token = ? AND status = ?",
                (JobStatus.FAILED.value, json.dumps(dict(error)), now, now,
                 str(error.get("detail", "failed")), job_id, lease_token,
                 JobStatus.RUNNING.value),
            )
            return cur.rowcount == 1

    def expire_leases_of(self, worker_id: str) -> int:
        with self._write() as conn:
            cur = conn.execute(
                "UPDATE jobs SET lease_expires = 0 WHERE worker_id = ? AND status = ?",
                (worker_id, JobStatus.RUNNING.value),
            )
            return cur.rowcount

    def dismiss(self, job_id: str) -> JobRecord | None:
        now = time.time()
        with self._write() as conn:
            row = conn.execute("SELECT status FROM jobs WHERE job_id = ?", (job_id,)).fetchone()
            if row is None:
                return None
            if row["status"] != JobStatus.DISMISSED.value:
                conn.execute("DELETE FROM artifacts WHERE job_id = ?", (job_id,))
                conn.execute(
                    "UPDATE jobs SET status = ?, result = NULL, finished = COALESCE(finished, ?),"
                    " updated = ?, message = 'dismissed by the client' WHERE job_id = ?",
                    (JobStatus.DISMISSED.value, now, now, job_id),
                )
            full = conn.execute("SELECT * FROM jobs WHERE job_id = ?", (job_id,)).fetchone()
            return self._record(conn, full)

    def get_result(self, job_id: str) -> Mapping[str, Any] | None:
        row = self._conn().execute(
            "SELECT result FROM jobs WHERE job_id = ? AND status = ?",
            (job_id, JobStatus.SUCCESSFUL.value),
        ).fetchone()
        return None if row is None or row["result"] is None else json.loads(row["result"])

    def get_artifact(self, job_id: str, name: str) -> Artifact | None:
        row = self._conn().execute(
            "SELECT name, media_type, data, title FROM artifacts WHERE job_id = ? AND name = ?",
            (job_id, name),
        ).fetchone()
        if row is None:
            return None
        return Artifact(row["name"], row["media_type"], bytes(row["data"]), row["title"])

    # -- worker registry ------------------------------------------------------------
    def register_worker(self, worker_id: str, host: str, pid: int) -> None:
        now = time.time()
        with self._write() as conn:
            conn.execute(
                "INSERT OR REPLACE INTO workers (worker_id, host, pid, started, heartbeat) "
                "VALUES (?, ?, ?, ?, ?)",
                (worker_id, host, pid, now, now),
            )

    def worker_heartbeat(self, worker_id: str) -> None:
        with self._write() as conn:
            conn.execute(
                "UPDATE workers SET heartbeat = ? WHERE worker_id = ?", (time.time(), worker_id)
            )

    def unregister_worker(self, worker_id: str) -> None:
        with self._write() as conn:
            conn.execute("DELETE FROM workers WHERE worker_id = ?", (worker_id,))

    def live_workers(self, within_s: float) -> list[WorkerInfo]:
        rows = self._conn().execute(
            "SELECT * FROM workers WHERE heartbeat >= ? ORDER BY started",
            (time.time() - within_s,),
        ).fetchall()
        return [
            WorkerInfo(r["worker_id"], r["host"], r["pid"], r["started"], r["heartbeat"])
            for r in rows
        ]
