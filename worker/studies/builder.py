"""What the study builder form offers, and the study its choices spell.

The ``design-study`` process page builds a study in four steps (the pages draw them,
:mod:`service.pages.builder_form`): the process, one of its worked examples, the
example's numeric inputs to vary, and objectives among the process's result paths.
This module reads all of that from a registry: :func:`studied_processes` lists the
processes a study can run, :func:`builder_options` one process's examples with their
numeric inputs (input paths such as ``links[0]``, with units) and its objectives (result
paths with their description, unit and symbol; a path through a list, ``[]``, needs a
reduction).  :func:`study_inputs` writes the chosen study as the inputs of
``design-study``; nothing is validated here: the inputs go through the same submission
as an API request, whose field errors name what is wrong.
"""

from __future__ import annotations

import copy
import re
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal

from worker.processes import ProcessDefinition, ProcessRegistry
from worker.result_paths import unit_text
from worker.studies.files import parameter_unit
from worker.studies.number_inputs import takes_number
from worker.studies.paths import REDUCTIONS, parse_input_path
from worker.studies.spec import MAX_OBJECTIVES, MAX_VARIED, NOT_STUDIED

__all__ = [
    "MAX_OFFERED_INPUTS",
    "BuilderExample",
    "BuilderObjective",
    "BuilderOptions",
    "NumericInput",
    "ObjectiveChoice",
    "VariedInput",
    "builder_options",
    "numeric_inputs",
    "studied_processes",
    "study_inputs",
]

#: Numeric inputs offered per example at most (a long list of task points stops there).
MAX_OFFERED_INPUTS = 60
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


@dataclass(frozen=True)
class NumericInput:
    """A number in an example's inputs: its input path (``links[0]``), value and unit
    (``deg``, the example's ``length_unit``, or ``-``); ``whole``: written as a whole
    number (an integer input, as like as not: a grid's points per axis)."""

    path: str
    value: float
    unit: str
    whole: bool = False


@dataclass(frozen=True)
class BuilderExample:
    """A worked example as a study's starting point: its inputs become ``fixed``."""

    title: str
    inputs: Mapping[str, Any]
    numeric: tuple[NumericInput, ...]


@dataclass(frozen=True)
class BuilderObjective:
    """A result path a study may optimise; ``listed``: it runs through a list (``[]``)
    and needs one of :data:`~worker.studies.paths.REDUCTIONS`."""

    path: str
    description: str
    unit: str
    symbol: str

    @property
    def listed(self) -> bool:
        return "[]" in self.path


@dataclass(frozen=True)
class BuilderOptions:
    """What the builder offers for one process: its examples, and for the chosen one
    its objectives (units in that example's ``length_unit``)."""

    process_id: str
    title: str
    examples: tuple[BuilderExample, ...]
    objectives: tuple[BuilderObjective, ...]
    max_varied: int = MAX_VARIED
    max_objectives: int = MAX_OBJECTIVES
    reductions: tuple[str, ...] = REDUCTIONS


@dataclass(frozen=True)
class VariedInput:
    """A chosen input: from ``low`` to ``high`` in ``count`` values (a grid's axis), or
    a sample's bounds.  Values are as the form gave them (a text that is no number is
    passed on, and the submission says so at its field)."""

    path: str
    low: Any
    high: Any
    count: Any


@dataclass(frozen=True)
class ObjectiveChoice:
    """A chosen objective: a result path, its reduction (``""``: none) and direction."""

    path: str
    reduction: str
    goal: Literal["max", "min"] | str

    @property
    def name(self) -> str:
        """The objective as a study names it: ``task_points[].d_z|min``."""
        return f"{self.path}|{self.reduction}" if self.reduction else self.path


def studied_processes(registry: ProcessRegistry) -> list[ProcessDefinition]:
    """Every process of ``registry`` a design study can run, in the registry's order."""
    return [d for d in registry if d.id not in NOT_STUDIED]


def _leaves(value: Any, path: str) -> Iterator[tuple[str, int | float]]:
    if isinstance(value, bool):
        return
    if isinstance(value, int | float):
        yield path, value
    elif isinstance(value, Mapping):
        for key, item in value.items():
            if isinstance(key, str) and _NAME.match(key):
                yield from _leaves(item, f"{path}.{key}" if path else key)
    elif isinstance(value, list | tuple) and path:
        for index, item in enumerate(value):
            yield from _leaves(item, f"{path}[{index}]")


def numeric_inputs(
    definition: ProcessDefinition, inputs: Mapping[str, Any]
) -> tuple[NumericInput, ...]:
    """The numbers of ``inputs`` a study of ``definition`` can vary, in document order
    (at most :data:`MAX_OFFERED_INPUTS`): each a place the input schema takes a number."""
    schema = definition.inputs_schema
    found: list[NumericInput] = []
    for path, value in _leaves(dict(inputs), ""):
        if not takes_number(schema, parse_input_path(path)):
            continue
        unit = parameter_unit(definition, path, inputs)
        found.append(NumericInput(path, float(value), unit, isinstance(value, int)))
        if len(found) == MAX_OFFERED_INPUTS:
            break
    return tuple(found)


def builder_options(
    registry: ProcessRegistry, process_id: str, example: int = 0
) -> BuilderOptions | None:
    """The builder's options for ``process_id`` (None if a study cannot run it), with
    the objectives' units in example ``example``'s ``length_unit``."""
    definition = registry.get(process_id)
    if definition is None or process_id in NOT_STUDIED:
        return None
    examples = tuple(
        BuilderExample(ex.title, ex.inputs, numeric_inputs(definition, ex.inputs))
        for ex in definition.examples
    )
    chosen = examples[example].inputs if 0 <= example < len(examples) else {}
    length_unit = str(chosen.get("length_unit", "units"))
    objectives = tuple(
        BuilderObjective(r.path, r.description, unit_text(r.unit, length_unit), r.symbol)
        for r in definition.result_paths
        if "*" not in r.path
    )
    return BuilderOptions(definition.id, definition.title, examples, objectives)


def _without(fixed: Mapping[str, Any], varied: Sequence[VariedInput]) -> dict[str, Any]:
    """A copy of ``fixed`` without the varied inputs a key names (a varied list element
    stays: the list's length is part of the inputs)."""
    kept: dict[str, Any] = copy.deepcopy(dict(fixed))
    for item in varied:
        *parents, last = parse_input_path(item.path)
        node: Any = kept
        for step in parents:  # the example holds the path: the builder offered it
            node = node[step]
        if isinstance(last, str) and isinstance(node, dict):
            node.pop(last, None)
    return kept


def study_inputs(
    process_id: str,
    fixed: Mapping[str, Any],
    varied: Sequence[VariedInput],
    objectives: Sequence[ObjectiveChoice],
    *,
    sample: Mapping[str, Any] | None = None,
) -> dict[str, Any]:
    """The inputs of ``design-study`` for these choices: a grid over ``varied`` (each
    ``[low, high, count]``), or, with ``sample`` (``method``, ``count``, ``seed``), a
    sample within their ``[low, high]``."""
    inputs: dict[str, Any] = {"process": process_id, "fixed": _without(fixed, varied)}
    if sample is None:
        inputs["vary"] = {v.path: [v.low, v.high, v.count] for v in varied} or None
    else:
        bounds = {v.path: [v.low, v.high] for v in varied}
        inputs["sample"] = {**sample, "bounds": bounds}
    inputs["objectives"] = {o.name: o.goal for o in objectives}
    return inputs
