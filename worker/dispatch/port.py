"""The dispatcher port: what the service and the sweepers ask of a way to reach the
workers (:mod:`worker.dispatch` picks the adapter; the Celery one imports only this)."""

from __future__ import annotations

from typing import Protocol

__all__ = ["Dispatcher"]


class Dispatcher(Protocol):
    """Hands committed jobs to the workers."""

    def dispatch(self, job_id: str, time_limit_s: float) -> None:
        """Make the job reach a worker; never raises for a broker outage (the job is
        committed, and the sweeper sends it again)."""

    def waiting_messages(self) -> int | None:
        """Messages waiting in the broker for a worker to take them, or None when
        there is no broker or it cannot say."""

    def close(self) -> None: ...
