"""Leases: taking a claimed job, renewing and reaping leases, and the writes an
attempt fences with its lease token (progress, failure).  Which job a claim takes is
:mod:`worker.store.scheduling`'s."""

from __future__ import annotations

import json
import time
import uuid
from collections.abc import Mapping
from typing import Any

from worker.contract import JobStatus
from worker.store.connector import Conn, Row, SqlConnector
from worker.store.records import Claim, HeartbeatAck
from worker.store.retry import retrying

__all__ = ["Leases"]

_RUNNING = JobStatus.RUNNING.value
_ACCEPTED = JobStatus.ACCEPTED.value


class Leases(SqlConnector):
    """The lease half of :class:`worker.store.sql.SqlJobStore`."""

    # -- leases -----------------------------------------------------------------------
    def _reap(self, conn: Conn, row: Row, now: float) -> JobStatus:
        """Requeue one running job whose lease expired, or fail it if out of attempts
        (``row``: its job_id, process_id, attempts, max_attempts, worker_id, started)."""
        lost = f"worker {row['worker_id']} was lost during attempt {row['attempts']}"
        if row["attempts"] >= row["max_attempts"]:
            error = {
                "type": "worker-lost",
                "title": "Worker lost",
                "detail": f"{lost}; no attempts left ({row['max_attempts']} allowed).",
            }
            self._exec(
                conn,
                "UPDATE jobs SET status = ?, error = ?, finished = ?, updated = ?, "
                "expires = ? + retention_s, lease_token = NULL, lease_expires = NULL, "
                "message = ? WHERE job_id = ?",
                (
                    JobStatus.FAILED.value,
                    json.dumps(error),
                    now,
                    now,
                    now,
                    error["detail"],
                    row["job_id"],
                ),
            )
            self._tally_finish(conn, row, JobStatus.FAILED, now)
            self._child_ended(conn, row["job_id"], JobStatus.FAILED, error, now)
            return JobStatus.FAILED
        self._exec(
            conn,
            "UPDATE jobs SET status = ?, updated = ?, lease_token = NULL, lease_expires = NULL,"
            " progress = 0, dispatched = 0, message = ? WHERE job_id = ?",
            (_ACCEPTED, now, f"{lost}; queued for a retry", row["job_id"]),
        )
        return JobStatus.ACCEPTED

    @retrying
    def reap_expired(self) -> list[str]:
        """Requeue (or fail) every running job whose lease expired; the requeued IDs."""
        now = time.time()
        with self._write() as conn:
            # In process order: the tallies' rows are then locked in one order.
            rows = self._all(
                conn,
                "SELECT job_id, process_id, attempts, max_attempts, worker_id, started "
                "FROM jobs WHERE status = ? AND lease_expires < ? "
                "AND COALESCE(phase, '') <> 'waiting' ORDER BY process_id, job_id"
                f"{self.lock_clause}",
                (_RUNNING, now),
            )
            outcomes = {r["job_id"]: self._reap(conn, r, now) for r in rows}
        for job_id, status in outcomes.items():
            if status is JobStatus.FAILED:
                self._discard_artifact_data(job_id)
        return [j for j, status in outcomes.items() if status is JobStatus.ACCEPTED]

    def _take(
        self, conn: Conn, job_id: str, worker_id: str, lease_s: float, before: Row = None
    ) -> Claim:
        """Start an attempt on a job the transaction has locked (``before``: its row
        with process_id, created, started and attempts, if already read)."""
        now = time.time()
        token = uuid.uuid4().hex
        self._tally_claim(conn, job_id, now, before)
        rows = self._all(
            conn,
            """UPDATE jobs SET status = ?, lease_token = ?, lease_expires = ?,
                   worker_id = ?, attempts = attempts + 1, attempt_started = ?,
                   started = COALESCE(started, ?), updated = ?, progress = 0,
                   message = 'running attempt ' || (attempts + 1)
               WHERE job_id = ? RETURNING *""",
            (_RUNNING, token, now + lease_s, worker_id, now, now, now, job_id),
        )
        return Claim(self._record(conn, rows[0]), token)

    @retrying
    def heartbeat(self, job_id: str, lease_token: str, lease_s: float) -> HeartbeatAck:
        with self._write() as conn:
            cur = self._exec(
                conn,
                "UPDATE jobs SET lease_expires = ? WHERE job_id = ? AND lease_token = ? "
                "AND status = ?",
                (time.time() + lease_s, job_id, lease_token, _RUNNING),
            )
            if cur.rowcount == 1:
                return HeartbeatAck(True, JobStatus.RUNNING)
            row = self._one(conn, "SELECT status FROM jobs WHERE job_id = ?", (job_id,))
            return HeartbeatAck(False, None if row is None else JobStatus(row["status"]))

    @retrying
    def report_progress(self, job_id: str, lease_token: str, percent: float, message: str) -> bool:
        with self._write() as conn:
            cur = self._exec(
                conn,
                "UPDATE jobs SET progress = ?, message = ?, updated = ? "
                "WHERE job_id = ? AND lease_token = ? AND status = ?",
                (
                    max(0.0, min(100.0, percent)),
                    message,
                    time.time(),
                    job_id,
                    lease_token,
                    _RUNNING,
                ),
            )
            return bool(cur.rowcount == 1)

    @retrying
    def fail(self, job_id: str, lease_token: str, error: Mapping[str, Any]) -> bool:
        now = time.time()
        with self._write() as conn:
            row = self._one(
                conn,
                "SELECT status, process_id, started FROM jobs WHERE job_id = ? AND "
                f"lease_token = ?{self.lock_clause}",
                (job_id, lease_token),
            )
            if row is None or row["status"] not in (_RUNNING, JobStatus.FAILED.value):
                return False
            if row["status"] == _RUNNING:  # (failed: our own earlier, ambiguous commit)
                # The token stays on the row so a retried call recognises its commit.
                self._exec(
                    conn,
                    "UPDATE jobs SET status = ?, error = ?, finished = ?, updated = ?, "
                    "expires = ? + retention_s, message = ?, lease_expires = NULL "
                    "WHERE job_id = ?",
                    (
                        JobStatus.FAILED.value,
                        json.dumps(dict(error)),
                        now,
                        now,
                        now,
                        str(error.get("detail", "failed")),
                        job_id,
                    ),
                )
                self._tally_finish(conn, row, JobStatus.FAILED, now)
                self._child_ended(conn, job_id, JobStatus.FAILED, error, now)
        self._discard_artifact_data(job_id)
        return True

    @retrying
    def expire_leases_of(self, worker_id: str) -> int:
        with self._write() as conn:
            cur = self._exec(
                conn,
                # Not a study parked while its chunks run: it holds no lease (fan_out).
                "UPDATE jobs SET lease_expires = 0 WHERE worker_id = ? AND status = ? "
                "AND COALESCE(phase, '') <> 'waiting'",
                (worker_id, _RUNNING),
            )
            return int(cur.rowcount)
