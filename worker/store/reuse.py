"""Reusing stored results: a new job answered by a successful job of the same result key.

A job created by reuse is a row of its own (its ID, owner, timestamps and retention),
``successful`` from the start, holding a copy of the source's result document and index
rows that point at the source's stored bytes: each ``artifact_index`` row names the
``holder``, the job whose bytes it reads (NULL: its own).  The bytes of a holder are
removed only when no index row refers to them any more, whichever of the jobs sharing
them is deleted first (:meth:`Reuse._drop_unreferenced`).

A source must be successful, unexpired, not invalidated (``reusable``), not a partial
result (a study whose chunks failed), and shareable with the new job's owner: its own
owner's, or any owner's ``shareable`` result when the scope is ``all``.  ``reused_from``
names the job that computed the result (the root of a chain of reuses), and
``reused_own`` whether it was the new job's owner's.
"""

from __future__ import annotations

import json
import logging
import time
from collections.abc import Iterable

from worker.contract import JobStatus
from worker.store.connector import Conn, Row, SqlConnector
from worker.store.records import NewJob
from worker.store.retry import retrying

__all__ = ["Reuse"]

log = logging.getLogger("dexlab.store")

_SUCCESSFUL = JobStatus.SUCCESSFUL.value


class Reuse(SqlConnector):
    """The reuse half of :class:`worker.store.sql.SqlJobStore`."""

    def _reuse_source(self, conn: Conn, new: NewJob, now: float) -> Row:
        """The newest successful job ``new`` may reuse (None: none)."""
        if new.reuse is None or new.result_key is None:
            return None
        shared = "owner = ?" if new.reuse == "owner" else "(owner = ? OR shareable = 1)"
        return self._one(
            conn,
            "SELECT job_id, owner, result, reused_from, reused_own FROM jobs "
            "WHERE result_key = ? AND process_id = ? AND status = ? AND reusable = 1 "
            f"AND children_failed = 0 AND (expires IS NULL OR expires > ?) AND {shared} "
            # the owner's own first, then a computing job over a reuse of it
            "ORDER BY CASE WHEN owner = ? THEN 0 ELSE 1 END, "
            "CASE WHEN reused_from IS NULL THEN 0 ELSE 1 END, seq DESC LIMIT 1",
            (new.result_key, new.process_id, _SUCCESSFUL, now, new.owner, new.owner),
        )

    def _insert_reused(self, conn: Conn, new: NewJob, job_id: str, source: Row, now: float) -> None:
        """Insert ``new`` as ``job_id``, successful with ``source``'s result and files."""
        root = source["reused_from"] or source["job_id"]
        # Owned when the computing job was this owner's: the source is, and (when the
        # source is itself a reuse) the source's own root was its owner's.
        own = source["owner"] == new.owner and (
            source["reused_from"] is None or bool(source["reused_own"])
        )
        self._exec(
            conn,
            """INSERT INTO jobs (job_id, process_id, status, inputs, created, updated,
                   started, finished, progress, max_attempts, time_limit_s, idempotency,
                   request_hash, message, owner, cheap, retention_s, expires, parent_id,
                   result, result_key, shareable, reused_from, reused_own, reuse_scope)
               VALUES (?, ?, ?, ?, ?, ?, ?, ?, 100, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?,
                       ?, ?, ?)""",
            (
                job_id, new.process_id, _SUCCESSFUL, json.dumps(dict(new.inputs)), now, now,
                now, now, new.max_attempts, new.time_limit_s, new.idempotency_key,
                new.request_hash, "reused a stored result", new.owner, 1 if new.cheap else 0,
                new.retention_s, now + new.retention_s, new.parent_id, source["result"],
                new.result_key, 1 if new.share else 0, root, 1 if own else 0, new.reuse,
            ),
        )  # fmt: skip
        self._exec(
            conn,
            "INSERT INTO artifact_index (job_id, name, media_type, title, size, ord, attempt, "
            "etag, holder) SELECT ?, name, media_type, title, size, ord, attempt, etag, "
            "COALESCE(holder, job_id) FROM artifact_index WHERE job_id = ?",
            (job_id, source["job_id"]),
        )
        self._tally(conn, new.process_id, "submitted")
        self._tally(conn, new.process_id, "reused")

    @retrying
    def reusable(self, new: NewJob) -> bool:
        """Whether a stored result would answer ``new`` now (its inputs then passed
        every check once already: the same key is the same inputs, process version
        and build)."""
        return self._reuse_source(self._conn(), new, time.time()) is not None

    @retrying
    def invalidate_reuse(self, process_id: str, result_key: str | None = None) -> int:
        """Make the stored results of ``process_id`` (those of ``result_key`` only, when
        given) reusable no more, deleting no job; how many jobs were reusable."""
        key_clause = " AND result_key = ?" if result_key is not None else ""
        params = (process_id, result_key) if result_key is not None else (process_id,)
        with self._write() as conn:
            cur = self._exec(
                conn,
                f"UPDATE jobs SET reusable = 0 WHERE process_id = ? AND reusable = 1{key_clause}",
                params,
            )
            return int(cur.rowcount)

    # -- shared bytes -------------------------------------------------------------------
    def _held_attempt(self, job_id: str) -> int | None:
        """The attempt of ``job_id``'s bytes that other jobs' index rows read (None:
        no other job reads them)."""
        row = self._one(
            self._conn(),
            "SELECT MAX(attempt) AS a FROM artifact_index WHERE holder = ?",
            (job_id,),
        )
        return None if row is None or row["a"] is None else int(row["a"])

    def _holders(self, conn: Conn, job_ids: Iterable[str]) -> set[str]:
        """The jobs whose bytes the index rows of ``job_ids`` read, besides their own."""
        ids = list(job_ids)
        if not ids:
            return set()
        marks = ", ".join("?" for _ in ids)
        rows = self._all(
            conn,
            f"SELECT DISTINCT holder FROM artifact_index WHERE job_id IN ({marks}) "
            "AND holder IS NOT NULL",
            tuple(ids),
        )
        return {r["holder"] for r in rows}

    def _drop_unreferenced(self, holders: Iterable[str]) -> None:
        """Remove the bytes of each of ``holders`` that no index row refers to any more
        (best effort: logged, never raised)."""
        for holder in holders:
            try:
                row = self._one(
                    self._conn(),
                    "SELECT 1 AS x FROM artifact_index WHERE holder = ? "
                    "OR (job_id = ? AND holder IS NULL)",
                    (holder, holder),
                )
                if row is None:
                    self._drop_artifact_data(holder, None)
            except Exception:
                log.warning("could not remove the shared files of job %s", holder, exc_info=True)
