"""How a committed job reaches a worker process.

- no broker: the local pool's processes poll the store (:class:`LocalDispatch`);
- ``broker_url`` set: the job ID is sent to Celery (:class:`CeleryDispatch`), and a
  :class:`Sweeper` re-sends jobs whose worker died or whose message was lost.

The store stays the source of truth either way; the broker only delivers job IDs.
"""

from __future__ import annotations

from typing import Protocol

from worker.settings import WorkerSettings
from worker.store.base import JobStore

__all__ = ["Dispatcher", "LocalDispatch", "make_dispatcher"]


class Dispatcher(Protocol):
    """Hands committed jobs to the workers."""

    def dispatch(self, job_id: str, time_limit_s: float) -> None:
        """Make the job reach a worker; never raises for a broker outage (the job is
        committed, and the sweeper sends it again)."""

    def waiting_messages(self) -> int | None:
        """Messages waiting in the broker for a worker to take them, or None when
        there is no broker or it cannot say."""

    def close(self) -> None: ...


class LocalDispatch:
    """The local pool polls the store, so there is nothing to send."""

    def dispatch(self, job_id: str, time_limit_s: float) -> None:
        return None

    def waiting_messages(self) -> int | None:
        return None

    def close(self) -> None:
        return None


def make_dispatcher(settings: WorkerSettings, store: JobStore) -> Dispatcher:
    """The dispatcher the settings call for."""
    if not settings.broker_url:
        return LocalDispatch()
    from worker.dispatch.celery.dispatch import CeleryDispatch

    return CeleryDispatch(settings, store)
