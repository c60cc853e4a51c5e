"""Which engine evaluates a study's designs: the process's study kernel (``batched``) or
the whole process once per design (``per-design``, the reference).

A study is batched when the process has a kernel (:mod:`worker.study_kernels`), every
objective reads a result path the kernel covers, every varied input is one it can
vary, and the fixed inputs validate as the kernel's template; ``"engine":
"per-design"`` forces the reference path.  The choice follows from the study's inputs
alone, so the submission, the split and every chunk make the same one.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

from pydantic import ValidationError

from worker.errors import InvalidInputs
from worker.input_schema import schema_errors
from worker.input_validation import field_errors
from worker.processes import ProcessDefinition
from worker.result_paths import declared_steps
from worker.studies.files import objective_entry
from worker.studies.paths import InputPath, parse_input_path, with_input
from worker.studies.spec import StudySpec
from worker.study_kernels import STUDY_TEMPLATE, KernelPlan, KernelRequest, StudyKernel

__all__ = ["Engine", "EngineChoice", "choose_engine", "pattern_matches"]

log = logging.getLogger(__name__)

Engine = Literal["batched", "per-design"]


@dataclass(frozen=True)
class EngineChoice:
    """The engine, why a study is not batched (``""`` when it is), and for a batched
    study the kernel's plan and the process's cost of the template."""

    engine: Engine
    why: str = ""
    kernel: StudyKernel | None = None
    plan: KernelPlan | None = None
    template_cost: int = 0


def pattern_matches(pattern: str, path: InputPath) -> bool:
    """Whether a kernel's input pattern (``chains[].lengths[]``, ``links.*``) names the
    input ``path`` (``("chains", 3, "lengths", 2)``): ``[]`` any index, ``*`` any key."""
    steps = declared_steps(pattern)
    if len(steps) != len(path):
        return False
    for step, part in zip(steps, path, strict=True):
        if step is None:
            if not isinstance(part, int):
                return False
        elif step == "*":
            if not isinstance(part, str):
                return False
        elif step != part:
            return False
    return True


def _reference(kernel: StudyKernel, path: InputPath) -> float | None:
    for pattern, value in kernel.varies.items():
        if pattern_matches(pattern, path):
            return float(value)
    return None


def _template(process: ProcessDefinition, spec: StudySpec, references: Sequence[float]) -> Any:
    """The process's inputs validated from ``fixed`` with the reference values at the
    varied paths, in the template's context; InvalidInputs if it refuses them."""

    raw: dict[str, Any] = dict(spec.fixed)
    for name, value in zip(spec.designs.names, references, strict=True):
        raw = with_input(raw, parse_input_path(name), value)
    if "plots" in process.inputs_model.model_fields:
        raw["plots"] = False
    try:
        inputs = process.inputs_model.model_validate(raw, context={STUDY_TEMPLATE: True})
    except ValidationError as exc:
        raise InvalidInputs(field_errors(exc, ("inputs",))) from exc
    mismatches = schema_errors(process.inputs_schema, raw)
    if mismatches:
        raise InvalidInputs(mismatches)
    return inputs


def choose_engine(spec: StudySpec, process: ProcessDefinition) -> EngineChoice:
    """The engine of ``spec`` over ``process`` (see the module doc)."""

    if spec.engine == "per-design":
        return EngineChoice("per-design", "the study asks for the per-design engine")
    kernel = process.study_kernel
    if kernel is None:
        return EngineChoice("per-design", f"{process.id} has no study kernel")
    wanted: set[str] = set()
    for name in spec.objectives:
        entry = objective_entry(process, name)
        if entry is None or entry.path not in kernel.covers:
            return EngineChoice("per-design", f"its kernel does not cover the objective "
                                f"'{name}'")  # fmt: skip
        wanted.add(entry.path)
    paths = [parse_input_path(name) for name in spec.designs.names]
    references = [_reference(kernel, path) for path in paths]
    for name, reference in zip(spec.designs.names, references, strict=True):
        if reference is None:
            return EngineChoice("per-design", f"its kernel cannot vary '{name}'")
    try:
        template = _template(process, spec, [float(r) for r in references if r is not None])
    except (InvalidInputs, ValueError) as exc:
        return EngineChoice("per-design", f"the fixed inputs are refused: {exc}")
    try:
        plan = kernel.prepare(KernelRequest(template, tuple(paths), frozenset(wanted)))
    except Exception as exc:  # a kernel's bug: the reference path still answers
        log.exception("the study kernel of %s could not be prepared", process.id)
        return EngineChoice("per-design", f"its kernel could not be prepared: {exc}")
    return EngineChoice("batched", "", kernel, plan, int(process.cost(template)))
