"""Evaluating a block of a study's designs with the single-design process (the
per-design engine, the reference the batched one is checked against).

Each design is the fixed inputs with the varied values set at their paths, validated as
the service validates a request of that process (its model, its published schema, its
cost limit), run as a job of that process would run
(plots off when the process has the switch) and read at the objective paths.  A design
is infeasible exactly when the process refuses it (``refused``, with the first field
the refusal names) or reports no value for an objective (``no-value``); a design whose
run raises is kept too (``failed``), with the error.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from worker.errors import InvalidInputs
from worker.input_validation import validate_inputs
from worker.processes import ProcessDefinition
from worker.studies.paths import parse_input_path, parse_result_path, read_result, with_input
from worker.studies.rows import FAILED, FEASIBLE, NO_VALUE, REFUSED, ChunkRows, ReasonTally
from worker.studies.spec import StudySpec

__all__ = [
    "DesignRow",
    "SilentContext",
    "chunk_rows",
    "design_inputs",
    "evaluate_block",
    "one_design_inputs",
]


@dataclass(frozen=True)
class DesignRow:
    """One evaluated design: its index, varied values, objective values (None where
    the process reported none) and, when infeasible, why: a reason code
    (:mod:`.rows`), the field a refusal names and the message."""

    index: int
    parameters: tuple[float, ...]
    objectives: tuple[float | None, ...]
    reason: str | None
    code: int = FEASIBLE
    field: str = ""

    @property
    def feasible(self) -> bool:
        return self.reason is None

    def as_json(self) -> dict[str, Any]:
        return {"index": self.index, "parameters": list(self.parameters),
                "objectives": list(self.objectives), "reason": self.reason}  # fmt: skip


def chunk_rows(rows: list[DesignRow], start: int, stop: int, k: int) -> ChunkRows:
    """Designs ``start`` to ``stop`` as the arrays a chunk stores."""
    objectives = np.array(
        [[np.nan if v is None else v for v in row.objectives] for row in rows], dtype=np.float64
    ).reshape(len(rows), k)
    names: list[str] = [""]
    fields = np.zeros(len(rows), dtype=np.int16)
    tally = ReasonTally()
    for n, row in enumerate(rows):
        if row.reason is None:
            continue
        if row.field not in names:
            names.append(row.field)
        fields[n] = names.index(row.field)
        tally.add(row.code, row.field, row.reason)
    codes = np.array([row.code for row in rows], dtype=np.int8)
    return ChunkRows(start, stop, objectives, codes, fields, tuple(names), tally, "per-design")


class SilentContext:
    """A context that drops progress: a design's own progress is not the study's."""

    def report_progress(self, percent: float, message: str = "") -> None:
        pass


def design_inputs(spec: StudySpec, values: tuple[float, ...]) -> dict[str, Any]:
    """The process's raw inputs for one design: ``fixed`` with the varied values set."""
    inputs: dict[str, Any] = dict(spec.fixed)
    for name, value in zip(spec.designs.names, values, strict=True):
        inputs = with_input(inputs, parse_input_path(name), value)
    return inputs


def one_design_inputs(spec: StudySpec, process: ProcessDefinition, index: int) -> dict[str, Any]:
    """The inputs of design ``index`` run alone as a job of ``process``: ``fixed`` with
    its varied values, plots on where the process draws any (``IndexError`` past the
    last design)."""
    if not 0 <= index < spec.designs.count:
        raise IndexError(f"the study has {spec.designs.count:,} designs (0 to "
                         f"{spec.designs.count - 1:,})")  # fmt: skip
    values = tuple(float(v) for v in spec.designs.block(index, index + 1)[0])
    inputs = design_inputs(spec, values)
    if "plots" in process.inputs_model.model_fields:
        inputs["plots"] = True
    return inputs


def evaluate_block(
    spec: StudySpec,
    process: ProcessDefinition,
    start: int,
    stop: int,
    on_design: Callable[[int, int], None] | None = None,
) -> list[DesignRow]:
    """Rows of the designs ``start`` to ``stop`` (exclusive) of the study."""
    paths = [parse_result_path(name) for name in spec.objectives]
    has_plots = "plots" in process.inputs_model.model_fields
    rows: list[DesignRow] = []
    block = spec.designs.block(start, stop)
    for offset, values in enumerate(block.tolist()):
        parameters = tuple(float(v) for v in values)
        rows.append(_evaluate(spec, process, start + offset, parameters, paths, has_plots))
        if on_design is not None:
            on_design(offset + 1, stop - start)
    return rows


def _evaluate(
    spec: StudySpec,
    process: ProcessDefinition,
    index: int,
    parameters: tuple[float, ...],
    paths: list[Any],
    has_plots: bool,
) -> DesignRow:
    missing = (None,) * len(paths)
    try:
        raw = design_inputs(spec, parameters)
        if has_plots:
            raw["plots"] = False
        inputs = validate_inputs(process, raw)
    except InvalidInputs as exc:  # what the service would answer with a 422
        field = str(exc.errors[0]["field"]) if exc.errors else "inputs"
        return DesignRow(index, parameters, missing, f"refused: {exc}", REFUSED, field)
    except ValueError as exc:  # a path the fixed inputs do not hold
        return DesignRow(index, parameters, missing, f"refused: {exc}", REFUSED, "inputs")
    cost = process.cost(inputs)
    if cost > process.cost_limit:
        reason = f"refused: costs {cost:,} {process.cost_unit}, above {process.cost_limit:,}"
        return DesignRow(index, parameters, missing, reason, REFUSED, "inputs")
    try:
        outcome = process.run(inputs, SilentContext())
    except Exception as exc:  # kept with its reason, never dropped silently
        reason = f"failed: {type(exc).__name__}: {exc}"
        return DesignRow(index, parameters, missing, reason, FAILED)
    values = tuple(read_result(outcome.result, path) for path in paths)
    absent = [name for name, v in zip(spec.objectives, values, strict=True) if v is None]
    if absent:
        return DesignRow(index, parameters, values, f"no value for {', '.join(absent)}", NO_VALUE)
    return DesignRow(index, parameters, values, None)
