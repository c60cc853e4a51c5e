"""A study's outcome: the result document, the data files and the figures."""

from __future__ import annotations

from typing import Any

import numpy as np

from worker.common.figures import figure_artifacts
from worker.contract import Artifact, JobContext, JobOutcome
from worker.processes import ChildFiles, ChildResults, ProcessDefinition
from worker.studies.assembly import StudyTable, collect, entry, pareto_rows, summary
from worker.studies.designs import GridSpace
from worker.studies.engine import choose_engine
from worker.studies.figures import (
    Marker,
    code,
    objective_label,
    objective_maps_figure,
    objective_slices_figure,
    pareto_figure,
)
from worker.studies.files import (
    designs_csv,
    designs_npz,
    objective_entry,
    objective_unit,
    parameter_unit,
)
from worker.studies.paper_points import PaperMark, paper_marks
from worker.studies.spec import StudySpec

__all__ = ["study_outcome"]


def study_outcome(
    spec: StudySpec,
    process: ProcessDefinition,
    children: ChildResults,
    files: ChildFiles,
    ctx: JobContext,
) -> JobOutcome:
    """The study of ``process`` assembled from its chunks' results and files."""
    ctx.report_progress(90.0, "assembling the chunks")
    counted: list[int] = []

    def counting(items: ChildResults) -> ChildResults:
        for item in items:
            counted.append(1)
            yield item

    table = collect(spec, counting(children), files)
    front = pareto_rows(spec, table)
    marks = paper_marks(spec, process)
    batched = table.engines == ("batched",)
    why = "" if batched else (choose_engine(spec, process).why or "a chunk ran per design")
    result: dict[str, Any] = {"process": spec.process,
                              "engine": "batched" if batched else "per-design",
                              "engine_reason": why, **summary(spec, table, front),
                              "paper_points": _paper_points(spec, table, marks),
                              "chunks": len(counted)}  # fmt: skip
    ctx.report_progress(95.0, "data files and figures")
    artifacts: tuple[Artifact, ...] = (
        designs_csv(spec, process, table),
        designs_npz(spec, process, table, front),
    )
    if spec.plots:
        artifacts += _figures(spec, process, table, marks, front)
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(_notes(result)))


def _table_row(table: StudyTable, design: int | None) -> int | None:
    """The table's row of a design index, if it was evaluated."""
    if design is None:
        return None
    row = int(np.searchsorted(table.index, design))
    return row if row < table.index.size and int(table.index[row]) == design else None


def _paper_points(
    spec: StudySpec, table: StudyTable, marks: list[PaperMark]
) -> list[dict[str, Any]]:
    """The paper's designs in the study, with the study's own design there if any."""
    points = []
    for mark in marks:
        row = _table_row(table, mark.row)
        points.append({
            "label": mark.label,
            "parameters": dict(zip(spec.designs.names, mark.parameters, strict=True)),
            "design": None if row is None else entry(spec, table, row),
        })  # fmt: skip
    return points


def _markers(table: StudyTable, marks: list[PaperMark], axes: list[int]) -> list[Marker]:
    """The paper's designs as figure markers: their values on ``axes``, and their
    objectives where the study evaluated them."""
    markers = []
    for mark in marks:
        row = _table_row(table, mark.row)
        values = None if row is None else tuple(table.objectives[row].tolist())
        markers.append(Marker(mark.label, tuple(mark.parameters[a] for a in axes), values))
    return markers


def _figures(
    spec: StudySpec,
    process: ProcessDefinition,
    table: StudyTable,
    marks: list[PaperMark],
    front: np.ndarray[Any, Any],
) -> tuple[Artifact, ...]:
    labels = []
    for name in spec.objectives:
        entry = objective_entry(process, name)
        unit = objective_unit(process, name, spec.fixed)
        labels.append(objective_label(name, entry.symbol if entry else "", unit))
    out: tuple[Artifact, ...] = ()
    space = spec.designs
    axes = [a for a in space.axes if a[3] > 1] if isinstance(space, GridSpace) else []
    values = np.where(table.feasible[:, None], table.objectives, np.nan)
    if isinstance(space, GridSpace) and 1 <= len(axes) <= 3 and table.index.size == space.count:
        positions = [space.names.index(a[0]) for a in axes]
        shape = tuple(a[3] for a in axes)
        maps = [values[:, k].reshape(shape) for k in range(values.shape[1])]
        axes_labels = [f"{code(a[0])} [{parameter_unit(process, a[0], spec.fixed)}]" for a in axes]
        values_of_axes = [space.values(position) for position in positions]
        markers = _markers(table, marks, positions)
        title = f"Design study of {spec.process}"
        draw = objective_slices_figure if len(axes) == 3 else objective_maps_figure
        fig = draw(values_of_axes, axes_labels, maps, labels, title, markers)
        out += figure_artifacts(fig, "objective_maps", "Each objective over the varied inputs")
    if len(spec.objectives) >= 2:
        markers = _markers(table, marks, list(range(len(space.names))))
        fig = pareto_figure(values, front, labels, list(spec.objectives.values()),
                            f"Design study of {spec.process}: objective space",
                            markers)  # fmt: skip
        out += figure_artifacts(fig, "pareto", "The objectives and the non-dominated designs")
    return out


def _notes(result: dict[str, Any]) -> list[str]:
    notes = [
        f"{result['feasible']:,} of {result['count']:,} designs are feasible; "
        f"{result['pareto_size']:,} {'is' if result['pareto_size'] == 1 else 'are'} "
        "non-dominated."
    ]
    if result["infeasible_reasons"]:
        top = result["infeasible_reasons"][0]
        counts = ", ".join(f"{n:,} {code}" for code, n in result["infeasible"].items() if n)
        notes.append(
            f"{result['evaluated'] - result['feasible']:,} designs are infeasible ({counts}); "
            f"the most frequent reason ({top['designs']:,}): {top['reason']}"
        )
    if result["engine"] == "per-design":
        notes.append(f"Evaluated per design: {result['engine_reason']}.")
    if result["missing"]:
        notes.append(
            f"{result['missing']:,} designs are missing: chunks "
            f"{', '.join(result['missing_chunks'])} failed (allow_partial)."
        )
    return notes
