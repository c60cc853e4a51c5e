"""The embedded job store: one SQLite file (WAL mode), safe across processes, with the
artifacts as files beside it (``<data dir>/artifacts/<job>/<attempt>/<name>``).

Writes run in ``BEGIN IMMEDIATE`` transactions, so claims are serialised by SQLite's
write lock; each thread keeps its own connection.  A busy or locked database is waited
for (about a second per try) and retried for ``retry_s`` in all; then the call raises
:class:`worker.errors.StoreUnavailable`.
"""

from __future__ import annotations

import sqlite3
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Any, ClassVar

from worker.store.artifact_files import FULL_ERRNOS, ArtifactFiles
from worker.store.connector import ThreadConnections
from worker.store.retry import Fault, Outage, retrying, single_try
from worker.store.sql import SqlJobStore

__all__ = ["SqliteJobStore"]

#: SQLite's own busy wait per statement (seconds); the retry loop goes on after it.
_BUSY_TIMEOUT_S = 1.0
#: Readiness wants at least this much free disk for results.
MIN_FREE_BYTES = 64 << 20

_TRANSIENT_CODES = frozenset(
    {
        "SQLITE_BUSY",
        "SQLITE_LOCKED",
        "SQLITE_BUSY_SNAPSHOT",
        "SQLITE_BUSY_RECOVERY",
        "SQLITE_LOCKED_SHAREDCACHE",
    }
)
_BROKEN_CODES = frozenset(
    {
        "SQLITE_CORRUPT",
        "SQLITE_NOTADB",
        "SQLITE_CANTOPEN",
        "SQLITE_READONLY",
        "SQLITE_IOERR",
        "SQLITE_PERM",
    }
)


class SqliteJobStore(SqlJobStore):
    """The job store on a SQLite file."""

    ddl_types: ClassVar[Mapping[str, str]] = {
        "seq_pk": "INTEGER PRIMARY KEY AUTOINCREMENT",
        "blob": "BLOB",
        "float": "REAL",
        "bigint": "INTEGER",
    }

    def __init__(self, path: Path | str, retry_s: float = 5.0) -> None:
        self.path = Path(path)
        self.retry_s = retry_s
        self.outage = Outage()
        self.files = ArtifactFiles(self.path.parent / "artifacts")
        self.connections = ThreadConnections()

    @classmethod
    def from_url(cls, url: str, retry_s: float = 5.0) -> SqliteJobStore:
        prefix = "sqlite:///"
        if not url.startswith(prefix):
            raise ValueError(f"The 'store_url' must start with {prefix!r}. Got {url!r} instead.")
        return cls(Path(url[len(prefix) :]), retry_s=retry_s)

    @property
    def location(self) -> str:
        return f"sqlite:///{self.path}"

    def _conn(self) -> sqlite3.Connection:
        conn: sqlite3.Connection | None = self.connections.current()
        if conn is None:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            conn = sqlite3.connect(
                self.path,
                timeout=_BUSY_TIMEOUT_S,
                isolation_level=None,
                check_same_thread=False,
            )
            try:
                conn.row_factory = sqlite3.Row
                conn.execute("PRAGMA journal_mode=WAL")
                conn.execute("PRAGMA synchronous=NORMAL")
                conn.execute("PRAGMA foreign_keys=ON")
            except BaseException:
                conn.close()
                raise
            self.connections.keep(conn)
        return conn

    @contextmanager
    def _write(self) -> Iterator[sqlite3.Connection]:
        conn = self._conn()
        conn.execute("BEGIN IMMEDIATE")
        try:
            yield conn
        except BaseException:
            try:
                conn.execute("ROLLBACK")
            except sqlite3.Error:  # (disk full, I/O error): a fresh connection is clean
                self.connections.drop()
            raise
        else:
            try:
                conn.execute("COMMIT")
            except BaseException:
                try:
                    conn.execute("ROLLBACK")
                except sqlite3.Error:
                    self.connections.drop()
                raise

    def classify(self, exc: BaseException) -> Fault:
        if isinstance(exc, OSError):
            return Fault.FULL if exc.errno in FULL_ERRNOS else Fault.BROKEN
        if not isinstance(exc, sqlite3.Error):
            return Fault.OTHER
        name = getattr(exc, "sqlite_errorname", "") or ""
        text = str(exc).lower()
        if name.startswith("SQLITE_FULL") or "disk is full" in text:
            return Fault.FULL
        if name in _TRANSIENT_CODES or "locked" in text or "busy" in text:
            return Fault.TRANSIENT
        if any(name.startswith(code) for code in _BROKEN_CODES) or (
            isinstance(exc, sqlite3.DatabaseError)
            and not isinstance(exc, sqlite3.IntegrityError | sqlite3.ProgrammingError)
        ):
            return Fault.BROKEN
        return Fault.OTHER

    def after_fault(self, fault: Fault) -> None:
        if fault is not Fault.TRANSIENT:
            self.connections.drop()

    def close(self) -> None:
        """Close every connection this store opened, in any thread."""
        self.connections.close_all()

    @retrying
    def ping(self) -> None:
        self._conn().execute("SELECT 1 FROM jobs LIMIT 1").fetchall()

    @single_try
    def check_storage(self) -> None:
        """The database takes a write lock (waiting at most SQLite's busy timeout), and
        the artifact folder a file, with :data:`MIN_FREE_BYTES` to spare."""
        with self._write() as conn:
            conn.execute("SELECT 1 FROM jobs LIMIT 1").fetchall()
        self.files.check_writable(MIN_FREE_BYTES)

    # -- artifact bytes: files ----------------------------------------------------------
    def _put_artifact_data(
        self,
        job_id: str,
        attempt: int,
        name: str,
        data: bytes,
        conn: Any = None,
        lease_token: str | None = None,
    ) -> bool:
        # One machine: the pool SIGKILLs a paused writer before its lease can pass on,
        # and files of a superseded attempt are never pointed at (and are removed by
        # the commit that supersedes it, or by this attempt's own refused commit).
        self.files.write(job_id, attempt, name, data)
        return True

    def _artifact_data(self, job_id: str, attempt: int, name: str) -> Iterator[bytes]:
        return self.files.chunks(job_id, attempt, name)

    def _drop_artifact_data(self, job_id: str, keep_attempt: int | None) -> None:
        self.files.delete(job_id, keep_attempt)
