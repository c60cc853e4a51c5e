"""Assembling a study: every design's row, the non-dominated set and the best designs.

The chunks are read one at a time (a study's assembly streams them from the store:
each chunk's result document and its ``rows.npz``, :mod:`.rows`) into one table of
arrays: design index, varied parameters (rebuilt from the study's inputs, a chunk's
block at a time), objective values (NaN where the process reported none), reason
codes and fields; the reasons' messages are counted, never kept per design.  A chunk
that failed (with ``allow_partial``) leaves its designs missing, counted and named in
the result.  Nothing here holds a Python object per design.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.contract import ChildEnd
from worker.processes import ChildFiles
from worker.studies.pareto import non_dominated
from worker.studies.rows import FEASIBLE, REASON_CODES, ROWS_FILE, ChunkRows, ReasonTally
from worker.studies.spec import StudySpec

__all__ = ["MAX_LISTED", "StudyTable", "collect", "entry", "pareto_rows", "summary"]

#: Most designs a result document lists in ``pareto`` (the data files hold them all).
MAX_LISTED = 1000
#: Most distinct reasons of infeasibility listed.
MAX_REASONS = 20


@dataclass(frozen=True)
class StudyTable:
    """Every evaluated design, in index order: ``index`` (n,), ``parameters`` (n, d),
    ``objectives`` (n, k, NaN where none), ``codes`` (n,) reason codes (0: feasible),
    ``fields`` (n,) indices into ``field_names`` (0: none), the reasons counted, the
    chunks that failed and the engines that evaluated the chunks."""

    index: NDArray[np.int64]
    parameters: NDArray[np.float64]
    objectives: NDArray[np.float64]
    codes: NDArray[np.int8]
    fields: NDArray[np.int16]
    field_names: tuple[str, ...]
    tally: ReasonTally
    missing_chunks: list[str]
    engines: tuple[str, ...] = ()

    @property
    def feasible(self) -> NDArray[np.bool_]:
        return np.asarray(self.codes == FEASIBLE)


def collect(
    spec: StudySpec,
    children: Iterable[tuple[ChildEnd, Mapping[str, Any] | None]],
    files: ChildFiles,
) -> StudyTable:
    """The table of every chunk's rows, read a chunk at a time (chunks without a result
    are listed as missing)."""
    space = spec.designs
    count, d, k = space.count, len(space.names), len(spec.objectives)
    parameters = np.full((count, d), np.nan)
    objectives = np.full((count, k), np.nan)
    codes = np.zeros(count, dtype=np.int8)
    fields = np.zeros(count, dtype=np.int16)
    evaluated = np.zeros(count, dtype=bool)
    names: list[str] = [""]
    tally = ReasonTally()
    missing: list[str] = []
    engines: list[str] = []
    for end, result in children:
        if result is None:
            missing.append(end.job_id)
            continue
        rows = ChunkRows.stored(result, files(end.job_id, ROWS_FILE), k)
        block = slice(rows.start, rows.stop)
        parameters[block] = space.block(rows.start, rows.stop)
        objectives[block] = rows.objectives
        codes[block] = rows.codes
        remap = np.array([_place(names, name) for name in rows.field_names], dtype=np.int16)
        fields[block] = remap[rows.fields]
        evaluated[block] = True
        tally.merge(rows.tally)
        if rows.engine not in engines:
            engines.append(rows.engine)
    if evaluated.all():
        index = np.arange(count, dtype=np.int64)
        return StudyTable(index, parameters, objectives, codes, fields, tuple(names), tally,
                          missing, tuple(engines))  # fmt: skip
    keep = np.flatnonzero(evaluated)
    return StudyTable(keep.astype(np.int64), parameters[keep], objectives[keep], codes[keep],
                      fields[keep], tuple(names), tally, missing, tuple(engines))  # fmt: skip


def _place(names: list[str], name: str) -> int:
    if name not in names:
        names.append(name)
    return names.index(name)


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


def summary(spec: StudySpec, table: StudyTable, front: NDArray[np.intp]) -> dict[str, Any]:
    """The result document's numbers: counts, reasons, the Pareto set, the best."""
    count = spec.designs.count
    feasible = table.feasible
    by_code = np.bincount(table.codes.astype(np.intp), minlength=len(REASON_CODES))
    return {
        "count": count,
        "evaluated": int(table.index.size),
        "feasible": int(feasible.sum()),
        "missing": count - int(table.index.size),
        "missing_chunks": table.missing_chunks,
        "infeasible": {
            name: int(by_code[code]) for code, name in enumerate(REASON_CODES) if code != FEASIBLE
        },
        "infeasible_reasons": table.tally.most_common(MAX_REASONS),
        "parameters": list(spec.designs.names),
        "objectives": dict(spec.objectives),
        "pareto_size": int(front.size),
        "pareto": [entry(spec, table, int(row)) for row in front[:MAX_LISTED]],
        "best": {
            name: [entry(spec, table, row) for row in rows]
            for name, rows in best_rows(spec, table).items()
        },
    }
