"""Monotonic progress reporting, with sub-tasks mapped onto slices of 0-100 %."""

from __future__ import annotations

from collections.abc import Callable

from worker.contract import JobContext

__all__ = ["ProgressReporter"]


class ProgressReporter:
    """Forwards progress to a :class:`JobContext`, never letting the percentage fall."""

    def __init__(self, ctx: JobContext) -> None:
        self._ctx = ctx
        self._percent = 0.0

    def report(self, percent: float, message: str) -> None:
        """Report ``percent`` (clipped to [last reported, 100]) with ``message``."""
        self._percent = min(100.0, max(self._percent, float(percent)))
        self._ctx.report_progress(self._percent, message)

    def span(self, start: float, end: float, message: str) -> Callable[[int, int], None]:
        """A ``(done, total)`` callback that reports ``start + (end - start) * done/total``."""

        def on_progress(done: int, total: int) -> None:
            fraction = done / total if total > 0 else 1.0
            self.report(start + (end - start) * fraction, message)

        return on_progress
