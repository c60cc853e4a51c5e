"""Progress reporting from a running job back to the store."""

from __future__ import annotations

import logging
import time

from worker.store.base import QueuePort

__all__ = ["StoreProgress"]

log = logging.getLogger("dexlab.worker")


class StoreProgress:
    """A :class:`worker.contract.JobContext` writing progress to the store.

    Writes are throttled to one every ``min_interval_s``, counted from the claim (which
    shows the attempt running at 0 %): a job shorter than that writes none, and its
    result's commit sets 100 %.  A report held back by the throttle is written by the
    next report due or by :meth:`flush` (the attempt's guard calls it at each
    heartbeat), so a long step's message shows however the job reports.  Writes are
    fenced by the attempt's lease token and best-effort: a store that is locked or down
    loses a progress update, never the job.
    """

    def __init__(
        self, store: QueuePort, job_id: str, lease_token: str, min_interval_s: float = 0.25
    ) -> None:
        self._store = store
        self._job_id = job_id
        self._token = lease_token
        self._min_interval_s = min_interval_s
        self._last_write = time.monotonic()
        self._percent = 0.0
        self._pending: tuple[float, str] | None = None

    def report_progress(self, percent: float, message: str = "") -> None:
        # Progress never goes backwards.
        self._percent = max(self._percent, max(0.0, min(100.0, float(percent))))
        self._pending = (self._percent, message)
        if time.monotonic() - self._last_write >= self._min_interval_s:
            self.flush()

    def flush(self) -> None:
        """Write the report held back, if any (from any thread)."""
        pending, self._pending = self._pending, None
        if pending is None:
            return
        self._last_write = time.monotonic()
        try:
            self._store.report_progress(self._job_id, self._token, *pending)
        except Exception as exc:  # best-effort: the next report tries again
            log.warning("job %s: progress not recorded (%s)", self._job_id, exc)
