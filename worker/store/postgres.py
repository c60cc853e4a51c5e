"""The shared job store on PostgreSQL (psycopg 3), for many API replicas and workers.

Installed with the ``distributed`` extra.  Each thread keeps its own autocommit
connection; writes run in explicit transactions, rows are locked with
``SELECT ... FOR UPDATE`` (claims skip rows another worker has locked), and concurrent
migrations are serialised by an advisory lock.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from typing import Any, ClassVar

from worker.errors import StoreUnavailable
from worker.store.sql import SqlJobStore

__all__ = ["PostgresJobStore"]

#: Key of the advisory lock held while migrating (any constant unique to dexlab).
_MIGRATION_LOCK = 0x646578_6C6162


class PostgresJobStore(SqlJobStore):
    """The job store on a PostgreSQL database (``postgresql://...``)."""

    lock_clause = " FOR UPDATE"
    ddl_types: ClassVar[Mapping[str, str]] = {
        "seq_pk": "BIGSERIAL PRIMARY KEY",
        "blob": "BYTEA",
        "float": "DOUBLE PRECISION",
    }

    def __init__(self, url: str) -> None:
        try:
            import psycopg  # noqa: F401
        except ImportError as exc:  # pragma: no cover - depends on the install
            raise StoreUnavailable(
                "A postgresql:// store needs the 'distributed' extra: "
                "pip install 'dexlab[distributed]'."
            ) from exc
        self.url = url
        self._local = threading.local()
        self._opened: list[Any] = []
        self._opened_lock = threading.Lock()

    @property
    def location(self) -> str:
        return self.url.split("@")[-1]  # never echo credentials

    def _sql(self, query: str) -> str:
        return query.replace("?", "%s")

    def _conn(self) -> Any:
        import psycopg
        from psycopg.rows import dict_row

        conn = getattr(self._local, "conn", None)
        if conn is not None and conn.closed:
            conn = None
        if conn is None:
            try:
                conn = psycopg.connect(
                    self.url, autocommit=True, row_factory=dict_row, connect_timeout=10
                )
            except psycopg.Error as exc:
                raise StoreUnavailable(
                    f"Cannot connect to the job store at {self.location}: {exc}"
                ) from exc
            self._local.conn = conn
            with self._opened_lock:
                self._opened.append(conn)
        return conn

    @contextmanager
    def _write(self) -> Iterator[Any]:
        conn = self._conn()
        with conn.transaction():
            yield conn

    def _lock_schema(self, conn: Any) -> None:
        self._exec(conn, "SELECT pg_advisory_xact_lock(?)", (_MIGRATION_LOCK,))

    def close(self) -> None:
        """Close every connection this store opened, in any thread."""
        with self._opened_lock:
            opened, self._opened = self._opened, []
        for conn in opened:
            conn.close()
        self._local = threading.local()

    def ping(self) -> None:
        import psycopg

        try:
            self._exec(self._conn(), "SELECT 1 FROM jobs LIMIT 1").fetchall()
        except psycopg.Error as exc:
            self.close()
            raise StoreUnavailable(
                f"The job store at {self.location} does not answer: {exc}"
            ) from exc
