"""Retention: finished jobs expire, their files are deleted, a tombstone stays a while.

A job's ``retention_s`` is fixed at submission (``DEXLAB_RESULT_TTL_S``, or less if the
request asked); the transaction that finishes the job (success, failure, dismissal)
sets ``expires = finished + retention_s``.  A sweeper (:mod:`worker.retention`) calls
:meth:`Retention.expire_jobs` in small batches: for each expired job, its artifact
bytes go first (embedded: the files; PostgreSQL: the chunk rows), then, in one short
transaction, its row (``artifact_index`` and ``callbacks`` rows go with it, by their
foreign keys) is replaced by a tombstone in ``expired_jobs``.  Deleting the bytes
first means a crash in between leaves a row whose bytes are gone, which the next
sweep deletes: never bytes that no row leads to.

**Tombstones.**  An expired job answers ``410 job-expired`` for a grace period, then
``404`` like any unknown ID: the grace is the job's own retention, at most a day
(:data:`MAX_GRACE_S`), so a client that polls less often than the job was kept still
learns what happened, and tombstones stay bounded.  Tally counts are not touched
(metrics never go back).
"""

from __future__ import annotations

import time
from datetime import UTC, datetime

from worker.store.connector import SqlConnector
from worker.store.retry import retrying

__all__ = ["MAX_GRACE_S", "Retention"]


#: The longest an expired job's tombstone is kept (s): 410 that long, then 404.
MAX_GRACE_S = 86400.0


class Retention(SqlConnector):
    """The retention half of :class:`worker.store.sql.SqlJobStore`."""

    @retrying
    def expire_jobs(self, limit: int) -> list[str]:
        now = time.time()
        rows = self._all(
            self._conn(),
            # A study's chunk outlives its expiry until the study has assembled it.
            "SELECT job_id FROM jobs WHERE expires <= ? AND (parent_id IS NULL OR NOT EXISTS "
            "(SELECT 1 FROM jobs p WHERE p.job_id = jobs.parent_id AND p.finished IS NULL)) "
            "ORDER BY expires LIMIT ?",
            (now, limit),
        )
        job_ids = [r["job_id"] for r in rows]
        if not job_ids:  # the usual answer: one indexed read, no write lock
            return []
        for job_id in job_ids:  # bytes other jobs' index rows read stay (worker.store.reuse)
            self._drop_artifact_data(job_id, self._held_attempt(job_id))
        marks = ", ".join("?" for _ in job_ids)
        with self._write() as conn:
            holders = self._holders(conn, job_ids)
            doomed = self._all(
                conn,
                f"SELECT job_id, owner, retention_s FROM jobs WHERE job_id IN ({marks}) "
                f"AND expires <= ?{self.lock_clause}",
                (*job_ids, now),
            )
            for row in doomed:
                grace = min(float(row["retention_s"]), MAX_GRACE_S)
                self._exec(
                    conn,
                    "INSERT INTO expired_jobs (job_id, owner, expired, forget) "
                    "VALUES (?, ?, ?, ?) ON CONFLICT DO NOTHING",
                    (row["job_id"], row["owner"], now, now + grace),
                )
            self._exec(
                conn,
                f"DELETE FROM jobs WHERE job_id IN ({marks}) AND expires <= ?",
                (*job_ids, now),
            )
        self._drop_unreferenced(holders | set(job_ids))
        return [r["job_id"] for r in doomed]

    @retrying
    def forget_expired(self, limit: int) -> int:
        now = time.time()
        row = self._one(
            self._conn(), "SELECT 1 AS x FROM expired_jobs WHERE forget <= ? LIMIT 1", (now,)
        )
        if row is None:
            return 0
        with self._write() as conn:
            cur = self._exec(
                conn,
                "DELETE FROM expired_jobs WHERE job_id IN (SELECT job_id FROM expired_jobs "
                "WHERE forget <= ? ORDER BY forget LIMIT ?)",
                (now, limit),
            )
            return int(cur.rowcount)

    @retrying
    def expired_at(self, job_id: str, *, owner: str | None = None) -> datetime | None:
        query = "SELECT expired FROM expired_jobs WHERE job_id = ?"
        params: tuple[str, ...] = (job_id,)
        if owner is not None:
            query += " AND owner = ?"
            params = (job_id, owner)
        row = self._one(self._conn(), query, params)
        return None if row is None else datetime.fromtimestamp(row["expired"], tz=UTC)
