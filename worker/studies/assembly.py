"""Assembling a study: every design's row, the non-dominated set and the best designs.

The chunks' results are read one at a time (a study's assembly streams them from the
store) into one table: design index, varied parameters, objective values (NaN where
the process reported none) and, for an infeasible design, why.  A chunk that failed
(with ``allow_partial``) leaves its designs missing, counted and named in the result.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.contract import ChildEnd
from worker.studies.pareto import non_dominated
from worker.studies.spec import StudySpec

__all__ = ["MAX_LISTED", "StudyTable", "collect", "entry", "pareto_rows", "summary"]

#: Most designs a result document lists in ``pareto`` (the data files hold them all).
MAX_LISTED = 1000
#: Most distinct reasons of infeasibility listed.
MAX_REASONS = 20


@dataclass(frozen=True)
class StudyTable:
    """Every evaluated design, in index order: ``index`` (n,), ``parameters`` (n, d),
    ``objectives`` (n, k, NaN where none), ``reasons`` (n, None where feasible)."""

    index: NDArray[np.int64]
    parameters: NDArray[np.float64]
    objectives: NDArray[np.float64]
    reasons: list[str | None]
    missing_chunks: list[str]

    @property
    def feasible(self) -> NDArray[np.bool_]:
        return np.array([r is None for r in self.reasons], dtype=bool)


def collect(
    spec: StudySpec, children: Iterable[tuple[ChildEnd, Mapping[str, Any] | None]]
) -> StudyTable:
    """The table of every chunk's rows (chunks without a result are listed as missing)."""
    d, k = len(spec.designs.names), len(spec.objectives)
    index: list[int] = []
    parameters: list[list[float]] = []
    objectives: list[list[float]] = []
    reasons: list[str | None] = []
    missing: list[str] = []
    for end, result in children:
        if result is None:
            missing.append(end.job_id)
            continue
        for row in result["rows"]:
            index.append(int(row["index"]))
            parameters.append([float(v) for v in row["parameters"]])
            objectives.append([math.nan if v is None else float(v) for v in row["objectives"]])
            reasons.append(row["reason"])
    order = np.argsort(np.asarray(index, dtype=np.int64), kind="stable")
    return StudyTable(
        index=np.asarray(index, dtype=np.int64)[order],
        parameters=np.asarray(parameters, dtype=np.float64).reshape(-1, d)[order],
        objectives=np.asarray(objectives, dtype=np.float64).reshape(-1, k)[order],
        reasons=[reasons[i] for i in order],
        missing_chunks=missing,
    )


def entry(spec: StudySpec, table: StudyTable, row: int) -> dict[str, Any]:
    """One design as the result lists it: its index, parameters and objectives."""
    values = table.objectives[row]
    return {
        "index": int(table.index[row]),
        "parameters": dict(zip(spec.designs.names, table.parameters[row].tolist(), strict=True)),
        "objectives": {
            name: None if math.isnan(v) else float(v)
            for name, v in zip(spec.objectives, values.tolist(), strict=True)
        },
    }


def pareto_rows(spec: StudySpec, table: StudyTable) -> NDArray[np.intp]:
    """Rows of the non-dominated feasible designs (ascending)."""
    maximise = [goal == "max" for goal in spec.objectives.values()]
    values = np.where(table.feasible[:, None], table.objectives, np.nan)
    return non_dominated(values, maximise)


def best_rows(spec: StudySpec, table: StudyTable) -> dict[str, list[int]]:
    """Per objective, the rows of its best feasible designs (ties by design index)."""
    best: dict[str, list[int]] = {}
    feasible = np.flatnonzero(table.feasible)
    for column, (name, goal) in enumerate(spec.objectives.items()):
        values = table.objectives[feasible, column]
        key = -values if goal == "max" else values
        order = np.lexsort((table.index[feasible], key))
        best[name] = feasible[order[: spec.best_count]].tolist()
    return best


def summary(spec: StudySpec, table: StudyTable) -> dict[str, Any]:
    """The result document's numbers: counts, reasons, the Pareto set, the best."""
    count = spec.designs.count
    feasible = table.feasible
    front = pareto_rows(spec, table)
    reasons = Counter(r for r in table.reasons if r is not None)
    return {
        "count": count,
        "evaluated": int(table.index.size),
        "feasible": int(feasible.sum()),
        "missing": count - int(table.index.size),
        "missing_chunks": table.missing_chunks,
        "infeasible_reasons": [
            {"reason": reason, "designs": n} for reason, n in reasons.most_common(MAX_REASONS)
        ],
        "parameters": list(spec.designs.names),
        "objectives": dict(spec.objectives),
        "pareto_size": int(front.size),
        "pareto": [entry(spec, table, int(row)) for row in front[:MAX_LISTED]],
        "best": {
            name: [entry(spec, table, row) for row in rows]
            for name, rows in best_rows(spec, table).items()
        },
    }
