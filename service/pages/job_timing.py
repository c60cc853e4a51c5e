"""How long a job took, how long it may still take, and when it goes: for the pages.

A duration is ``finished - started`` (``now - started`` while it runs; none before it
starts or once back in the queue).  The estimate of the time left assumes the rest of
the work goes at the pace so far: ``elapsed * (100 - p) / p`` at progress ``p`` (%),
shown only while running with ``0 < p < 100``.
"""

from __future__ import annotations

from datetime import datetime

from worker.contract import JobRecord, JobStatus

__all__ = ["duration_s", "duration_text", "job_timing", "remaining_s"]

_LIVE = (JobStatus.ACCEPTED, JobStatus.RUNNING)


def duration_s(job: JobRecord, now: datetime) -> float | None:
    """Seconds the job has run (to ``now`` while running); None if it has not started."""
    if job.started is None or job.status is JobStatus.ACCEPTED:
        return None
    end = job.finished if job.finished is not None else now
    return max(0.0, (end - job.started).total_seconds())


def remaining_s(job: JobRecord, now: datetime) -> float | None:
    """Estimated seconds left for a running job, from its progress; None otherwise."""
    elapsed = duration_s(job, now)
    if job.status is not JobStatus.RUNNING or elapsed is None or not 0 < job.progress < 100:
        return None
    return elapsed * (100.0 - job.progress) / job.progress


def duration_text(seconds: float | None) -> str:
    """``0.4 s``, ``12 s``, ``3 min 05 s``, ``2 h 10 min``, ``3 d 4 h``; empty for None."""
    if seconds is None:
        return ""
    if seconds < 10:
        return f"{seconds:.1f} s"
    whole = round(seconds)
    if whole < 60:
        return f"{whole} s"
    minutes, secs = divmod(whole, 60)
    if minutes < 60:
        return f"{minutes} min {secs:02d} s"
    hours, minutes = divmod(minutes, 60)
    if hours < 24:
        return f"{hours} h {minutes:02d} min"
    days, hours = divmod(hours, 24)
    return f"{days} d {hours} h"


def job_timing(job: JobRecord, now: datetime) -> dict[str, str | bool]:
    """What a job page says about time: ``duration`` (text, with ``running`` true while
    it grows), ``eta`` (text, running jobs with progress) and ``expires`` (ISO 8601 UTC,
    set once finished)."""
    left = remaining_s(job, now)
    return {
        "duration": duration_text(duration_s(job, now)),
        "running": job.status in _LIVE,
        "eta": "" if left is None else duration_text(left),
        "expires": "" if job.expires is None else job.expires.isoformat().replace("+00:00", "Z"),
    }
