"""Job stores: one interface (:class:`JobStore`), chosen by URL."""

from __future__ import annotations

from worker.store.base import (
    Claim,
    ClaimAttempt,
    HeartbeatAck,
    JobPage,
    JobStore,
    NewJob,
    WorkerInfo,
)

__all__ = [
    "Claim",
    "ClaimAttempt",
    "HeartbeatAck",
    "JobPage",
    "JobStore",
    "NewJob",
    "WorkerInfo",
    "open_store",
]


def open_store(url: str) -> JobStore:
    """The store behind ``url`` (``sqlite:///path`` or ``postgresql://...``), its schema
    created or migrated."""
    store: JobStore
    if url.startswith("sqlite:///"):
        from worker.store.sqlite import SqliteJobStore

        store = SqliteJobStore.from_url(url)
    elif url.startswith(("postgresql://", "postgres://", "postgresql+psycopg://")):
        from worker.store.postgres import PostgresJobStore

        store = PostgresJobStore(url.replace("postgresql+psycopg://", "postgresql://", 1))
    else:
        raise ValueError(
            "The 'store_url' setting must be a sqlite:/// or postgresql:// URL. "
            f"Got {url!r} instead."
        )
    store.initialise()
    return store
