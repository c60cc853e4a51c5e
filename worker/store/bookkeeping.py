"""The store's bookkeeping beside the jobs: dispatch times (for re-sending lost broker
messages) and the registry of live worker processes."""

from __future__ import annotations

import time
from collections.abc import Sequence

from worker.contract import JobStatus
from worker.store.connector import SqlConnector
from worker.store.records import WorkerInfo
from worker.store.retry import retrying

__all__ = ["Bookkeeping"]

_ACCEPTED = JobStatus.ACCEPTED.value


class Bookkeeping(SqlConnector):
    """Dispatch and worker bookkeeping of :class:`worker.store.sql.SqlJobStore`."""

    # -- dispatch bookkeeping ---------------------------------------------------------
    @retrying
    def mark_dispatched(self, job_id: str) -> None:
        with self._write() as conn:
            self._exec(
                conn, "UPDATE jobs SET dispatched = ? WHERE job_id = ?", (time.time(), job_id)
            )

    @retrying
    def undispatched(self, older_than_s: float, limit: int = 100) -> list[str]:
        """Accepted jobs dispatched (or, never dispatched, created) over ``older_than_s`` ago."""
        rows = self._all(
            self._conn(),
            "SELECT job_id FROM jobs WHERE status = ? AND COALESCE(dispatched, created) < ?"
            " ORDER BY seq LIMIT ?",
            (_ACCEPTED, time.time() - older_than_s, limit),
        )
        return [r["job_id"] for r in rows]

    @retrying
    def take_overdue(self, job_ids: Sequence[str], older_than_s: float) -> list[str]:
        """Of these jobs, those still accepted and dispatched (or created) over
        ``older_than_s`` ago, each marked dispatched now by the same statement: of
        several sweepers picking the same overdue jobs at once, one re-sends each."""
        now = time.time()
        taken = []
        with self._write() as conn:
            for job_id in job_ids:
                cur = self._exec(
                    conn,
                    "UPDATE jobs SET dispatched = ? WHERE job_id = ? AND status = ?"
                    " AND COALESCE(dispatched, created) < ?",
                    (now, job_id, _ACCEPTED, now - older_than_s),
                )
                if cur.rowcount == 1:
                    taken.append(job_id)
        return taken

    @retrying
    def accepted_count(self, bound: int) -> int:
        """Accepted jobs (chunks included), counted up to ``bound``."""
        rows = self._all(
            self._conn(),
            "SELECT COUNT(*) AS n FROM (SELECT 1 FROM jobs WHERE status = ? LIMIT ?) AS q",
            (_ACCEPTED, bound),
        )
        return int(rows[0]["n"]) if rows else 0

    # -- worker registry --------------------------------------------------------------
    @retrying
    def register_worker(self, worker_id: str, host: str, pid: int) -> None:
        now = time.time()
        with self._write() as conn:
            self._exec(
                conn,
                "INSERT INTO workers (worker_id, host, pid, started, heartbeat) "
                "VALUES (?, ?, ?, ?, ?) ON CONFLICT (worker_id) DO UPDATE SET "
                "host = excluded.host, pid = excluded.pid, started = excluded.started, "
                "heartbeat = excluded.heartbeat",
                (worker_id, host, pid, now, now),
            )

    @retrying
    def worker_heartbeat(self, worker_id: str) -> None:
        with self._write() as conn:
            self._exec(
                conn,
                "UPDATE workers SET heartbeat = ? WHERE worker_id = ?",
                (time.time(), worker_id),
            )

    @retrying
    def unregister_worker(self, worker_id: str) -> None:
        with self._write() as conn:
            self._exec(conn, "DELETE FROM workers WHERE worker_id = ?", (worker_id,))

    @retrying
    def live_workers(self, within_s: float) -> list[WorkerInfo]:
        rows = self._all(
            self._conn(),
            "SELECT * FROM workers WHERE heartbeat >= ? ORDER BY started",
            (time.time() - within_s,),
        )
        return [
            WorkerInfo(r["worker_id"], r["host"], r["pid"], r["started"], r["heartbeat"])
            for r in rows
        ]
