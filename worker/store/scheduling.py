"""Fair claims: which accepted job a worker takes next.

**Fair between owners.**  ``job_owners.last_claim`` records when a claim last took one
of each owner's jobs.  A claim goes to the owner with queued work whose last claim is
oldest (ties by name), and takes that owner's oldest job: round-robin over the owners
with work, so one owner's twenty queued jobs do not hold back another owner's one.

**Cheap jobs are not starved.**  A job is *cheap* when its cost is within its process's
``sync_cost_limit`` (recorded at submission).  A claim with ``prefer_cheap`` (one slot of
each pool, :mod:`worker.pool`; one process of each Celery worker) takes the fair-order
cheap job if one is queued, else any job in fair order: so a single-worker pool loses
nothing, and a small job waits at most for the job its slot is running.

**Running cap.**  With ``max_running_per_owner``, an owner (other than the anonymous
owner of a service without keys) with that many jobs running is skipped until one ends
(a study's chunks count; the study itself, parked while they run, does not).

Claims stay what :mod:`worker.store.leases` makes them: one short transaction that
locks the job (PostgreSQL: ``FOR UPDATE SKIP LOCKED``, so concurrent claimers take
different jobs; SQLite: the write lock) and fences its writes with a lease token.
"""

from __future__ import annotations

import time

from worker.contract import JobStatus
from worker.store.connector import Conn, SqlConnector
from worker.store.records import Claim, ClaimAttempt
from worker.store.retry import retrying

__all__ = ["CAPPED_RETRY_S", "Scheduling"]


#: When a delivery whose job waits behind its owner's running cap tries again (s).
CAPPED_RETRY_S = 2.0

_RUNNING = JobStatus.RUNNING.value
_ACCEPTED = JobStatus.ACCEPTED.value


class Scheduling(SqlConnector):
    """The claim half of :class:`worker.store.sql.SqlJobStore`."""

    @retrying
    def claim_next(
        self,
        worker_id: str,
        lease_s: float,
        *,
        prefer_cheap: bool = False,
        max_running_per_owner: int | None = None,
        reap: bool = True,
    ) -> Claim | None:
        if reap:
            self.reap_expired()
        for cheap_only in (True, False) if prefer_cheap else (False,):
            decided, claim = self._quick_claim(
                worker_id, lease_s, cheap_only, max_running_per_owner
            )
            if claim is not None:
                return claim
            if not decided:
                break
        else:
            return None
        with self._batch() as conn:
            claim = None
            if prefer_cheap:
                claim = self._fair_claim(conn, worker_id, lease_s, True, max_running_per_owner)
            if claim is None:
                claim = self._fair_claim(conn, worker_id, lease_s, False, max_running_per_owner)
            return claim

    def _quick_claim(
        self, worker_id: str, lease_s: float, cheap_only: bool, max_running: int | None
    ) -> tuple[bool, Claim | None]:
        """A claim in one statement where the dialect has one
        (:mod:`worker.store.postgres_quick`): ``(decided, claim)``, where undecided
        means "take the general path"."""
        return False, None

    def _fair_claim(
        self,
        conn: Conn,
        worker_id: str,
        lease_s: float,
        cheap_only: bool,
        max_running: int | None,
    ) -> Claim | None:
        cheap = " AND cheap = 1" if cheap_only else ""
        # A probe per owner (LIMIT 1), not EXISTS: PostgreSQL would make that a join over
        # every queued job, a cost that grows with the queue.
        owners = self._all(
            conn,
            "SELECT o.owner FROM job_owners o WHERE (SELECT 1 FROM jobs j "
            f"WHERE j.owner = o.owner AND j.status = ?{' AND j.cheap = 1' if cheap else ''}"
            " LIMIT 1) IS NOT NULL ORDER BY o.last_claim, o.owner",
            (_ACCEPTED,),
        )
        skip = " SKIP LOCKED" if self.lock_clause else ""
        for candidate in owners:
            owner = candidate["owner"]
            if self._capped(conn, owner, max_running):
                continue
            row = self._one(
                conn,
                "SELECT job_id, process_id, created, started, attempts FROM jobs "
                f"WHERE owner = ? AND status = ?{cheap} "
                f"ORDER BY seq LIMIT 1{self.lock_clause}{skip}",
                (owner, _ACCEPTED),
            )
            if row is not None:
                self._note_claim(conn, owner)
                return self._take(conn, row["job_id"], worker_id, lease_s, row)
        return None

    def _capped(self, conn: Conn, owner: str, max_running: int | None) -> bool:
        """Whether the owner runs as many jobs as it may: jobs holding a worker, a
        study's chunks included, a study waiting for its chunks not (it holds none)."""
        if max_running is None or owner == "":
            return False
        row = self._one(
            conn,
            "SELECT COUNT(*) AS n FROM (SELECT 1 FROM jobs WHERE owner = ? AND status = ? "
            "AND COALESCE(phase, '') <> 'waiting' LIMIT ?) AS r",
            (owner, _RUNNING, max_running),
        )
        return row is not None and int(row["n"]) >= max_running

    def _note_claim(self, conn: Conn, owner: str) -> None:
        """Move the owner to the back of the round-robin."""
        self._exec(
            conn,
            "INSERT INTO job_owners (owner, last_claim) VALUES (?, ?) ON CONFLICT (owner) "
            "DO UPDATE SET last_claim = excluded.last_claim",
            (owner, time.time()),
        )

    @retrying
    def claim_job(
        self,
        job_id: str,
        worker_id: str,
        lease_s: float,
        *,
        max_running_per_owner: int | None = None,
    ) -> ClaimAttempt:
        now = time.time()
        with self._write() as conn:
            row = self._job_row(conn, job_id, lock=True)
            if row is None:
                return ClaimAttempt(None, None, None)
            status = JobStatus(row["status"])
            if status is JobStatus.RUNNING:
                if row["lease_expires"] is not None and row["lease_expires"] >= now:
                    return ClaimAttempt(None, status, row["lease_expires"] - now)
                status = self._reap(conn, row, now)
            if status is not JobStatus.ACCEPTED:
                return ClaimAttempt(None, status, None)
            if self._capped(conn, row["owner"], max_running_per_owner):
                return ClaimAttempt(None, status, CAPPED_RETRY_S)
            self._note_claim(conn, row["owner"])
            claim = self._take(conn, job_id, worker_id, lease_s, row)
            return ClaimAttempt(claim, status, None)
