"""Job stores: one interface (:class:`JobStore`), chosen by URL."""

from __future__ import annotations

from worker.store.base import (
    CallbackClaim,
    Claim,
    ClaimAttempt,
    HeartbeatAck,
    JobFilter,
    JobPage,
    JobStore,
    NewJob,
    QueueLimits,
    StoredArtifact,
    WorkerInfo,
)
from worker.store.sqlite import SqliteJobStore

__all__ = [
    "CallbackClaim",
    "Claim",
    "ClaimAttempt",
    "HeartbeatAck",
    "JobFilter",
    "JobPage",
    "JobStore",
    "NewJob",
    "QueueLimits",
    "StoredArtifact",
    "WorkerInfo",
    "open_store",
]


def open_store(url: str, retry_s: float = 5.0) -> JobStore:
    """The store behind ``url`` (``sqlite:///path`` or ``postgresql://...``), its schema
    created or migrated.  Each call retries transient faults for ``retry_s`` seconds."""
    store: JobStore
    if url.startswith("sqlite:///"):
        store = SqliteJobStore.from_url(url, retry_s=retry_s)
    elif url.startswith(("postgresql://", "postgres://", "postgresql+psycopg://")):
        # optional: PostgreSQL (psycopg) is loaded only for a postgresql:// store
        from worker.store.postgres import PostgresJobStore

        store = PostgresJobStore(
            url.replace("postgresql+psycopg://", "postgresql://", 1), retry_s=retry_s
        )
    else:
        raise ValueError(
            "The 'store_url' setting must be a sqlite:/// or postgresql:// URL. "
            f"Got {url!r} instead."
        )
    store.initialise()
    return store
