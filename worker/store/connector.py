"""The connector every topic of the SQL job store is written against, declared once.

:class:`SqlConnector` is the base of each topic module's class (scheduling, leases,
fan-out, quotas, retention, artifact index, bookkeeping, callbacks, API keys, tallies)
and so of :class:`worker.store.sql.SqlJobStore`.  It holds three things, and no topic
module restates any of them (``tests/test_architecture_store.py`` checks it):

- **the dialect hooks**, which :class:`worker.store.sqlite.SqliteJobStore` and
  :class:`worker.store.postgres.PostgresJobStore` override: a thread's connection
  (:meth:`~SqlConnector._conn`), a write transaction (:meth:`~SqlConnector._write`,
  :meth:`~SqlConnector._batch`), placeholders (:meth:`~SqlConnector._sql`), locks
  (:attr:`~SqlConnector.lock_clause`, :meth:`~SqlConnector._lock_schema`,
  :meth:`~SqlConnector._lock_submissions`), fault classification for
  :mod:`worker.store.retry` (:meth:`~SqlConnector.classify`,
  :meth:`~SqlConnector.after_fault`) and where artifact bytes live;
- **the statement helpers** every topic uses: :meth:`~SqlConnector._exec`,
  :meth:`~SqlConnector._one`, :meth:`~SqlConnector._all` and the job row
  (:meth:`~SqlConnector._job_row`);
- **what one topic offers the others** (a record from a row, the tallies of an event,
  a child's end, a lease taken or reaped, artifact clean-up): declared here for the
  type checker, written in the module each names.
"""

from __future__ import annotations

import threading
from abc import ABC, abstractmethod
from collections.abc import Iterable, Iterator, Mapping, Sequence
from contextlib import AbstractContextManager, suppress
from typing import TYPE_CHECKING, Any, ClassVar

from worker.contract import JobRecord, JobStatus
from worker.store.retry import Fault, Outage

if TYPE_CHECKING:
    from worker.store.records import Claim, NewJob, StoredArtifact

__all__ = ["Conn", "Row", "SqlConnector", "ThreadConnections"]

#: A DB-API connection of the dialect (``sqlite3.Connection``, ``psycopg.Connection``).
Conn = Any
#: A row read by name (``sqlite3.Row``, a psycopg ``dict_row``).
Row = Any


class ThreadConnections:
    """A dialect's connections: one per thread, each remembered so that
    :meth:`close_all` can close them from any thread."""

    def __init__(self) -> None:
        self._local = threading.local()
        self._opened: list[Conn] = []
        self._lock = threading.Lock()

    def current(self) -> Conn | None:
        """This thread's connection (None: none open)."""
        return getattr(self._local, "conn", None)

    def keep(self, conn: Conn) -> None:
        """Make ``conn`` this thread's connection."""
        self._local.conn = conn
        with self._lock:
            self._opened.append(conn)

    def drop(self) -> None:
        """Forget and close this thread's connection (a close that fails is moot: the
        connection is dead already)."""
        conn = self.current()
        self._local.conn = None
        if conn is not None:
            with self._lock:
                if conn in self._opened:
                    self._opened.remove(conn)
            with suppress(Exception):
                conn.close()

    def close_all(self) -> None:
        """Close every connection opened, in any thread."""
        with self._lock:
            opened, self._opened = self._opened, []
        for conn in opened:
            conn.close()
        self._local = threading.local()


class SqlConnector(ABC):
    """Connections, transactions and statements of the SQL job store, for its topics."""

    #: Appended to a SELECT whose rows the transaction goes on to change.
    lock_clause: str = ""
    #: Type names substituted into the migrations' ``{placeholders}``.
    ddl_types: ClassVar[Mapping[str, str]] = {}
    #: How long (seconds) a call keeps retrying transient faults before it gives up.
    retry_s: float = 5.0
    #: Whether the store is known to be down (set by each dialect's constructor).
    outage: Outage

    # -- dialect hooks: connections and transactions ----------------------------------
    @abstractmethod
    def _conn(self) -> Conn:
        """This thread's connection (autocommit; transactions are explicit)."""

    @abstractmethod
    def _write(self) -> AbstractContextManager[Conn]:
        """A write transaction yielding the connection."""

    def _batch(self) -> AbstractContextManager[Conn]:
        """A write transaction whose statements may travel together: each result
        arrives when it is fetched (PostgreSQL's pipeline mode), so a statement whose
        result is not read costs no round trip of its own.  Only for code that reads
        nothing but fetched rows (not ``rowcount``).  Elsewhere, :meth:`_write`."""
        return self._write()

    def _sql(self, query: str) -> str:
        """The query in the dialect's placeholders (queries are written with ``?``)."""
        return query

    def _lock_schema(self, conn: Conn) -> None:
        """Serialise concurrent migrations (a no-op where the transaction does it)."""
        return None  # by default nothing to do (a dialect's hook may do more)

    def _lock_submissions(self, conn: Conn) -> None:
        """Serialise submissions until the transaction ends (a no-op where the
        transaction already holds the write lock)."""
        return None  # by default nothing to do (a dialect's hook may do more)

    # -- dialect hooks: faults (see worker.store.retry) -------------------------------
    def classify(self, exc: BaseException) -> Fault:
        """What a database exception means (see :mod:`worker.store.retry`)."""
        return Fault.OTHER

    def after_fault(self, fault: Fault) -> None:
        """Drop what a fault may have broken (a dialect closes a dead connection)."""
        return None  # by default nothing to do (a dialect's hook may do more)

    def close(self) -> None:
        """Close this thread's connection."""
        return None  # by default nothing to do (a dialect's hook may do more)

    @property
    def location(self) -> str:
        """Where the store is, safe to log (never credentials)."""
        return type(self).__name__

    # -- dialect hooks: where artifact bytes live -------------------------------------
    @abstractmethod
    def _put_artifact_data(
        self,
        job_id: str,
        attempt: int,
        name: str,
        data: bytes,
        conn: Conn | None = None,
        lease_token: str | None = None,
    ) -> bool:
        """Store one attempt's artifact bytes durably (in ``conn``'s transaction when
        given, during a migration).  With ``lease_token``, a store whose writers may
        resume after a pause (another machine) fences every write on the lease: False
        once the attempt no longer owns the job, and nothing more is written."""

    @abstractmethod
    def _artifact_data(self, job_id: str, attempt: int, name: str) -> Iterator[bytes]:
        """The bytes, a chunk at a time."""

    @abstractmethod
    def _drop_artifact_data(self, job_id: str, keep_attempt: int | None) -> None:
        """Remove the job's bytes: every attempt's, or all but ``keep_attempt``'s."""

    # -- statement helpers -------------------------------------------------------------
    def _exec(self, conn: Conn, query: str, params: Sequence[Any] = ()) -> Any:
        """Run one statement; the cursor (``rowcount``, ``fetchone``, ``fetchall``)."""
        cur = conn.cursor()
        cur.execute(self._sql(query), tuple(params))
        return cur

    def _one(self, conn: Conn, query: str, params: Sequence[Any] = ()) -> Row:
        """The statement's first row (None: no row; typed ``Any``, as a row is, so
        that a caller's own test of it narrows)."""
        return self._exec(conn, query, params).fetchone()

    def _all(self, conn: Conn, query: str, params: Sequence[Any] = ()) -> list[Row]:
        """Every row of the statement."""
        return list(self._exec(conn, query, params).fetchall())

    def _job_row(
        self, conn: Conn, job_id: str, lock: bool = False, owner: str | None = None
    ) -> Row | None:
        """The job's row (locked with ``lock``; None if unknown or not ``owner``'s)."""
        suffix = self.lock_clause if lock else ""
        if owner is None:
            return self._one(conn, f"SELECT * FROM jobs WHERE job_id = ?{suffix}", (job_id,))
        return self._one(
            conn, f"SELECT * FROM jobs WHERE job_id = ? AND owner = ?{suffix}", (job_id, owner)
        )

    # -- what one topic offers the others ----------------------------------------------
    if TYPE_CHECKING:
        # worker.store.sql
        def _record(self, conn: Conn, row: Row) -> JobRecord: ...

        # worker.store.tallies
        def _tally(
            self, conn: Conn, process_id: str, tally: str, label: str = "", value: float = 0.0
        ) -> None: ...
        def _tally_all(self, conn: Conn, events: Sequence[tuple[str, str, str, float]]) -> None: ...
        def _tally_claim(self, conn: Conn, job_id: str, now: float, row: Row = None) -> None: ...
        def _tally_finish(self, conn: Conn, row: Row, status: JobStatus, now: float) -> None: ...

        # worker.store.fan_out
        def _child_ended(
            self,
            conn: Conn,
            child_id: str,
            status: JobStatus,
            error: Mapping[str, Any] | None,
            now: float,
        ) -> str | None: ...
        def _dismiss_children(
            self, conn: Conn, parent_id: str, now: float, message: str
        ) -> None: ...

        # worker.store.leases
        def _take(
            self, conn: Conn, job_id: str, worker_id: str, lease_s: float, before: Row = None
        ) -> Claim: ...
        def _reap(self, conn: Conn, row: Row, now: float) -> JobStatus: ...
        def reap_expired(self) -> list[str]: ...

        # worker.store.artifact_index
        def _artifact_rows(self, conn: Conn, job_id: str) -> list[StoredArtifact]: ...
        def _discard_artifact_data(self, job_id: str, keep_attempt: int | None = None) -> None: ...

        # worker.store.reuse
        def _reuse_source(self, conn: Conn, new: NewJob, now: float) -> Row: ...
        def _insert_reused(
            self, conn: Conn, new: NewJob, job_id: str, source: Row, now: float
        ) -> None: ...
        def _held_attempt(self, job_id: str) -> int | None: ...
        def _holders(self, conn: Conn, job_ids: Iterable[str]) -> set[str]: ...
        def _drop_unreferenced(self, holders: Iterable[str]) -> None: ...
