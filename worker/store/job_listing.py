"""The WHERE clause of a job listing, built from a :class:`JobFilter` in portable SQL."""

from __future__ import annotations

from datetime import datetime
from typing import Any

from worker.contract import JobStatus
from worker.store.base import JobFilter

__all__ = ["filter_clauses"]

#: Documents print times to the microsecond; a bound matches what they print.
_HALF_MICROSECOND = 5e-7


def _placeholders(values: list[Any]) -> str:
    return ", ".join("?" for _ in values)


def _epoch(value: datetime) -> float:
    return value.timestamp()


def filter_clauses(where: JobFilter, now: float) -> tuple[list[str], list[Any]]:
    """``(clauses, params)`` selecting the jobs ``where`` describes (``?`` placeholders;
    ``now`` is the time a running job's duration runs to)."""
    clauses: list[str] = []
    params: list[Any] = []
    if where.statuses is not None:
        statuses = sorted(s.value for s in where.statuses)
        if not statuses:
            return ["1 = 0"], []
        clauses.append(f"status IN ({_placeholders(statuses)})")
        params.extend(statuses)
    if where.process_ids is not None:
        process_ids = sorted(where.process_ids)
        if not process_ids:
            return ["1 = 0"], []
        clauses.append(f"process_id IN ({_placeholders(process_ids)})")
        params.extend(process_ids)
    if where.created_from is not None:
        clauses.append("created >= ?")
        params.append(_epoch(where.created_from) - _HALF_MICROSECOND)
    if where.created_to is not None:
        clauses.append("created <= ?")
        params.append(_epoch(where.created_to) + _HALF_MICROSECOND)
    if where.min_duration_s is not None or where.max_duration_s is not None:
        # Only jobs that ran have a duration: started, and not back in the queue.
        clauses.append("started IS NOT NULL AND status <> ?")
        params.append(JobStatus.ACCEPTED.value)
        duration = "(COALESCE(finished, ?) - started)"
        if where.min_duration_s is not None:
            clauses.append(f"{duration} >= ?")
            params.extend([now, where.min_duration_s])
        if where.max_duration_s is not None:
            clauses.append(f"{duration} <= ?")
            params.extend([now, where.max_duration_s])
    return clauses, params
