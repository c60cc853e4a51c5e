"""How a worker loop with nothing to claim waits for work, alive meanwhile.

A local pool's process sleeps on its pool's wake-up socket
(:mod:`worker.dispatch.wake_ups`) until a hint says jobs were queued, or for
``poll_seconds`` at most: that poll is the safety net for a lost hint.  Without a
socket it claims every ``poll_seconds``.  Either way it beats its worker registration
every ``heartbeat_seconds`` while it sleeps (readiness and synchronous answers count
the workers that beat lately), so a long poll interval never makes an idle worker look
dead.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

from worker.dispatch.wake_ups import WakeUpListener
from worker.settings import WorkerSettings
from worker.store.base import Claim, WorkersPort

__all__ = ["IdleWait"]


class IdleWait:
    """A worker loop's claims and sleeps between jobs, and its registration beats."""

    def __init__(
        self,
        settings: WorkerSettings,
        store: WorkersPort,
        worker_id: str,
        stop: threading.Event,
        wake_ups: WakeUpListener | None,
    ) -> None:
        self._settings = settings
        self._store = store
        self._worker_id = worker_id
        self._stop = stop
        self.wake_ups = wake_ups
        self._next_beat = time.monotonic() + settings.heartbeat_seconds

    def beat_if_due(self) -> None:
        """Tell the store the worker is alive, once every ``heartbeat_seconds``."""
        now = time.monotonic()
        if now >= self._next_beat:
            self._store.worker_heartbeat(self._worker_id)
            self._next_beat = now + self._settings.heartbeat_seconds

    def claim_or_sleep(self, claim: Callable[[], Claim | None]) -> Claim | None:
        """``claim()``'s job; or, with nothing to claim, None after a sleep until a
        wake-up hint comes (``poll_seconds`` at most).  Hints that came in since the
        claim ask for one more (they may announce jobs queued after it); a claim made
        on hints that announced more jobs passes the rest on, to wake the next idle
        process of the pool."""
        hints = self.wake_ups
        claimed = claim()
        if claimed is None and hints is not None and hints.take():
            claimed = claim()
        if claimed is not None:
            if hints is not None:
                hints.pass_on()
            return claimed
        if hints is not None:
            hints.drop()  # the jobs they announced are taken
        self._sleep(time.monotonic() + self._settings.poll_seconds)
        return None

    def interrupt(self) -> None:
        """Cut a sleep short (the stop event is set; safe in a signal handler)."""
        if self.wake_ups is not None:
            self.wake_ups.interrupt()

    def _sleep(self, until: float) -> None:
        """Sleep until a hint comes, the stop event is set, or the monotonic time
        ``until``, beating when due."""
        while not self._stop.is_set():
            self.beat_if_due()
            now = time.monotonic()
            if now >= until:
                return
            left = min(until, self._next_beat) - now
            if self.wake_ups is None:
                self._stop.wait(left)
            else:
                self.wake_ups.wait(left)
                if self.wake_ups.held:
                    return
