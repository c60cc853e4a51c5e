"""How a committed job reaches a worker process.

- no broker: the local pool's processes claim it from the store; an idle one is woken
  by a hint on its pool's wake-up socket (:class:`LocalDispatch`,
  :mod:`worker.dispatch.wake_ups`), and polls the store as a safety net;
- ``broker_url`` set: the job ID is sent to Celery (:class:`CeleryDispatch`), and a
  :class:`Sweeper` re-sends jobs whose worker died or whose message was lost.

The store stays the source of truth either way; the broker only delivers job IDs.
"""

from __future__ import annotations

from worker.dispatch.port import Dispatcher
from worker.dispatch.wake_ups import WakeUpSender, wake_up_dir
from worker.processes import ProcessRegistry
from worker.settings import WorkerSettings
from worker.store.base import JobStore

__all__ = ["Dispatcher", "LocalDispatch", "make_dispatcher"]


class LocalDispatch:
    """Wakes an idle process of each local pool of the store on this machine (the
    processes claim the job from the store; a lost hint costs a poll interval)."""

    def __init__(self, sender: WakeUpSender) -> None:
        self.sender = sender

    def dispatch(self, job_id: str, time_limit_s: float) -> None:
        self.sender.wake(1)

    def waiting_messages(self) -> int | None:
        return None

    def close(self) -> None:
        self.sender.close()


def make_dispatcher(
    settings: WorkerSettings, store: JobStore, registry: ProcessRegistry
) -> Dispatcher:
    """The dispatcher the settings call for (``registry``: the processes whose jobs it
    sends, for the longest time limit a Celery message must allow)."""
    if not settings.broker_url:
        return LocalDispatch(WakeUpSender(wake_up_dir(settings.resolved_store_url())))
    # optional: Celery is loaded only with a broker
    from worker.dispatch.celery.dispatch import CeleryDispatch

    return CeleryDispatch(settings, store, registry)
