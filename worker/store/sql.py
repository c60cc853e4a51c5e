"""The job store's logic, written once in portable SQL for SQLite and PostgreSQL.

Each topic class below is built on :class:`worker.store.connector.SqlConnector`, which
declares the connection, transaction and statement helpers once; a dialect subclass
overrides its hooks: connections, transactions, fault classification and where
artifact bytes live (:class:`worker.store.sqlite.SqliteJobStore`,
:class:`worker.store.postgres.PostgresJobStore`).  Queries use ``?`` placeholders;
every write is one short transaction, and the rows a decision depends on are locked
before the decision (``BEGIN IMMEDIATE`` in SQLite, ``SELECT ... FOR UPDATE`` in
PostgreSQL).  Every public method is retried over transient faults
(:mod:`worker.store.retry`); artifacts are handled in
:class:`worker.store.artifact_index.ArtifactIndex`, API keys in
:class:`worker.store.api_keys.ApiKeys`, claims in
:class:`worker.store.scheduling.Scheduling` (fair order) and
:class:`worker.store.leases.Leases`, quotas in :class:`worker.store.quotas.Quotas`,
retention in :class:`worker.store.retention.Retention`.  Reads and dismissals take an
optional ``owner``: given, a job of another owner is as good as unknown.
"""

from __future__ import annotations

import base64
import json
import re
import time
import uuid
from collections.abc import Mapping, Sequence
from datetime import UTC, datetime
from typing import Any

from worker.contract import ArtifactInfo, JobRecord, JobStatus
from worker.errors import IdempotencyConflict
from worker.store.api_keys import ApiKeys
from worker.store.artifact_index import ArtifactIndex
from worker.store.bookkeeping import Bookkeeping
from worker.store.callbacks import Callbacks
from worker.store.connector import Conn, Row
from worker.store.fan_out import FanOut
from worker.store.job_listing import filter_clauses
from worker.store.leases import Leases
from worker.store.quotas import Quotas
from worker.store.records import JobFilter, JobPage, NewJob
from worker.store.retention import Retention
from worker.store.retry import retrying
from worker.store.reuse import Reuse
from worker.store.scheduling import Scheduling
from worker.store.schema import MIGRATIONS
from worker.store.tallies import Tallies

__all__ = ["SqlJobStore", "decode_cursor", "encode_cursor"]

_RUNNING = JobStatus.RUNNING.value
_ACCEPTED = JobStatus.ACCEPTED.value


def _ts(value: float | None) -> datetime | None:
    return None if value is None else datetime.fromtimestamp(value, tz=UTC)


_CURSOR_NUMBER = re.compile(r"[0-9]{1,19}")
_MAX_SEQ = 2**63 - 1


def encode_cursor(seq: int) -> str:
    return base64.urlsafe_b64encode(f"seq:{seq}".encode()).decode().rstrip("=")


def decode_cursor(cursor: str) -> int:
    try:
        padded = cursor + "=" * (-len(cursor) % 4)
        text = base64.urlsafe_b64decode(padded.encode()).decode()
        prefix, _, number = text.partition(":")
        # Digits only, and within a signed 64-bit integer: what the stores' seq holds.
        if prefix != "seq" or not _CURSOR_NUMBER.fullmatch(number) or int(number) > _MAX_SEQ:
            raise ValueError(cursor)
        return int(number)
    except (ValueError, UnicodeDecodeError) as exc:
        raise ValueError(
            f"The 'cursor' parameter is not a cursor this service issued: {cursor!r}"
        ) from exc


class SqlJobStore(
    Scheduling,
    Leases,
    FanOut,
    Quotas,
    Retention,
    ArtifactIndex,
    Bookkeeping,
    Callbacks,
    ApiKeys,
    Tallies,
    Reuse,
):
    """A :class:`worker.store.base.JobStore` over a DB-API connection."""

    # -- schema -----------------------------------------------------------------------
    @retrying
    def initialise(self) -> None:
        with self._write() as conn:
            self._lock_schema(conn)
            self._exec(conn, "CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)")
            row = self._one(conn, "SELECT MAX(version) AS v FROM schema_version")
            current = (row["v"] if row is not None else None) or 0
            for version, statements in MIGRATIONS:
                if version <= current:
                    continue
                for statement in statements:
                    self._exec(conn, statement.format(**self.ddl_types))
                self._migrate_data(conn, version)
                self._exec(conn, "INSERT INTO schema_version (version) VALUES (?)", (version,))

    @retrying
    def schema_version(self) -> int:
        row = self._one(self._conn(), "SELECT MAX(version) AS v FROM schema_version")
        return int((row["v"] if row is not None else None) or 0)

    # -- records ----------------------------------------------------------------------
    def _record(self, conn: Conn, row: Row) -> JobRecord:
        status = JobStatus(row["status"])
        artifacts: tuple[ArtifactInfo, ...] = ()
        if status is JobStatus.SUCCESSFUL:
            artifacts = tuple(a.info for a in self._artifact_rows(conn, row["job_id"]))
        created = _ts(row["created"])
        updated = _ts(row["updated"])
        assert created is not None and updated is not None
        return JobRecord(
            job_id=row["job_id"],
            process_id=row["process_id"],
            status=status,
            inputs=json.loads(row["inputs"]),
            created=created,
            updated=updated,
            progress=row["progress"],
            message=row["message"],
            started=_ts(row["started"]),
            finished=_ts(row["finished"]),
            attempts=row["attempts"],
            max_attempts=row["max_attempts"],
            time_limit_s=row["time_limit_s"],
            error=json.loads(row["error"]) if row["error"] else None,
            worker_id=row["worker_id"],
            artifacts=artifacts,
            owner=row["owner"],
            expires=_ts(row["expires"]),
            parent_id=row["parent_id"],
            phase=row["phase"],
            children_total=row["children_total"],
            children_done=row["children_done"],
            children_failed=row["children_failed"],
            result_key=row["result_key"],
            reused_from=row["reused_from"],
            reused_own=bool(row["reused_own"]),
            reuse_scope=row["reuse_scope"],
            shareable=bool(row["shareable"]),
        )

    def create_job(self, new: NewJob) -> tuple[JobRecord, bool]:
        # The ID is chosen once, before any try, so a retry after an ambiguous commit
        # finds the job it already created instead of creating a second one.
        return self._create_job(new, str(uuid.uuid4()))

    @retrying
    def _create_job(self, new: NewJob, job_id: str) -> tuple[JobRecord, bool]:
        now = time.time()
        with self._write() as conn:
            self._lock_submissions(conn)  # quotas are checked atomically with the insert
            row = self._job_row(conn, job_id)
            if row is not None:  # this call's earlier, ambiguous try committed
                return self._record(conn, row), True
            replayed = self._replay(conn, new)
            if replayed is not None:  # an idempotent replay makes nothing, counts nothing
                return replayed, False
            self._admit(conn, new, now)
            source = self._reuse_source(conn, new, now)
            if source is not None:  # answered at once by a stored result (worker.store.reuse)
                self._insert_reused(conn, new, job_id, source, now)
                return self._record(conn, self._job_row(conn, job_id)), True
            # ON CONFLICT DO NOTHING: a concurrent submit with this idempotency key that
            # got in first (where submissions are not serialised) is found below.
            inserted = self._exec(
                conn,
                """INSERT INTO jobs (job_id, process_id, status, inputs, created, updated,
                       max_attempts, time_limit_s, idempotency, request_hash, message, owner,
                       cheap, retention_s, parent_id, result_key, shareable, reuse_scope)
                   VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)
                   ON CONFLICT DO NOTHING""",
                (
                    job_id,
                    new.process_id,
                    _ACCEPTED,
                    json.dumps(dict(new.inputs)),
                    now,
                    now,
                    new.max_attempts,
                    new.time_limit_s,
                    new.idempotency_key,
                    new.request_hash,
                    "queued",
                    new.owner,
                    1 if new.cheap else 0,
                    new.retention_s,
                    new.parent_id,
                    new.result_key,
                    1 if new.share else 0,
                    new.reuse,
                ),
            )
            if inserted.rowcount == 1:
                self._tally(conn, new.process_id, "submitted")
                return self._record(conn, self._job_row(conn, job_id)), True
            replayed = self._replay(conn, new)
            if replayed is None:  # pragma: no cover - a job ID collision
                raise RuntimeError(f"job {job_id} could not be created")
            return replayed, False

    def _replay(self, conn: Conn, new: NewJob) -> JobRecord | None:
        """The owner's job with ``new``'s idempotency key (None: none); another request
        body with that key is a conflict."""
        if new.idempotency_key is None:
            return None
        row = self._one(
            conn,
            "SELECT * FROM jobs WHERE owner = ? AND idempotency = ?",
            (new.owner, new.idempotency_key),
        )
        if row is None:
            return None
        if row["request_hash"] != new.request_hash:
            raise IdempotencyConflict(
                "This Idempotency-Key was already used with a different request "
                f"body (job {row['job_id']}); use a new key for a new request."
            )
        return self._record(conn, row)

    @retrying
    def get_job(self, job_id: str, *, owner: str | None = None) -> JobRecord | None:
        conn = self._conn()
        row = self._job_row(conn, job_id, owner=owner)
        return None if row is None else self._record(conn, row)

    @retrying
    def statuses(self, job_ids: Sequence[str]) -> dict[str, JobStatus]:
        """The status of each known job among ``job_ids``, in one query."""
        if not job_ids:
            return {}
        marks = ", ".join("?" for _ in job_ids)
        rows = self._all(
            self._conn(),
            f"SELECT job_id, status FROM jobs WHERE job_id IN ({marks})",
            tuple(job_ids),
        )
        return {r["job_id"]: JobStatus(r["status"]) for r in rows}

    @retrying
    def list_jobs(
        self,
        *,
        limit: int,
        cursor: str | None = None,
        status: JobStatus | None = None,
        process_id: str | None = None,
        where: JobFilter | None = None,
        owner: str | None = None,
    ) -> JobPage:
        clauses: list[str] = []
        params: list[Any] = []
        if where is not None:
            clauses, params = filter_clauses(where, time.time())
        if where is None or where.parent_id is None:  # a study's chunks only when asked
            clauses.append("parent_id IS NULL")
        else:
            clauses.append("parent_id = ?")
            params.append(where.parent_id)
        if owner is not None:
            clauses.append("owner = ?")
            params.append(owner)
        if cursor is not None:
            clauses.append("seq < ?")
            params.append(decode_cursor(cursor))
        if status is not None:
            clauses.append("status = ?")
            params.append(status.value)
        if process_id is not None:
            clauses.append("process_id = ?")
            params.append(process_id)
        condition = f"WHERE {' AND '.join(clauses)}" if clauses else ""
        conn = self._conn()
        rows = self._all(
            conn, f"SELECT * FROM jobs {condition} ORDER BY seq DESC LIMIT ?", (*params, limit + 1)
        )
        more = len(rows) > limit
        rows = rows[:limit]
        next_cursor = encode_cursor(rows[-1]["seq"]) if more and rows else None
        return JobPage([self._record(conn, r) for r in rows], next_cursor)

    @retrying
    def dismiss(self, job_id: str, *, owner: str | None = None) -> JobRecord | None:
        now = time.time()
        with self._write() as conn:
            row = self._job_row(conn, job_id, lock=True, owner=owner)
            if row is None:
                return None
            if row["status"] != JobStatus.DISMISSED.value:
                unfinished = row["status"] in (_ACCEPTED, _RUNNING)
                self._tally_finish(conn, row, JobStatus.DISMISSED, now)
                holders = self._holders(conn, [job_id])
                self._exec(conn, "DELETE FROM artifact_index WHERE job_id = ?", (job_id,))
                self._exec(
                    conn,
                    "UPDATE jobs SET status = ?, result = NULL, finished = COALESCE(finished, ?),"
                    " expires = COALESCE(finished, ?) + retention_s, updated = ?, phase = NULL,"
                    " message = 'dismissed by the client' WHERE job_id = ?",
                    (JobStatus.DISMISSED.value, now, now, now, job_id),
                )
                if unfinished:  # its unfinished chunks stop; its parent counts the end
                    self._dismiss_children(conn, job_id, now, "dismissed with its study")
                    self._child_ended(conn, job_id, JobStatus.DISMISSED, None, now)
            else:
                holders = set()
            record = self._record(conn, self._job_row(conn, job_id))
        self._discard_artifact_data(job_id)
        self._drop_unreferenced(holders)
        return record

    @retrying
    def get_result(self, job_id: str) -> Mapping[str, Any] | None:
        row = self._one(
            self._conn(),
            "SELECT result FROM jobs WHERE job_id = ? AND status = ?",
            (job_id, JobStatus.SUCCESSFUL.value),
        )
        return None if row is None or row["result"] is None else json.loads(row["result"])
