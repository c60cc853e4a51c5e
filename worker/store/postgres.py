"""The shared job store on PostgreSQL (psycopg 3), for many API replicas and workers.

Installed with the ``distributed`` extra.  Each thread keeps its own autocommit
connection; writes run in explicit transactions, rows are locked with
``SELECT ... FOR UPDATE`` (claims skip rows another worker has locked), and concurrent
migrations are serialised by an advisory lock.  Artifact bytes live in
``artifact_chunks`` as ~1 MiB ``bytea`` rows, each written and read by one short
query, so API and workers on different machines share them without a long
transaction or a connection held for a whole download.  Sessions set
``idle_in_transaction_session_timeout``, so a stopped process cannot hold row locks.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from typing import Any, ClassVar

from worker.contract import JobStatus
from worker.errors import StoreUnavailable
from worker.store.artifact_files import CHUNK_BYTES
from worker.store.connector import ThreadConnections
from worker.store.postgres_quick import QuickStatements
from worker.store.retry import Fault, Outage, retrying, single_try
from worker.store.sql import SqlJobStore

_RUNNING = JobStatus.RUNNING.value

__all__ = ["PostgresJobStore"]

#: Key of the advisory lock held while migrating (any constant unique to dexlab).
_MIGRATION_LOCK = 0x646578_6C6162
#: Key of the advisory lock that serialises submissions (quotas: worker.store.quotas).
_SUBMISSION_LOCK = 0x646578_717565
#: A session idle inside a transaction this long is ended by the server (ms).
IDLE_IN_TRANSACTION_MS = 10_000

#: How long a connection attempt may take (seconds; libpq's least is 2); a readiness
#: probe's the least.
CONNECT_TIMEOUT_S = 5
PROBE_CONNECT_TIMEOUT_S = 2

#: SQLSTATE classes and codes: retry, disk full, unusable.
_TRANSIENT_STATES = ("08", "40001", "40P01", "55P03", "57P01", "57P02", "57P03", "53300")
_FULL_STATES = ("53100",)


class PostgresJobStore(QuickStatements, SqlJobStore):
    """The job store on a PostgreSQL database (``postgresql://...``)."""

    lock_clause = " FOR UPDATE"
    ddl_types: ClassVar[Mapping[str, str]] = {
        "seq_pk": "BIGSERIAL PRIMARY KEY",
        "blob": "BYTEA",
        "float": "DOUBLE PRECISION",
        "bigint": "BIGINT",
    }

    def __init__(self, url: str, retry_s: float = 5.0) -> None:
        try:
            import psycopg  # noqa: F401
        except ImportError as exc:  # pragma: no cover - depends on the install
            raise StoreUnavailable(
                "A postgresql:// store needs the 'distributed' extra: "
                "pip install 'dexlab[distributed]'."
            ) from exc
        self.url = url
        self.retry_s = retry_s
        self.outage = Outage()
        self.connections = ThreadConnections()

    @property
    def location(self) -> str:
        return self.url.split("@")[-1]  # never echo credentials

    def _sql(self, query: str) -> str:
        return query.replace("?", "%s")

    def _conn(self, connect_timeout_s: int = CONNECT_TIMEOUT_S) -> Any:
        import psycopg
        from psycopg.rows import dict_row

        conn = self.connections.current()
        if conn is not None and (conn.closed or conn.broken):
            self.connections.drop()
            conn = None
        if conn is None:
            conn = psycopg.connect(
                self.url, autocommit=True, row_factory=dict_row, connect_timeout=connect_timeout_s
            )
            conn.execute(f"SET idle_in_transaction_session_timeout = {IDLE_IN_TRANSACTION_MS}")
            self.connections.keep(conn)
        return conn

    @contextmanager
    def _write(self) -> Iterator[Any]:
        conn = self._conn()
        with conn.transaction():
            yield conn

    @contextmanager
    def _batch(self) -> Iterator[Any]:
        conn = self._conn()
        with conn.pipeline(), conn.transaction():
            yield conn

    def _lock_schema(self, conn: Any) -> None:
        self._exec(conn, "SELECT pg_advisory_xact_lock(?)", (_MIGRATION_LOCK,))

    def _lock_submissions(self, conn: Any) -> None:
        # Every replica's submissions queue here until the inserting transaction ends,
        # so a quota's count and the insert it admits are one step (READ COMMITTED
        # would otherwise let two submissions count the same free slot).
        self._exec(conn, "SELECT pg_advisory_xact_lock(?)", (_SUBMISSION_LOCK,))

    def classify(self, exc: BaseException) -> Fault:
        import psycopg

        if not isinstance(exc, psycopg.Error):
            return Fault.OTHER
        state = exc.sqlstate or ""
        if state.startswith(_FULL_STATES):
            return Fault.FULL
        if isinstance(exc, psycopg.OperationalError) or state.startswith(_TRANSIENT_STATES):
            return Fault.TRANSIENT
        return Fault.OTHER

    def after_fault(self, fault: Fault) -> None:
        conn = self.connections.current()
        if conn is not None and (conn.closed or conn.broken or fault is not Fault.TRANSIENT):
            self.connections.drop()

    def close(self) -> None:
        """Close every connection this store opened, in any thread."""
        self.connections.close_all()

    @retrying
    def ping(self) -> None:
        self._exec(self._conn(), "SELECT 1 FROM jobs LIMIT 1").fetchall()

    @single_try
    def check_storage(self) -> None:
        conn = self._conn(PROBE_CONNECT_TIMEOUT_S)
        with conn.transaction():
            self._exec(conn, "SELECT 1 FROM jobs LIMIT 1").fetchall()

    # -- artifact bytes: chunk rows -------------------------------------------------------
    def _put_artifact_data(
        self,
        job_id: str,
        attempt: int,
        name: str,
        data: bytes,
        conn: Any = None,
        lease_token: str | None = None,
    ) -> bool:
        view = memoryview(data)
        chunks = [view[i : i + CHUNK_BYTES] for i in range(0, len(data), CHUNK_BYTES)]
        if conn is not None:  # a migration's own transaction
            self._delete_chunks_in(conn, job_id, attempt, name)
            for index, chunk in enumerate(chunks):
                self._insert_chunk(conn, job_id, attempt, name, index, chunk)
            return True
        self._delete_chunks(job_id, attempt, name)
        for index, chunk in enumerate(chunks):
            if not self._put_chunk(job_id, attempt, name, index, chunk, lease_token):
                return False
        return True

    def _delete_chunks_in(self, conn: Any, job_id: str, attempt: int, name: str) -> None:
        self._exec(
            conn,
            "DELETE FROM artifact_chunks WHERE job_id = ? AND attempt = ? AND name = ?",
            (job_id, attempt, name),
        )

    def _insert_chunk(
        self, conn: Any, job_id: str, attempt: int, name: str, index: int, chunk: memoryview
    ) -> None:
        self._exec(
            conn,
            "INSERT INTO artifact_chunks (job_id, attempt, name, chunk, data) "
            "VALUES (?, ?, ?, ?, ?) ON CONFLICT (job_id, attempt, name, chunk) "
            "DO UPDATE SET data = excluded.data",
            (job_id, attempt, name, index, bytes(chunk)),
        )

    @retrying
    def _delete_chunks(self, job_id: str, attempt: int, name: str) -> None:
        self._delete_chunks_in(self._conn(), job_id, attempt, name)

    @retrying
    def _put_chunk(
        self,
        job_id: str,
        attempt: int,
        name: str,
        index: int,
        chunk: memoryview,
        lease_token: str | None,
    ) -> bool:
        """Write one chunk; with ``lease_token`` only while that lease still runs the
        job (the job row is share-locked for the insert, so a reaper's takeover waits
        for it and every later insert of this attempt finds the lease gone)."""
        if lease_token is None:
            self._insert_chunk(self._conn(), job_id, attempt, name, index, chunk)
            return True
        cur = self._exec(
            self._conn(),
            "INSERT INTO artifact_chunks (job_id, attempt, name, chunk, data) "
            "SELECT ?, ?, ?, ?, ? WHERE EXISTS (SELECT 1 FROM jobs WHERE job_id = ? "
            "AND lease_token = ? AND status = ? FOR SHARE) "
            "ON CONFLICT (job_id, attempt, name, chunk) DO UPDATE SET data = excluded.data",
            (job_id, attempt, name, index, bytes(chunk), job_id, lease_token, _RUNNING),
        )
        return bool(cur.rowcount)

    @retrying
    def _get_chunk(self, job_id: str, attempt: int, name: str, index: int) -> bytes | None:
        row = self._one(
            self._conn(),
            "SELECT data FROM artifact_chunks WHERE job_id = ? AND attempt = ? AND name = ? "
            "AND chunk = ?",
            (job_id, attempt, name, index),
        )
        return None if row is None else bytes(row["data"])

    def _artifact_data(self, job_id: str, attempt: int, name: str) -> Iterator[bytes]:
        index = 0
        while (chunk := self._get_chunk(job_id, attempt, name, index)) is not None:
            yield chunk
            index += 1

    @retrying
    def _drop_artifact_data(self, job_id: str, keep_attempt: int | None) -> None:
        if keep_attempt is None:
            self._exec(self._conn(), "DELETE FROM artifact_chunks WHERE job_id = ?", (job_id,))
        else:
            self._exec(
                self._conn(),
                "DELETE FROM artifact_chunks WHERE job_id = ? AND attempt <> ?",
                (job_id, keep_attempt),
            )
