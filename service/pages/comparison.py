"""Jobs of one process side by side: every input and every result number in one row
per place, the rows that differ marked (numbers with their difference from the first
job), and the plots of each job next to each other.

Places are dotted paths (``grid.points_per_axis``, ``links[0].length``).  A list of up
to :data:`SHORT_LIST` scalars is one value (shown as JSON); a longer one is summarised
by its length (the maps' arrays stay in their files and plots).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from typing import Any

from service.pages.job_timing import duration_text
from worker.contract import ArtifactInfo, JobRecord

__all__ = ["SHORT_LIST", "comparison_context", "flat_values"]

#: Lists of at most this many scalars are compared as one value.
SHORT_LIST = 12
#: Rows shown per table at most.
_MAX_ROWS = 400
_PLOTS = ("image/png", "image/svg+xml")


def _is_scalar(value: Any) -> bool:
    return value is None or isinstance(value, str | int | float | bool)


def flat_values(value: Any, prefix: str = "") -> dict[str, Any]:
    """Every leaf of ``value`` by its dotted place; short lists of scalars whole, long
    ones as ``"[n items]"``."""
    if isinstance(value, Mapping):
        flat: dict[str, Any] = {}
        for key, item in value.items():
            flat.update(flat_values(item, f"{prefix}.{key}" if prefix else str(key)))
        return flat
    if isinstance(value, list):
        if all(_is_scalar(v) for v in value):
            return {prefix: value if len(value) <= SHORT_LIST else f"[{len(value)} items]"}
        if len(value) > SHORT_LIST:
            return {prefix: f"[{len(value)} items]"}
        flat = {}
        for index, item in enumerate(value):
            flat.update(flat_values(item, f"{prefix}[{index}]"))
        return flat
    return {prefix: value}


def _number(value: Any) -> float | None:
    if isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value):
        return float(value)
    return None


def _shown(value: Any) -> str:
    if value is None:
        return "—"
    if isinstance(value, float):
        return f"{value:.6g}"
    return value if isinstance(value, str) else json.dumps(value)


def _rows(columns: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """One row per place: each job's value, whether they differ and, for numbers, each
    job's difference from the first job."""
    places = list(dict.fromkeys(p for column in columns for p in column))
    rows = []
    for place in places[:_MAX_ROWS]:
        values = [column.get(place) for column in columns]
        numbers = [_number(v) for v in values]
        differs = any(json.dumps(v) != json.dumps(values[0]) for v in values[1:])
        cells = []
        for index, (value, number) in enumerate(zip(values, numbers, strict=True)):
            delta = ""
            if index and differs and number is not None and numbers[0] is not None:
                delta = f"{number - numbers[0]:+.4g}"
            cells.append({"value": _shown(value), "delta": delta})
        rows.append({"place": place, "cells": cells, "differs": differs})
    return rows


def _plots(jobs: Sequence[JobRecord]) -> list[dict[str, Any]]:
    """One row per plot name: each job's image (its PNG, else its SVG), or none."""

    def chosen(artifacts: Sequence[ArtifactInfo]) -> dict[str, ArtifactInfo]:
        by_stem: dict[str, ArtifactInfo] = {}
        for a in artifacts:
            if a.media_type in _PLOTS:
                stem = a.name.rsplit(".", 1)[0]
                if stem not in by_stem or a.media_type == "image/png":
                    by_stem[stem] = a
        return by_stem

    per_job = [chosen(j.artifacts) for j in jobs]
    stems = list(dict.fromkeys(s for plots in per_job for s in plots))
    return [
        {
            "title": next(p[s].title for p in per_job if s in p) or s,
            "images": [
                None if s not in p else
                {"href": f"/v1/jobs/{j.job_id}/results/{p[s].name}",
                 "alt": f"{p[s].title} ({j.job_id[:8]})"}
                for j, p in zip(jobs, per_job, strict=True)
            ],
        }
        for s in stems
    ]  # fmt: skip


def comparison_context(
    jobs: Sequence[JobRecord], results: Sequence[Mapping[str, Any] | None]
) -> dict[str, Any]:
    """The compare page's context for ``jobs`` of one process (``results``: each one's
    result, None if it has none)."""
    inputs = _rows([flat_values(dict(j.inputs)) for j in jobs])
    outputs = _rows([
        flat_values({k: v for k, v in (r or {}).items() if k not in ("notes", "paper_errata")})
        for r in results
    ])  # fmt: skip
    durations = [
        duration_text((j.finished - j.started).total_seconds()) if j.started and j.finished else ""
        for j in jobs
    ]
    return {
        "jobs": [
            {"id": j.job_id, "short": j.job_id[:8], "status": j.status.value, "duration": d}
            for j, d in zip(jobs, durations, strict=True)
        ],
        "process_id": jobs[0].process_id,
        "inputs": inputs,
        "input_differences": sum(1 for r in inputs if r["differs"]),
        "outputs": outputs,
        "output_differences": sum(1 for r in outputs if r["differs"]),
        "plots": _plots(jobs),
    }
