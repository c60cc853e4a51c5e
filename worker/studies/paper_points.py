"""The paper's designs a study contains, to be marked on its plots and listed in its
result.

A process lists the designs its paper reports (:class:`worker.processes.PaperPoint`:
input paths and values, e.g. Table 1's ``alpha1_deg = 60, alpha2_deg = 90`` with
``beta_deg = 90``, ``gamma_deg = 0`` and Example I's workspace).  A study contains one
when each of its varied inputs is among the point's paths and within the study's
bounds, and every other path of the point has the point's value in the study's inputs
(as the process validates them, so a default counts).  Where the design is also one of
a grid's designs, its row is kept, so its objectives can be reported beside the label.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from pydantic import ValidationError

from worker.processes import PaperPoint, ProcessDefinition
from worker.studies.designs import GridSpace
from worker.studies.paths import parse_input_path, with_input
from worker.studies.spec import StudySpec

__all__ = ["PaperMark", "paper_marks"]

#: Relative and absolute tolerance of "the same value" (a printed 54.9 is 54.9).
_TOLERANCE = 1e-9


@dataclass(frozen=True)
class PaperMark:
    """A paper's design inside a study: its label, its varied inputs' values (in the
    study's column order), and its row when a grid design is that design."""

    label: str
    parameters: tuple[float, ...]
    row: int | None


def paper_marks(spec: StudySpec, process: ProcessDefinition) -> list[PaperMark]:
    """The process's paper points this study contains, in the process's order."""
    marks = []
    for point in process.paper_points:
        parameters = _inside(spec, point)
        if parameters is not None and _agrees(spec, process, point, parameters):
            marks.append(PaperMark(point.label, parameters, _grid_row(spec, parameters)))
    return marks


def _inside(spec: StudySpec, point: PaperPoint) -> tuple[float, ...] | None:
    """The point's values of the varied inputs if all are given and within bounds."""
    space = spec.designs
    bounds = (
        [(name, lo, hi) for name, lo, hi, _ in space.axes]
        if isinstance(space, GridSpace)
        else list(space.bounds)
    )
    values = []
    for name, lo, hi in bounds:
        value = point.inputs.get(name)
        if not isinstance(value, int | float):
            return None
        low, high = min(lo, hi), max(lo, hi)
        if not low - _slack(low) <= value <= high + _slack(high):
            return None
        values.append(float(value))
    return tuple(values)


def _agrees(
    spec: StudySpec, process: ProcessDefinition, point: PaperPoint, parameters: tuple[float, ...]
) -> bool:
    """Whether the study's inputs at the point have the point's other values."""
    inputs: dict[str, Any] = dict(spec.fixed)
    try:
        for name, value in zip(spec.designs.names, parameters, strict=True):
            inputs = with_input(inputs, parse_input_path(name), value)
        validated = process.inputs_model.model_validate(inputs).model_dump(mode="json")
    except (ValueError, ValidationError):
        return False
    others = {k: v for k, v in point.inputs.items() if k not in spec.designs.names}
    return all(_same(_read(validated, parse_input_path(k)), v) for k, v in others.items())


def _read(document: Mapping[str, Any], path: tuple[str | int, ...]) -> Any:
    node: Any = document
    for step in path:
        if isinstance(step, int):
            if not isinstance(node, list) or step >= len(node):
                return None
        elif not isinstance(node, Mapping) or step not in node:
            return None
        node = node[step]
    return node


def _same(found: Any, wanted: Any) -> bool:
    if isinstance(wanted, list | tuple):
        return (
            isinstance(found, list | tuple)
            and len(found) == len(wanted)
            and all(_same(f, w) for f, w in zip(found, wanted, strict=True))
        )
    if isinstance(wanted, bool) or not isinstance(wanted, int | float):
        return bool(found == wanted)
    return (
        isinstance(found, int | float)
        and not isinstance(found, bool)
        and math.isclose(found, wanted, rel_tol=_TOLERANCE, abs_tol=_TOLERANCE)
    )


def _slack(value: float) -> float:
    return _TOLERANCE * max(1.0, abs(value))


def _grid_row(spec: StudySpec, parameters: tuple[float, ...]) -> int | None:
    """The row of the grid design at ``parameters``, if there is one."""
    space = spec.designs
    if not isinstance(space, GridSpace):
        return None
    index = []
    for axis, value in enumerate(parameters):
        values = space.values(axis)
        nearest = int(abs(values - value).argmin())
        if abs(values[nearest] - value) > _slack(value):
            return None
        index.append(nearest)
    row = 0
    for position, n in zip(index, space.shape, strict=True):
        row = row * n + position
    return row
