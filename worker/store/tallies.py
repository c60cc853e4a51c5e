"""Job tallies: running counts kept beside the jobs, which the metrics read.

Each job event adds one to a row of ``job_tallies`` inside the transaction that makes
the event, so a tally is exact (a retried ambiguous commit adds nothing twice: the
event's own fencing decides), never goes back (a dismissed job keeps its place in the
count it finished in; pruning old jobs takes nothing away), and is the same whichever
process or machine ran the job.  Reading all of them is one query over a few rows per
process, whatever the number of jobs: a scrape stays cheap.  (Counting the ``jobs``
table instead would cost a scan per scrape and go back as jobs are dismissed or
pruned.)  Counts start at migration 6: jobs finished before it are not counted.

- ``submitted``: jobs created;
- ``attempts``: attempts started (claims); ``retries``: attempts after a job's first;
- ``finished``, labelled with the status: jobs that reached ``successful`` or
  ``failed``, or were ``dismissed`` before either;
- ``duration``, labelled with a bucket: ``finished - started`` (seconds) of jobs that
  finished ``successful`` or ``failed``;
- ``queue_wait``, labelled with a bucket: ``started - created`` (seconds), at a job's
  first claim.

A histogram's row holds the observations whose value is at most its bucket's upper
bound and above the bound before (``count``) and their sum (``total``); the reader makes
the buckets cumulative.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Sequence

from worker.contract import JobStatus
from worker.store.connector import Conn, Row, SqlConnector
from worker.store.records import JobTally
from worker.store.retry import retrying

__all__ = [
    "DURATION_BUCKETS",
    "QUEUE_WAIT_BUCKETS",
    "Tallies",
    "bound_label",
    "bucket_label",
    "label_bound",
]


#: Upper bounds (seconds) of the job-duration buckets (``+Inf`` follows).
DURATION_BUCKETS = (0.1, 0.25, 0.5, 1.0, 2.5, 5.0, 10.0, 30.0, 60.0, 120.0, 300.0,
                    600.0, 1800.0, 3600.0)  # fmt: skip
#: Upper bounds (seconds) of the queue-wait buckets (``+Inf`` follows).
QUEUE_WAIT_BUCKETS = (0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1.0, 2.5, 5.0, 10.0, 30.0,
                      60.0, 300.0, 1800.0)  # fmt: skip

_UNFINISHED = (JobStatus.ACCEPTED.value, JobStatus.RUNNING.value)


def bucket_label(seconds: float, bounds: Sequence[float]) -> str:
    """The label of the bucket ``seconds`` falls in: its upper bound as Prometheus
    writes it (``"0.5"``, ``"10.0"``), or ``"+Inf"`` above the last."""
    index = bisect.bisect_left(bounds, seconds)
    return bound_label(math.inf if index == len(bounds) else bounds[index])


def bound_label(bound: float) -> str:
    """A bucket's upper bound as Prometheus writes it: ``"0.5"``, ``"10.0"``, ``"+Inf"``."""
    return "+Inf" if bound == math.inf else repr(float(bound))


def label_bound(label: str) -> float:
    """The upper bound a bucket label stands for (``"+Inf"``: infinity)."""
    return math.inf if label == "+Inf" else float(label)


class Tallies(SqlConnector):
    """The tally half of :class:`worker.store.sql.SqlJobStore`."""

    # -- writing (inside the transaction of the event) ----------------------------------
    def _tally(
        self, conn: Conn, process_id: str, tally: str, label: str = "", value: float = 0.0
    ) -> None:
        self._tally_all(conn, [(process_id, tally, label, value)])

    def _tally_all(self, conn: Conn, events: Sequence[tuple[str, str, str, float]]) -> None:
        """Count each ``(process_id, tally, label, value)`` event, in one statement
        (events of one row are summed first: an upsert may touch a row only once)."""
        rows: dict[tuple[str, str, str], list[float]] = {}
        for process_id, tally, label, value in events:
            row = rows.setdefault((process_id, tally, label), [0, 0.0])
            row[0] += 1
            row[1] += value
        if not rows:
            return
        self._exec(
            conn,
            "INSERT INTO job_tallies (process_id, tally, label, count, total) VALUES "
            + ", ".join(["(?, ?, ?, ?, ?)"] * len(rows))
            + " ON CONFLICT (process_id, tally, label) DO UPDATE SET "
            "count = job_tallies.count + excluded.count, "
            "total = job_tallies.total + excluded.total",
            [v for key, (count, total) in rows.items() for v in (*key, int(count), total)],
        )

    def _tally_claim(self, conn: Conn, job_id: str, now: float, row: Row = None) -> None:
        """An attempt starts (before the claim's update): attempts, retries, and the
        queue wait at the first claim.  ``row`` (the job's process_id, created, started
        and attempts) saves reading it again."""
        if row is None:
            row = self._one(
                conn,
                "SELECT process_id, created, started, attempts FROM jobs WHERE job_id = ?",
                (job_id,),
            )
        if row is None:
            return
        process_id = row["process_id"]
        events = [(process_id, "attempts", "", 0.0)]
        if row["attempts"] > 0:
            events.append((process_id, "retries", "", 0.0))
        if row["started"] is None:
            wait = max(0.0, now - row["created"])
            events.append((process_id, "queue_wait", bucket_label(wait, QUEUE_WAIT_BUCKETS), wait))
        self._tally_all(conn, events)

    def _tally_finish(self, conn: Conn, row: Row, status: JobStatus, now: float) -> None:
        """A job reaches ``status`` (``row`` has its ``process_id`` and ``started``); a
        dismissal counts only for a job that had not finished (``row["status"]``)."""
        if status is JobStatus.DISMISSED and row["status"] not in _UNFINISHED:
            return
        process_id = row["process_id"]
        events = [(process_id, "finished", status.value, 0.0)]
        if status is not JobStatus.DISMISSED and row["started"] is not None:
            seconds = max(0.0, now - row["started"])
            events.append(
                (process_id, "duration", bucket_label(seconds, DURATION_BUCKETS), seconds)
            )
        self._tally_all(conn, events)

    # -- reading ------------------------------------------------------------------------
    @retrying
    def job_tallies(self) -> list[JobTally]:
        rows = self._all(
            self._conn(),
            "SELECT process_id, tally, label, count, total FROM job_tallies "
            "ORDER BY process_id, tally, label",
        )
        return [
            JobTally(r["process_id"], r["tally"], r["label"], int(r["count"]), float(r["total"]))
            for r in rows
        ]

    @retrying
    def queue_depth(self) -> dict[tuple[str, JobStatus], int]:
        rows = self._all(
            self._conn(),
            "SELECT process_id, status, COUNT(*) AS n FROM jobs WHERE status IN (?, ?) "
            "GROUP BY process_id, status",
            _UNFINISHED,
        )
        return {(r["process_id"], JobStatus(r["status"])): int(r["n"]) for r in rows}
