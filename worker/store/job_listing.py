"""The WHERE clause of a job listing, built from a :class:`JobFilter` in portable SQL."""

from __future__ import annotations

from datetime import UTC, datetime, timedelta
from typing import Any

from worker.contract import JobStatus
from worker.store.records import JobFilter

__all__ = ["filter_clauses"]

#: Documents print times rounded to the microsecond, and a bound matches what they
#: print.  A float near 1.8e9 s is only good to 0.24 us (and `created * 1e6`, rounded to
#: a quarter, is an exact tie one time in four), so a row is first kept by a range on
#: the column itself, a microsecond wider than the bound (its index serves it), then
#: its time is rounded exactly: its distance from the bound's whole second is exact in
#: floating point, and that distance in microseconds is rounded and compared.
_MICROSECOND = 1e-6
_ROUNDED = "ROUND((created - ?) * 1000000)"
_EPOCH = datetime(1970, 1, 1, tzinfo=UTC)


def _bound(value: datetime, sign: int) -> tuple[str, list[Any]]:
    """The clause and parameters of ``created >= value`` (sign -1) or ``created <=
    value`` (sign 1), to the printed microsecond."""
    micros = (value - _EPOCH) // timedelta(microseconds=1)
    second, micro = divmod(micros, 1_000_000)
    op = "<=" if sign > 0 else ">="
    widened = micros * _MICROSECOND + sign * _MICROSECOND
    return f"created {op} ? AND {_ROUNDED} {op} ?", [widened, float(second), micro]


def _placeholders(values: list[Any]) -> str:
    return ", ".join("?" for _ in values)


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
    for value, sign in ((where.created_from, -1), (where.created_to, 1)):
        if value is not None:
            clause, values = _bound(value, sign)
            clauses.append(clause)
            params.extend(values)
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
