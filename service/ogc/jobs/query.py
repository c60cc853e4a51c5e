"""The job-list query of the façade: OGC's ``processID``, ``status``, ``type``,
``datetime``, ``minDuration``, ``maxDuration`` and ``limit``, as a store filter.

``datetime`` is an RFC 3339 date-time (an instant: jobs created then, to the
microsecond) or an interval ``start/end`` whose open end is ``..`` or empty; it
bounds ``created``, both ends inclusive.  ``type`` matches the statusInfo ``type``:
every dexlab job is a ``process`` job.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from datetime import datetime
from urllib.parse import urlencode

from worker.contract import JobStatus
from worker.store.base import JobFilter

__all__ = ["MAX_PAGE", "listing_filter", "page_query", "parse_datetime_interval"]

#: The most jobs one page holds, whatever ``limit`` asks (the standard lets a server
#: return fewer; ``next`` continues).
MAX_PAGE = 1000

_DATE_TIME = re.compile(
    r"[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}(?:\.[0-9]+)?(?:Z|[+-][0-9]{2}:[0-9]{2})"
)


def _date_time(text: str) -> datetime:
    value = text.strip().upper()
    if not _DATE_TIME.fullmatch(value):
        raise ValueError(
            "must be an RFC 3339 date-time with a time zone (e.g. 2024-05-04T10:13:00Z), "
            f"got {text!r}"
        )
    try:
        return datetime.fromisoformat(value)
    except ValueError:
        raise ValueError(f"is not a valid date-time: {text!r}") from None


def parse_datetime_interval(text: str) -> tuple[datetime | None, datetime | None]:
    """``(start, end)`` of an OGC ``datetime`` value (None: open).  Raises ValueError
    saying what is wrong."""
    if "/" not in text:
        instant = _date_time(text)
        return instant, instant
    start_text, _, end_text = text.partition("/")
    if "/" in end_text:
        raise ValueError(f"must be a date-time or one interval start/end, got {text!r}")
    start = None if start_text.strip() in ("", "..") else _date_time(start_text)
    end = None if end_text.strip() in ("", "..") else _date_time(end_text)
    if start is None and end is None:
        raise ValueError("an interval needs at least one end (../.. selects nothing in it)")
    if start is not None and end is not None and start > end:
        raise ValueError(f"the interval ends before it starts: {text!r}")
    return start, end


def listing_filter(
    process_ids: Sequence[str] | None,
    statuses: Sequence[JobStatus] | None,
    types: Sequence[str] | None,
    interval: tuple[datetime | None, datetime | None] | None,
    min_duration_s: int | None,
    max_duration_s: int | None,
) -> JobFilter:
    """The store filter of the query (an empty result when ``type`` excludes process
    jobs)."""
    statuses_set = frozenset(statuses) if statuses else None
    if types and "process" not in types:
        statuses_set = frozenset()
    start, end = interval if interval is not None else (None, None)
    return JobFilter(
        statuses=statuses_set,
        process_ids=frozenset(process_ids) if process_ids else None,
        created_from=start,
        created_to=end,
        min_duration_s=min_duration_s,
        max_duration_s=max_duration_s,
    )


def page_query(params: Sequence[tuple[str, str]], cursor: str | None) -> str:
    """The query string of a page: the request's parameters (its cursor replaced)."""
    kept = [(k, v) for k, v in params if k != "cursor"]
    if cursor is not None:
        kept.append(("cursor", cursor))
    return urlencode(kept)
