"""What a client asked of a job beyond its inputs, and the callbacks it subscribed to.

OGC API - Processes lets an execute request choose how results are presented (the
``response`` form, the outputs, their transmission modes) and subscribe URIs to be
called when the job starts, succeeds or fails.  Both are kept with the job.  A callback
becomes *due* when its job reaches the event; each due callback is one row, which a
sender claims under a lease (one sender at a time, across API replicas), sends, and
marks delivered, or releases for a later retry, or gives up after the last attempt.
"""

from __future__ import annotations

import json
import time
import uuid
from collections.abc import Mapping
from typing import Any

from worker.contract import JobStatus
from worker.store.connector import Conn, SqlConnector
from worker.store.records import CallbackClaim
from worker.store.retry import retrying

__all__ = ["CALLBACK_EVENTS", "Callbacks"]


#: Event -> the subscriber member naming its URI.
CALLBACK_EVENTS: Mapping[str, str] = {
    "in-progress": "inProgressUri",
    "success": "successUri",
    "failed": "failedUri",
}

#: Jobs looked at per claim (only jobs whose callbacks may still become due).
_SCAN = 500


class Callbacks(SqlConnector):
    """Request options and callbacks of :class:`worker.store.sql.SqlJobStore`."""

    @retrying
    def set_request_options(
        self, job_id: str, presentation: Mapping[str, Any], subscriber: Mapping[str, Any] | None
    ) -> None:
        with self._write() as conn:
            self._exec(
                conn,
                "UPDATE jobs SET presentation = ?, subscriber = ?, callbacks_open = ? "
                "WHERE job_id = ?",
                (
                    json.dumps(dict(presentation)),
                    None if subscriber is None else json.dumps(dict(subscriber)),
                    1 if subscriber else 0,
                    job_id,
                ),
            )

    @retrying
    def request_options(
        self, job_id: str
    ) -> tuple[Mapping[str, Any] | None, Mapping[str, Any] | None]:
        row = self._one(
            self._conn(), "SELECT presentation, subscriber FROM jobs WHERE job_id = ?", (job_id,)
        )
        if row is None:
            return None, None
        presentation = json.loads(row["presentation"]) if row["presentation"] else None
        subscriber = json.loads(row["subscriber"]) if row["subscriber"] else None
        return presentation, subscriber

    def _record_due(self, conn: Conn, row: Any, now: float) -> None:
        """Add the callbacks the job's status makes due; close the job's callbacks once
        it is finished (an in-progress callback is not sent after the job finished)."""
        status = JobStatus(row["status"])
        subscriber = json.loads(row["subscriber"] or "{}")
        events = {
            JobStatus.RUNNING: "in-progress",
            JobStatus.SUCCESSFUL: "success",
            JobStatus.FAILED: "failed",
        }
        event = events.get(status)
        uri = subscriber.get(CALLBACK_EVENTS[event]) if event else None
        if event and uri:
            self._exec(
                conn,
                "INSERT INTO callbacks (job_id, event, uri, next_try) VALUES (?, ?, ?, ?) "
                "ON CONFLICT DO NOTHING",
                (row["job_id"], event, uri, now),
            )
        if status in (JobStatus.SUCCESSFUL, JobStatus.FAILED, JobStatus.DISMISSED):
            self._exec(
                conn, "UPDATE jobs SET callbacks_open = 0 WHERE job_id = ?", (row["job_id"],)
            )

    @retrying
    def claim_callbacks(self, lease_s: float, max_attempts: int, limit: int) -> list[CallbackClaim]:
        now = time.time()
        with self._write() as conn:
            for row in self._all(
                conn,
                "SELECT job_id, status, subscriber FROM jobs WHERE callbacks_open = 1 "
                "AND status <> ? ORDER BY seq LIMIT ?",
                (JobStatus.ACCEPTED.value, _SCAN),
            ):
                self._record_due(conn, row, now)
            skip = " SKIP LOCKED" if self.lock_clause else ""
            due = self._all(
                conn,
                "SELECT job_id, event, uri, attempts FROM callbacks WHERE delivered IS NULL "
                "AND gave_up IS NULL AND next_try <= ? AND attempts < ? "
                "AND (claim_until IS NULL OR claim_until < ?) "
                f"ORDER BY next_try LIMIT ?{self.lock_clause}{skip}",
                (now, max_attempts, now, limit),
            )
            claims = []
            for row in due:
                token = uuid.uuid4().hex
                claimed = self._exec(
                    conn,
                    "UPDATE callbacks SET claim_token = ?, claim_until = ?, "
                    "attempts = attempts + 1 WHERE job_id = ? AND event = ? "
                    "AND delivered IS NULL AND gave_up IS NULL "
                    "AND (claim_until IS NULL OR claim_until < ?)",
                    (token, now + lease_s, row["job_id"], row["event"], now),
                )
                if claimed.rowcount == 1:
                    claims.append(
                        CallbackClaim(
                            row["job_id"], row["event"], row["uri"], token, row["attempts"] + 1
                        )
                    )
        return claims

    @retrying
    def finish_callback(
        self, claim: CallbackClaim, delivered: bool, retry_after_s: float, max_attempts: int
    ) -> bool:
        now = time.time()
        gave_up = None if delivered or claim.attempt < max_attempts else now
        with self._write() as conn:
            done = self._exec(
                conn,
                "UPDATE callbacks SET claim_token = NULL, claim_until = NULL, delivered = ?, "
                "gave_up = ?, next_try = ? WHERE job_id = ? AND event = ? AND claim_token = ?",
                (
                    now if delivered else None,
                    gave_up,
                    now + retry_after_s,
                    claim.job_id,
                    claim.event,
                    claim.token,
                ),
            )
            return bool(done.rowcount == 1)

    @retrying
    def callback_log(self, job_id: str) -> list[dict[str, Any]]:
        """The job's callbacks: event, uri, attempts, delivered / gave_up (epoch s)."""
        rows = self._all(
            self._conn(),
            "SELECT event, uri, attempts, delivered, gave_up FROM callbacks WHERE job_id = ? "
            "ORDER BY next_try",
            (job_id,),
        )
        return [dict(r) for r in rows]
