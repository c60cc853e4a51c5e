"""Job stores: one interface (:class:`JobStore`), chosen by URL."""

from __future__ import annotations

from worker.store.base import Claim, HeartbeatAck, JobPage, JobStore, NewJob, WorkerInfo

__all__ = ["Claim", "HeartbeatAck", "JobPage", "JobStore", "NewJob", "WorkerInfo", "open_store"]


def open_store(url: str) -> JobStore:
    """The store behind ``url`` (``sqlite:///path``), schema created or migrated."""
    if url.startswith("sqlite:///"):
        from worker.store.sqlite import SqliteJobStore

        store = SqliteJobStore.from_url(url)
    else:
        raise ValueError(
            f"The 'store_url' setting must be a sqlite:/// URL. Got {url!r} instead."
        )
    store.initialise()
    return store
