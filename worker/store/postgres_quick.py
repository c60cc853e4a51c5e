"""A claim and a completion in one statement each, on PostgreSQL.

A worker's two writes per job are a claim and a commit of the result.  Written as
transactions of several statements they cost a round trip per statement plus BEGIN and
COMMIT; here each is one statement of data-modifying CTEs, run in autocommit (its own
transaction, one round trip), doing exactly what the general path does in the same
order and under the same locks:

- **claim**: the first owner in fair order with an accepted job (and below its running
  cap), its oldest such job locked ``FOR UPDATE SKIP LOCKED``, the attempt started on
  it, the owner moved to the back of the round-robin, and the attempt's tallies.  Its
  commit does not wait for the WAL to reach the disk (``synchronous_commit`` off for
  that transaction alone): should the database server crash in the next fraction of a
  second, the claim is undone as a whole, the job is queued again, and the attempt
  that ran it cannot write anything (its lease token is not on the row); nothing else
  depends on a claim being on disk.  Every other write waits for the disk as usual;
- **completion** of a job without a parent: the row locked by its lease token, the
  result and status written, the artifact index rows and the finish tallies.

Where one statement cannot decide, it says so and the caller takes the general path
(:mod:`worker.store.scheduling`, :mod:`worker.store.artifact_index`): when the chosen
owner's jobs are all locked by other claimers at that instant, and for a study's
chunk, whose end is counted in its parent (:mod:`worker.store.fan_out`).
"""

from __future__ import annotations

import hashlib
import time
import uuid
from collections.abc import Sequence

from worker.contract import Artifact, JobStatus
from worker.store.connector import SqlConnector
from worker.store.records import Claim
from worker.store.tallies import DURATION_BUCKETS, QUEUE_WAIT_BUCKETS, bound_label

__all__ = ["QuickStatements", "bucket_case"]


_ACCEPTED = JobStatus.ACCEPTED.value
_RUNNING = JobStatus.RUNNING.value
_SUCCESSFUL = JobStatus.SUCCESSFUL.value


def bucket_case(expr: str, bounds: Sequence[float]) -> str:
    """SQL giving the label of the bucket ``expr`` falls in, as
    :func:`worker.store.tallies.bucket_label` does in Python (the first bound at or
    above the value; ``'+Inf'`` above the last).  ``bounds`` are the module's constant
    floats, so they are written into the statement."""
    whens = " ".join(f"WHEN {expr} <= {float(b)!r} THEN '{bound_label(b)}'" for b in bounds)
    return f"CASE {whens} ELSE '+Inf' END"


_TALLY_UPSERT = (
    "ON CONFLICT (process_id, tally, label) DO UPDATE SET "
    "count = job_tallies.count + excluded.count, total = job_tallies.total + excluded.total"
)


def _claim_statement(cheap_only: bool, capped: bool) -> str:
    cheap = " AND j.cheap = 1" if cheap_only else ""
    cap = (
        " AND (o.owner = '' OR (SELECT COUNT(*) FROM (SELECT 1 FROM jobs r WHERE "
        "r.owner = o.owner AND r.status = %(running)s AND COALESCE(r.phase, '') <> 'waiting'"
        " LIMIT %(cap)s) AS n) < %(cap)s)"
        if capped
        else ""
    )
    wait = "GREATEST(0, %(now)s - pick.created)"
    return f"""
WITH relaxed AS (
    SELECT set_config('synchronous_commit', 'off', true) AS setting
), chosen AS (
    SELECT o.owner FROM job_owners o
    WHERE (SELECT 1 FROM jobs j WHERE j.owner = o.owner
           AND j.status = %(accepted)s{cheap} LIMIT 1) IS NOT NULL{cap}
    ORDER BY o.last_claim, o.owner LIMIT 1
), pick AS (
    SELECT j.job_id, j.process_id, j.created, j.started, j.attempts FROM jobs j
    WHERE j.owner = (SELECT owner FROM chosen) AND j.status = %(accepted)s{cheap}
    ORDER BY j.seq LIMIT 1 FOR UPDATE SKIP LOCKED
), taken AS (
    UPDATE jobs SET status = %(running)s, lease_token = %(token)s,
        lease_expires = %(expires)s, worker_id = %(worker)s, attempts = jobs.attempts + 1,
        attempt_started = %(now)s, started = COALESCE(jobs.started, %(now)s),
        updated = %(now)s, progress = 0, message = 'running attempt ' || (jobs.attempts + 1)
    FROM pick WHERE jobs.job_id = pick.job_id
    RETURNING jobs.*
), noted AS (
    INSERT INTO job_owners (owner, last_claim) SELECT owner, %(now)s FROM taken
    ON CONFLICT (owner) DO UPDATE SET last_claim = excluded.last_claim
), tallied AS (
    INSERT INTO job_tallies (process_id, tally, label, count, total)
    SELECT process_id, 'attempts', '', 1, 0 FROM pick
    UNION ALL SELECT process_id, 'retries', '', 1, 0 FROM pick WHERE attempts > 0
    UNION ALL SELECT process_id, 'queue_wait', {bucket_case(wait, QUEUE_WAIT_BUCKETS)}, 1,
        {wait} FROM pick WHERE started IS NULL
    {_TALLY_UPSERT}
)
SELECT (SELECT owner FROM chosen) AS chosen_owner, taken.*
FROM relaxed LEFT JOIN taken ON true"""


_SECONDS = "GREATEST(0, %(now)s - target.started)"
_COMPLETE = f"""
WITH target AS (
    SELECT job_id, status, process_id, started, attempts, parent_id FROM jobs
    WHERE job_id = %(job)s AND lease_token = %(token)s FOR UPDATE
), done AS (
    UPDATE jobs SET result = %(result)s, status = %(successful)s, progress = 100,
        finished = %(now)s, updated = %(now)s, expires = %(now)s + jobs.retention_s,
        message = 'finished', lease_expires = NULL
    FROM target
    WHERE jobs.job_id = target.job_id AND target.status = %(running)s
        AND target.parent_id IS NULL
    RETURNING jobs.job_id
), indexed AS (
    INSERT INTO artifact_index (job_id, name, media_type, title, size, ord, attempt, etag)
    SELECT done.job_id, a.name, a.media_type, a.title, a.size, a.ord, target.attempts,
        a.etag
    FROM done, target, unnest(%(names)s::text[], %(types)s::text[], %(titles)s::text[],
        %(sizes)s::bigint[], %(ords)s::integer[], %(etags)s::text[])
        AS a(name, media_type, title, size, ord, etag)
), tallied AS (
    INSERT INTO job_tallies (process_id, tally, label, count, total)
    SELECT target.process_id, 'finished', %(successful)s, 1, 0 FROM done, target
    UNION ALL SELECT target.process_id, 'duration', {bucket_case(_SECONDS, DURATION_BUCKETS)},
        1, {_SECONDS} FROM done, target WHERE target.started IS NOT NULL
    {_TALLY_UPSERT}
)
SELECT target.status, target.attempts, target.parent_id,
    (SELECT COUNT(*) FROM done) AS completed
FROM target"""


class QuickStatements(SqlConnector):
    """The one-statement claim and completion of
    :class:`worker.store.postgres.PostgresJobStore`."""

    def _quick_claim(
        self, worker_id: str, lease_s: float, cheap_only: bool, max_running: int | None
    ) -> tuple[bool, Claim | None]:
        """``(True, claim)`` or ``(True, None)`` when nothing is claimable; ``(False,
        None)`` when the chosen owner's jobs were all locked by other claimers."""
        now = time.time()
        token = uuid.uuid4().hex
        conn = self._conn()
        row = conn.execute(
            _claim_statement(cheap_only, max_running is not None),
            {
                "accepted": _ACCEPTED,
                "running": _RUNNING,
                "cap": max_running,
                "token": token,
                "expires": now + lease_s,
                "worker": worker_id,
                "now": now,
            },
        ).fetchone()
        if row is None or row["chosen_owner"] is None:
            return True, None
        if row["job_id"] is None:
            return False, None
        return True, Claim(self._record(conn, row), token)

    def _quick_complete(
        self, job_id: str, lease_token: str, payload: str, artifacts: Sequence[Artifact]
    ) -> tuple[bool | None, int | None]:
        """``(outcome, attempt)``: the outcome :meth:`complete` answers (True: this
        attempt's result is committed, now or by an earlier try; False: the attempt no
        longer owns the job), or None for a chunk (the general path counts it in its
        parent)."""
        now = time.time()
        row = (
            self._conn()
            .execute(
                _COMPLETE,
                {
                    "job": job_id,
                    "token": lease_token,
                    "result": payload,
                    "successful": _SUCCESSFUL,
                    "running": _RUNNING,
                    "now": now,
                    "names": [a.name for a in artifacts],
                    "types": [a.media_type for a in artifacts],
                    "titles": [a.title for a in artifacts],
                    "sizes": [len(a.data) for a in artifacts],
                    "ords": list(range(len(artifacts))),
                    "etags": [hashlib.sha256(a.data).hexdigest() for a in artifacts],
                },
            )
            .fetchone()
        )
        if row is None or row["status"] not in (_RUNNING, _SUCCESSFUL):
            return False, None
        attempt = int(row["attempts"])
        if row["status"] == _SUCCESSFUL or row["completed"]:
            return True, attempt
        return None, attempt
