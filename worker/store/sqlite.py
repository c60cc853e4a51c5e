"""The embedded job store: one SQLite file (WAL mode), safe across processes.

Writes run in ``BEGIN IMMEDIATE`` transactions, so claims are serialised by SQLite's
write lock; each thread keeps its own connection.
"""

from __future__ import annotations

import sqlite3
import threading
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Any, ClassVar

from worker.errors import StoreUnavailable
from worker.store.sql import SqlJobStore

__all__ = ["SqliteJobStore"]


class SqliteJobStore(SqlJobStore):
    """The job store on a SQLite file."""

    ddl_types: ClassVar[Mapping[str, str]] = {
        "seq_pk": "INTEGER PRIMARY KEY AUTOINCREMENT",
        "blob": "BLOB",
        "float": "REAL",
    }

    def __init__(self, path: Path | str) -> None:
        self.path = Path(path)
        self._local = threading.local()
        self._opened: list[Any] = []
        self._opened_lock = threading.Lock()

    @classmethod
    def from_url(cls, url: str) -> SqliteJobStore:
        prefix = "sqlite:///"
        if not url.startswith(prefix):
            raise ValueError(f"The 'store_url' must start with {prefix!r}. Got {url!r} instead.")
        return cls(Path(url[len(prefix) :]))

    @property
    def location(self) -> str:
        return f"sqlite:///{self.path}"

    def _conn(self) -> sqlite3.Connection:
        conn: sqlite3.Connection | None = getattr(self._local, "conn", None)
        if conn is None:
            try:
                self.path.parent.mkdir(parents=True, exist_ok=True)
                conn = sqlite3.connect(
                    self.path, timeout=30.0, isolation_level=None, check_same_thread=False
                )
                conn.row_factory = sqlite3.Row
                conn.execute("PRAGMA journal_mode=WAL")
                conn.execute("PRAGMA synchronous=NORMAL")
                conn.execute("PRAGMA foreign_keys=ON")
            except (sqlite3.Error, OSError) as exc:
                raise StoreUnavailable(f"Cannot open the job store at {self.path}: {exc}") from exc
            self._local.conn = conn
            with self._opened_lock:
                self._opened.append(conn)
        return conn

    @contextmanager
    def _write(self) -> Iterator[sqlite3.Connection]:
        conn = self._conn()
        conn.execute("BEGIN IMMEDIATE")
        try:
            yield conn
        except BaseException:
            conn.execute("ROLLBACK")
            raise
        else:
            conn.execute("COMMIT")

    def close(self) -> None:
        """Close every connection this store opened, in any thread."""
        with self._opened_lock:
            opened, self._opened = self._opened, []
        for conn in opened:
            conn.close()
        self._local = threading.local()

    def ping(self) -> None:
        try:
            self._conn().execute("SELECT 1 FROM jobs LIMIT 1").fetchall()
        except sqlite3.Error as exc:
            raise StoreUnavailable(f"The job store at {self.path} does not answer: {exc}") from exc
