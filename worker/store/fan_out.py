"""Jobs that fan out: a parent splits into child jobs and is assembled once they end.

A parent's first attempt returns its children's inputs; :meth:`FanOut.split` stores
them as ordinary queued jobs (``parent_id`` set, the parent's owner and retention) and,
in the same transaction, parks the parent: ``phase = 'waiting'``, still ``running`` for
its clients but without a lease, so it holds no worker and no reaper touches it.  Each
child's end is counted in the transaction that records it (:meth:`_child_ended`, called
by every path that ends a job: success, failure, a lost worker out of attempts, a
dismissal); the child that ends last queues the parent again with ``phase =
'assembling'``, and a worker claims it like any job to assemble the children's
results.  A child that fails fails the parent with the child's problem and dismisses
its unfinished siblings, unless the parent allows a partial result (``partial_ok``):
then it is counted as missing.  Dismissing the parent dismisses its unfinished
children.  Quotas, listings and retention know children by their ``parent_id``.
"""

from __future__ import annotations

import json
import time
import uuid
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import replace
from typing import Any

from worker.contract import ChildEnd, JobStatus
from worker.store.connector import Conn, Row, SqlConnector
from worker.store.records import NewJob
from worker.store.retry import retrying

__all__ = ["FanOut"]


_RUNNING = JobStatus.RUNNING.value
_ACCEPTED = JobStatus.ACCEPTED.value
_UNFINISHED = (_ACCEPTED, _RUNNING)
#: Children fetched per query while assembling.
CHILD_PAGE = 200


class FanOut(SqlConnector):
    """The fan-out half of :class:`worker.store.sql.SqlJobStore`."""

    @retrying
    def split(
        self,
        job_id: str,
        lease_token: str,
        children: Sequence[NewJob],
        *,
        allow_partial: bool = False,
    ) -> list[str] | None:
        """Queue ``children`` of the running job and park it; their IDs in order, or
        None if this attempt no longer owns the job.  A retry after an ambiguous commit
        finds the split done and returns the same IDs."""
        now = time.time()
        with self._write() as conn:
            parent = self._one(
                conn,
                "SELECT status, phase, owner, retention_s, lease_token FROM jobs "
                f"WHERE job_id = ?{self.lock_clause}",
                (job_id,),
            )
            if parent is None:
                return None
            if parent["phase"] == "waiting" and parent["lease_token"] is None:
                return self._child_ids(conn, job_id)
            if parent["status"] != _RUNNING or parent["lease_token"] != lease_token:
                return None
            ids = [str(uuid.uuid4()) for _ in children]
            placed = [replace(c, owner=parent["owner"], retention_s=parent["retention_s"],
                              parent_id=job_id) for c in children]  # fmt: skip
            # A chunk of a stored result key is answered by it (worker.store.reuse).
            computed = []
            for child_id, child in zip(ids, placed, strict=True):
                source = self._reuse_source(conn, child, now)
                if source is None:
                    computed.append((child_id, child))
                else:
                    self._insert_reused(conn, child, child_id, source, now)
            conn.cursor().executemany(
                self._sql(
                    "INSERT INTO jobs (job_id, process_id, status, inputs, created, updated, "
                    "max_attempts, time_limit_s, message, owner, cheap, retention_s, "
                    "parent_id, result_key, shareable, reuse_scope) "
                    "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, 0, ?, ?, ?, ?, ?)"
                ),
                [
                    (child_id, child.process_id, _ACCEPTED, json.dumps(dict(child.inputs)), now,
                     now, child.max_attempts, child.time_limit_s, "queued", child.owner,
                     child.retention_s, job_id, child.result_key, 1 if child.share else 0,
                     child.reuse)
                    for child_id, child in computed
                ],
            )  # fmt: skip
            self._tally_all(conn, [(c.process_id, "submitted", "", 0.0) for _, c in computed])
            reused = len(ids) - len(computed)
            self._exec(
                conn,
                "UPDATE jobs SET phase = 'waiting', children_total = ?, children_done = ?, "
                "children_failed = 0, partial_ok = ?, lease_token = NULL, lease_expires = NULL,"
                " progress = ?, updated = ?, message = ? WHERE job_id = ?",
                (len(ids), reused, 1 if allow_partial else 0, 100.0 * reused / max(len(ids), 1),
                 now, f"waiting for {len(computed)} chunks" + (
                     f" ({reused} reused)" if reused else ""), job_id),
            )  # fmt: skip
            if not computed:  # nothing to wait for: assemble at once
                self._queue_assembly(conn, job_id, len(ids), now)
        return ids

    def _child_ids(self, conn: Conn, job_id: str) -> list[str]:
        rows = self._all(
            conn, "SELECT job_id FROM jobs WHERE parent_id = ? ORDER BY seq", (job_id,)
        )
        return [r["job_id"] for r in rows]

    def _queue_assembly(self, conn: Conn, job_id: str, total: int, now: float) -> None:
        self._exec(
            conn,
            "UPDATE jobs SET status = ?, phase = 'assembling', attempts = 0, dispatched = NULL,"
            " updated = ?, message = ? WHERE job_id = ?",
            (_ACCEPTED, now, f"all {total} chunks ended; queued to assemble", job_id),
        )

    def _child_ended(
        self, conn: Conn, child_id: str, status: JobStatus, error: Mapping[str, Any] | None,
        now: float,
    ) -> str | None:  # fmt: skip
        """Count a child's end in its parent (in the caller's transaction); the parent's
        ID when this was its last child and it is queued to assemble."""
        row = self._one(conn, "SELECT parent_id FROM jobs WHERE job_id = ?", (child_id,))
        if row is None or row["parent_id"] is None:
            return None
        parent_id = row["parent_id"]
        parent = self._one(
            conn,
            "SELECT job_id, status, phase, process_id, started, children_total, children_done,"
            f" children_failed, partial_ok FROM jobs WHERE job_id = ?{self.lock_clause}",
            (parent_id,),
        )
        if parent is None or parent["phase"] != "waiting" or parent["status"] != _RUNNING:
            return None
        ended_badly = status is not JobStatus.SUCCESSFUL
        if ended_badly and not parent["partial_ok"]:
            self._fail_parent(conn, parent, child_id, status, error, now)
            return None
        done = int(parent["children_done"]) + 1
        failed = int(parent["children_failed"]) + (1 if ended_badly else 0)
        total = int(parent["children_total"])
        self._exec(
            conn,
            "UPDATE jobs SET children_done = ?, children_failed = ?, progress = ?, updated = ?,"
            " message = ? WHERE job_id = ?",
            (done, failed, 100.0 * done / max(total, 1), now,
             f"{done} of {total} chunks ended" + (f" ({failed} failed)" if failed else ""),
             parent_id),
        )  # fmt: skip
        if done < total:
            return None
        self._queue_assembly(conn, parent_id, total, now)
        return str(parent_id)

    def _fail_parent(
        self, conn: Conn, parent: Row, child_id: str, status: JobStatus,
        error: Mapping[str, Any] | None, now: float,
    ) -> None:  # fmt: skip
        what = (error or {}).get("detail") or f"it was {status.value}"
        problem = {
            "type": "chunk-failed",
            "title": "A chunk of the study failed",
            "detail": f"Chunk {child_id} ended {status.value}: {what}",
            "chunk": child_id,
            "chunk_error": dict(error) if error else None,
        }
        self._exec(
            conn,
            "UPDATE jobs SET status = ?, phase = NULL, error = ?, finished = ?, updated = ?, "
            "expires = ? + retention_s, message = ? WHERE job_id = ?",
            (JobStatus.FAILED.value, json.dumps(problem), now, now, now, problem["detail"],
             parent["job_id"]),
        )  # fmt: skip
        self._tally_finish(conn, parent, JobStatus.FAILED, now)
        self._dismiss_children(conn, parent["job_id"], now, "dismissed: its study failed")

    def _dismiss_children(self, conn: Conn, parent_id: str, now: float, message: str) -> None:
        """Dismiss the unfinished children of ``parent_id`` (their running processes see
        it at their next heartbeat and stop)."""
        rows = self._all(
            conn,
            "SELECT job_id, status, process_id, started FROM jobs WHERE parent_id = ? AND "
            f"status IN (?, ?){self.lock_clause}",
            (parent_id, *_UNFINISHED),
        )
        for row in rows:
            self._tally_finish(conn, row, JobStatus.DISMISSED, now)
        self._exec(
            conn,
            "UPDATE jobs SET status = ?, finished = ?, expires = ? + retention_s, updated = ?, "
            "lease_expires = NULL, message = ? WHERE parent_id = ? AND status IN (?, ?)",
            (JobStatus.DISMISSED.value, now, now, now, message, parent_id, *_UNFINISHED),
        )

    @retrying
    def children(self, job_id: str) -> list[ChildEnd]:
        """The children of ``job_id`` in the order they were made: status, error."""
        rows = self._all(
            self._conn(),
            "SELECT job_id, status, error FROM jobs WHERE parent_id = ? ORDER BY seq",
            (job_id,),
        )
        return [
            ChildEnd(r["job_id"], JobStatus(r["status"]),
                     json.loads(r["error"]) if r["error"] else None)
            for r in rows
        ]  # fmt: skip

    def child_results(self, job_id: str) -> Iterator[tuple[ChildEnd, Mapping[str, Any] | None]]:
        """Each child with its result document (None unless successful), in order,
        fetched a page at a time (a study's assembly streams them)."""
        ends = self.children(job_id)
        for start in range(0, len(ends), CHILD_PAGE):
            page = ends[start : start + CHILD_PAGE]
            results = self._results_of([e.job_id for e in page if e.status is JobStatus.SUCCESSFUL])
            for end in page:
                yield end, results.get(end.job_id)

    @retrying
    def _results_of(self, job_ids: Sequence[str]) -> dict[str, Mapping[str, Any]]:
        if not job_ids:
            return {}
        marks = ", ".join("?" for _ in job_ids)
        rows = self._all(
            self._conn(),
            f"SELECT job_id, result FROM jobs WHERE job_id IN ({marks}) AND result IS NOT NULL",
            tuple(job_ids),
        )
        return {r["job_id"]: json.loads(r["result"]) for r in rows}
