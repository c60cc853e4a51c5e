"""Progress reporting from a running job back to the store."""

from __future__ import annotations

import logging
import time

from worker.store.base import JobStore

__all__ = ["StoreProgress"]

log = logging.getLogger("dexlab.worker")


class StoreProgress:
    """A :class:`worker.contract.JobContext` writing progress to the store.

    Writes are throttled to one every ``min_interval_s`` (the final 100 always goes
    through) and fenced by the attempt's lease token.  They are best-effort: a store
    that is locked or down loses a progress update, never the job.
    """

    def __init__(
        self, store: JobStore, job_id: str, lease_token: str, min_interval_s: float = 0.25
    ) -> None:
        self._store = store
        self._job_id = job_id
        self._token = lease_token
        self._min_interval_s = min_interval_s
        self._last_write = 0.0
        self._last_percent = -1.0

    def report_progress(self, percent: float, message: str = "") -> None:
        percent = max(0.0, min(100.0, float(percent)))
        now = time.monotonic()
        if percent < 100.0 and now - self._last_write < self._min_interval_s:
            return
        if percent < self._last_percent:
            percent = self._last_percent  # progress never goes backwards
        try:
            self._store.report_progress(self._job_id, self._token, percent, message)
        except Exception as exc:  # best-effort: the next report tries again
            log.warning("job %s: progress not recorded (%s)", self._job_id, exc)
        self._last_write = now
        self._last_percent = percent
