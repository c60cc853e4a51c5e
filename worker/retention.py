"""The retention sweeper: deletes expired jobs, their files and, later, their tombstones.

One runs in every process that serves the API or supervises workers (the local pool's
supervisor, an API without a pool, each Celery worker's main process); running several
is harmless, since each deletion is one short transaction that checks the job is still
expired.  Every ``sweep_seconds`` it deletes expired jobs in batches of
:data:`BATCH` (at most :data:`MAX_BATCHES` a sweep, so one sweep never holds the store
for long), then tombstones past their grace.  What expires when is
:mod:`worker.store.retention`'s.
"""

from __future__ import annotations

import logging
import threading

from worker.errors import StoreUnavailable
from worker.settings import WorkerSettings
from worker.store.base import RetentionPort

__all__ = ["BATCH", "MAX_BATCHES", "RetentionSweeper"]

log = logging.getLogger("dexlab.retention")

#: Jobs deleted per transaction, and batches per sweep.
BATCH = 50
MAX_BATCHES = 20


class RetentionSweeper(threading.Thread):
    """Every ``settings.sweep_seconds``: :meth:`sweep` until told to stop."""

    def __init__(self, settings: WorkerSettings, store: RetentionPort) -> None:
        super().__init__(name="dexlab-retention", daemon=True)
        self.settings = settings
        self.store = store
        self._stopping = threading.Event()

    def stop(self) -> None:
        self._stopping.set()

    def sweep(self) -> int:
        """One pass; the number of jobs deleted."""
        deleted = 0
        for _ in range(MAX_BATCHES):
            batch = self.store.expire_jobs(BATCH)
            deleted += len(batch)
            if len(batch) < BATCH:
                break
        if deleted:
            log.info("deleted %d expired job(s) and their files", deleted)
        self.store.forget_expired(BATCH * MAX_BATCHES)
        return deleted

    def run(self) -> None:
        while not self._stopping.wait(self.settings.sweep_seconds):
            try:
                self.sweep()
            except StoreUnavailable as exc:  # the next sweep tries again
                log.warning("retention sweep skipped: %s", exc)
            except Exception:
                log.exception("retention sweep failed")
