"""Quotas: what a new job must fit, checked in the transaction that inserts it.

Three limits (:class:`worker.store.base.QueueLimits`, from the settings of the same
names):

- ``max_queued_per_owner`` (``DEXLAB_MAX_QUEUED_PER_KEY``): jobs one owner may have
  waiting (``accepted``); beyond it :class:`worker.errors.QuotaExceeded` (429);
- ``submit_rate_per_min`` (``DEXLAB_SUBMIT_RATE_PER_MIN``): a token bucket per owner in
  ``job_owners``, holding at most that many tokens and refilled at that many a minute;
  each new job takes one, and without one :class:`worker.errors.RateLimited` (429) says
  when the next comes;
- ``max_queued`` (``DEXLAB_MAX_QUEUED``): jobs waiting in the whole queue, every owner's;
  beyond it :class:`worker.errors.QueueFull` (503).

**Atomic with the insert.**  The checks and the insert are one transaction, and
submissions are serialised (:meth:`Quotas._lock_submissions`: SQLite's ``BEGIN
IMMEDIATE`` holds the write lock from the start; PostgreSQL takes a transaction-scoped
advisory lock, so API replicas on one database queue behind each other), so two
concurrent submissions cannot both take the last slot or the last token.  Counts are
bounded (``LIMIT`` the limit), so a full queue costs no more to check than the limit.

**What counts.**  An idempotent replay returns the job it names before any check (it
makes nothing).  Every count selects ``parent_id IS NULL``: work a job creates for
itself (a design study's chunks) will be inserted with its parent's ID, so it never
counts against its owner's quotas, and takes no token: the parent counts, once.  A
refused submission changes nothing (the transaction rolls back).
"""

from __future__ import annotations

from typing import Any

from worker.contract import JobStatus
from worker.errors import QueueFull, QuotaExceeded, RateLimited
from worker.store.connector import Conn, SqlConnector
from worker.store.records import NewJob

__all__ = ["QUEUE_FULL_RETRY_S", "QUOTA_RETRY_S", "Quotas"]


#: ``Retry-After`` hints (seconds): an owner's queue frees as its jobs start; the whole
#: queue as every owner's do.
QUOTA_RETRY_S = 5.0
QUEUE_FULL_RETRY_S = 10.0

_ACCEPTED = JobStatus.ACCEPTED.value


class Quotas(SqlConnector):
    """The quota half of :class:`worker.store.sql.SqlJobStore`."""

    def _admit(self, conn: Conn, new: NewJob, now: float) -> None:
        """Raise the quota error ``new`` meets; otherwise take its submission token.
        Runs in the inserting transaction, after :meth:`_lock_submissions`."""
        self._exec(
            conn, "INSERT INTO job_owners (owner) VALUES (?) ON CONFLICT DO NOTHING", (new.owner,)
        )
        if new.parent_id is not None:  # counted as its parent
            return
        limits = new.limits
        tokens = None
        if limits.submit_rate_per_min:
            tokens = self._tokens(conn, new.owner, limits.submit_rate_per_min, now)
        if limits.max_queued_per_owner is not None:
            queued = self._queued(conn, limits.max_queued_per_owner, new.owner)
            if queued >= limits.max_queued_per_owner:
                raise QuotaExceeded(
                    f"This API key has {queued} jobs queued, the most "
                    f"DEXLAB_MAX_QUEUED_PER_KEY allows; submit again once one has started.",
                    limit="DEXLAB_MAX_QUEUED_PER_KEY",
                    allowed=limits.max_queued_per_owner,
                    retry_after_s=QUOTA_RETRY_S,
                )
        if limits.max_queued is not None:
            queued = self._queued(conn, limits.max_queued)
            if queued >= limits.max_queued:
                raise QueueFull(
                    f"The queue holds {queued} jobs, the most DEXLAB_MAX_QUEUED allows; "
                    "submit again later.",
                    limit="DEXLAB_MAX_QUEUED",
                    allowed=limits.max_queued,
                    retry_after_s=QUEUE_FULL_RETRY_S,
                )
        if tokens is not None:
            self._exec(
                conn,
                "UPDATE job_owners SET tokens = ?, refilled = ? WHERE owner = ?",
                (tokens - 1.0, now, new.owner),
            )

    def _tokens(self, conn: Conn, owner: str, per_min: int, now: float) -> float:
        """The owner's tokens now (at most ``per_min``); raise RateLimited below one."""
        row = self._one(
            conn,
            f"SELECT tokens, refilled FROM job_owners WHERE owner = ?{self.lock_clause}",
            (owner,),
        )
        if row is None or row["tokens"] is None:
            return float(per_min)
        elapsed = max(0.0, now - float(row["refilled"]))
        tokens = min(float(per_min), float(row["tokens"]) + elapsed * per_min / 60.0)
        if tokens < 1.0:
            wait = (1.0 - tokens) * 60.0 / per_min
            raise RateLimited(
                f"This API key has used its {per_min} submissions a minute "
                f"(DEXLAB_SUBMIT_RATE_PER_MIN); the next is allowed in {wait:.1f} s.",
                limit="DEXLAB_SUBMIT_RATE_PER_MIN",
                allowed=per_min,
                retry_after_s=wait,
            )
        return tokens

    def _queued(self, conn: Conn, bound: int, owner: str | None = None) -> int:
        """Jobs waiting (without a parent), the owner's or everyone's, counted up to
        ``bound``."""
        where = "status = ? AND parent_id IS NULL"
        params: list[Any] = [_ACCEPTED]
        if owner is not None:
            where += " AND owner = ?"
            params.append(owner)
        row = self._one(
            conn,
            f"SELECT COUNT(*) AS n FROM (SELECT 1 FROM jobs WHERE {where} LIMIT ?) AS q",
            (*params, bound),
        )
        return int(row["n"]) if row is not None else 0
