"""The ``dexlab jobs`` table: one line per job within 80 columns, with durations.

Job IDs are shown by their shortest unique prefix (every command taking a job accepts
one); the process and message columns are cut with an ellipsis rather than wrapped.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from datetime import UTC, datetime
from typing import Any

from rich.table import Table
from rich.text import Text

from dexlab.cli.job_ids import short_ids
from dexlab.documents import JobStatus

__all__ = ["duration_s", "duration_text", "status_table"]


def _moment(text: Any) -> datetime | None:
    if not isinstance(text, str) or not text:
        return None
    try:
        moment = datetime.fromisoformat(text.replace("Z", "+00:00"))
    except ValueError:
        return None
    return moment if moment.tzinfo is not None else moment.replace(tzinfo=UTC)


def duration_s(document: Mapping[str, Any], now: datetime | None = None) -> float | None:
    """Seconds a job has run: ``finished - started``, or ``now - started`` while it runs;
    None before it starts (or when back in the queue)."""
    started = _moment(document.get("started"))
    if started is None or document.get("status") == "accepted":
        return None
    finished = _moment(document.get("finished"))
    end = finished or now or datetime.now(UTC)
    return max(0.0, (end - started).total_seconds())


def duration_text(seconds: float | None) -> str:
    """``0.4 s``, ``12 s``, ``3m 05s``, ``2h 10m``, ``3d 4h``; empty for None."""
    if seconds is None:
        return ""
    if seconds < 10:
        return f"{seconds:.1f} s"
    whole = round(seconds)
    if whole < 60:
        return f"{whole} s"
    minutes, secs = divmod(whole, 60)
    if minutes < 60:
        return f"{minutes}m {secs:02d}s"
    hours, minutes = divmod(minutes, 60)
    if hours < 24:
        return f"{hours}h {minutes:02d}m"
    days, hours = divmod(hours, 24)
    return f"{days}d {hours}h"


def status_table(statuses: Sequence[JobStatus], now: datetime | None = None) -> Table:
    """Jobs, one line each: short ID, process, status, progress, created (UTC, to the
    minute), duration and message."""
    table = Table(title="Jobs, newest first", title_justify="left", box=None,
                  pad_edge=False, header_style="bold underline")  # fmt: skip
    table.add_column("Job", no_wrap=True, style="bold", min_width=8)
    table.add_column("Process", no_wrap=True, overflow="ellipsis", max_width=18)
    table.add_column("Status", no_wrap=True, min_width=10)
    table.add_column("%", no_wrap=True, justify="right", min_width=3)
    table.add_column("Created", no_wrap=True, min_width=11)
    table.add_column("Took", no_wrap=True, justify="right", min_width=6)
    # Wrappable for Rich's fitting (it narrows such columns first); each message stays
    # one line, cut with an ellipsis.
    table.add_column("Message", overflow="ellipsis")
    for status, job in zip(statuses, short_ids([s.job_id for s in statuses]), strict=True):
        created = str(status.document.get("created") or "")[5:16].replace("T", " ")
        took = duration_text(duration_s(status.document, now))
        table.add_row(Text(job), Text(status.process_id), Text(status.status),
                      str(status.progress), created, took,
                      Text(status.message, no_wrap=True, overflow="ellipsis"))  # fmt: skip
    return table
