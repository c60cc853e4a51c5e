"""``design-study``: a single-design process evaluated over many designs, fanned out over
every worker, with the non-dominated set of its objectives.

The designs are evaluated by the process's study kernel when it covers the study
(``batched``, :mod:`.engine`, :mod:`.batched`) and by the whole process once per design
otherwise (``per-design``, :mod:`.evaluation`).  Its first attempt splits the designs
into chunks of about a second of work (:mod:`.chunking`) and queues them as
``design-study-chunk`` jobs (:mod:`worker.store.fan_out`); the parent holds no worker
while they run, and the chunk that ends last queues the assembly (:mod:`.assembly`,
:mod:`.files`, :mod:`.figures`), which reads the chunks' rows one chunk at a time.
``run`` does the same in one process (tests, small studies).

A study runs the processes of the registry it is built with (:func:`design_study`): it
never builds one.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from functools import partial
from typing import Any, TypeVar

import numpy as np

from worker.contract import ChildEnd, JobContext, JobOutcome, JobStatus
from worker.errors import InvalidInputs
from worker.input_validation import validate_inputs
from worker.processes import (
    ChildFiles,
    ChildResults,
    FanOutSteps,
    ProcessDefinition,
    ProcessFile,
    ProcessRegistry,
    figure_files,
)
from worker.result_paths import declared_steps
from worker.studies.chunk import ChunkSpec, run_chunk, target_of
from worker.studies.chunking import chunk_inputs, probe_costs, probe_indices
from worker.studies.engine import EngineChoice, choose_engine
from worker.studies.evaluation import SilentContext, design_inputs
from worker.studies.examples import STUDY_EXAMPLES
from worker.studies.files import objective_entry
from worker.studies.number_inputs import unvariable_paths
from worker.studies.paths import (
    nearest_place,
    parse_input_path,
    parse_result_path,
    reported,
    show_input_path,
)
from worker.studies.result_paths import STUDY_RESULT_PATHS
from worker.studies.spec import StudySpec, study_spec_for

__all__ = ["design_study", "dry_check", "study_cost"]

#: A study may cost as much as this many jobs of its process at their cost limit.
STUDY_JOBS_LIMIT = 1000
_MILLIONTHS = 1_000_000
Answer = TypeVar("Answer")


def study_cost(spec: StudySpec, process: ProcessDefinition) -> int:
    """Designs x a design's cost, in millionths of the cost limit of ``process`` (the
    process studied): the kernel's cost of a design when the study is batched, else the
    dearest of the designs spread over the space that the process accepts
    (:func:`~.chunking.probe_costs`; a design's cost may grow with its varied values),
    as a job of the process; 1 unit when it refuses every one tried (refused designs
    cost next to nothing)."""
    choice = choose_engine(spec, process)
    if choice.plan is not None:
        share = min(1.0, choice.plan.cost / process.cost_limit)
        return math.ceil(spec.designs.count * share * _MILLIONTHS)
    design_cost = max(probe_costs(spec, process), default=1.0)
    share = min(1.0, design_cost / process.cost_limit)
    return math.ceil(spec.designs.count * share * _MILLIONTHS)


def dry_check(spec: StudySpec, process: ProcessDefinition) -> list[dict[str, Any]]:
    """At submission, for the study of ``process``: varied paths the process takes no
    number at and objectives that are no number it declares
    (:attr:`ProcessDefinition.result_paths`), then a design run once, so that fixed
    inputs the process refuses whatever the varied values, and objective paths it does
    not report, are a 422 before anything is queued. The varied paths are checked
    against the process's published input schema; then the first design is tried, and
    others spread over the space until one validates: a design refused for its varied
    values is no error (other designs may be fine), but fixed inputs every tried design
    is refused for are, each at its place in ``fixed``. A refusal is for a varied value
    when it is at the varied place, inside it or at a place holding it. A design too
    costly to run during a request (above the process's sync limit and a thousandth of
    its cost limit) is not run. A batched study asks its kernel instead of running the
    process, and a study asking for ``"engine": "batched"`` that cannot be is refused at
    ``inputs.engine``."""
    undeclared = [
        *unvariable_paths(spec, process.inputs_schema),
        *_undeclared_objectives(spec, process),
    ]
    if undeclared:
        return undeclared
    choice = choose_engine(spec, process)
    if spec.engine == "batched" and choice.engine != "batched":
        return [{"field": "inputs.engine", "type": "value_error",
                 "message": f"this study cannot be batched: {choice.why}"}]  # fmt: skip
    unreported = _unreported_by_kernel(spec, process, choice) if choice.plan else []
    if unreported:
        return unreported
    varied = {_field_of(name) for name in spec.designs.names}
    inputs = None
    refusals: list[InvalidInputs] = []
    for index in probe_indices(spec.designs.count):
        design = tuple(float(v) for v in spec.designs.block(index, index + 1)[0])
        raw = design_inputs(spec, design)
        if "plots" in process.inputs_model.model_fields:
            raw["plots"] = False
        try:
            inputs = validate_inputs(process, raw)
            break
        except InvalidInputs as exc:
            if any(_related(e["field"], v) for e in exc.errors for v in varied):
                return []  # refused for a varied value: the designs will say which
            refusals.append(exc)
    if inputs is None:
        tried = (
            f"{spec.process} refuses every design tried ({len(refusals)}, spread over the space)"
        )
        return [_in_fixed(spec.fixed, error, tried) for error in refusals[0].errors]
    if choice.plan is not None:  # the kernel's answer said what the process reports
        return []
    if process.cost(inputs) > max(process.sync_cost_limit, process.cost_limit // 1000):
        return []
    try:
        result = process.run(inputs, SilentContext()).result
    except Exception:  # the study records it design by design
        return []
    return [
        {"field": f"inputs.objectives.{name}", "type": "value_error",
         "message": f"{spec.process} reports nothing at this path (checked on a design)"}
        for name in spec.objectives
        if not reported(result, parse_result_path(name))
    ]  # fmt: skip


def _unreported_by_kernel(
    spec: StudySpec, process: ProcessDefinition, choice: EngineChoice
) -> list[dict[str, Any]]:
    """A batched study's objectives checked on its kernel's answer for the first design:
    an index past the end of a list the kernel reports (``chains[7].P`` of five chains)
    is a path the process does not report."""
    assert choice.plan is not None
    with np.errstate(all="ignore"):  # a design out of range is the kernel's to refuse
        block = choice.plan.evaluate(spec.designs.block(0, 1))
    problems = []
    for name in spec.objectives:
        entry = objective_entry(process, name)
        assert entry is not None  # the engine's choice checked it
        shape = block.values[entry.path].shape[1:]
        steps = declared_steps(entry.path)
        lists = [part for step, part in zip(steps, parse_result_path(name).steps, strict=False)
                 if step is None]  # fmt: skip
        if any(isinstance(i, int) and i >= n for i, n in zip(lists, shape, strict=False)):
            problems.append({"field": f"inputs.objectives.{name}", "type": "value_error",
                             "message": f"{spec.process} reports nothing at this path "
                             "(checked on a design)"})  # fmt: skip
    return problems


def _undeclared_objectives(spec: StudySpec, process: ProcessDefinition) -> list[dict[str, Any]]:
    """An objective must read numbers the process declares (so that every study knows
    their unit): one field error per objective that does not."""
    return [
        {"field": f"inputs.objectives.{name}", "type": "value_error",
         "message": f"{spec.process} reports no number at this path (its result_paths, in "
         f"GET /v1/processes/{spec.process}, list every number it reports)"}
        for name in spec.objectives
        if objective_entry(process, name) is None
    ]  # fmt: skip


def _in_fixed(fixed: Mapping[str, Any], error: Mapping[str, Any], tried: str) -> dict[str, Any]:
    """A process's refusal of the fixed inputs as the study's field error: at the place
    in ``fixed`` nearest to what the process names (``inputs.grid.points`` ->
    ``inputs.fixed.grid.points``), the process's own field in the message if it differs."""
    named = error["field"].removeprefix("inputs").removeprefix(".")
    try:
        path = parse_input_path(named)
        place = show_input_path(nearest_place(fixed, path, missing=error["type"] == "missing"))
    except ValueError:  # "inputs" itself, or a field that is no input path
        place = ""
    at = f" (at '{named}')" if named and named != place else ""
    return {**error, "field": f"inputs.fixed.{place}" if place else "inputs.fixed",
            "message": f"{tried}{at}: {error['message']}"}  # fmt: skip


def _field_of(name: str) -> str:
    """An input path as the field errors spell it: ``links[0]`` -> ``inputs.links[0]``."""
    return f"inputs.{name}"


def _related(field: str, varied: str) -> bool:
    """Whether a refusal at ``field`` may be for the value at ``varied`` (both spelt
    ``inputs.links[0]``): the same place, a place inside it, or one holding it (a
    list's or a mapping's own check), but not the whole inputs."""

    def within(inner: str, outer: str) -> bool:
        return inner == outer or inner.startswith((f"{outer}.", f"{outer}["))

    return within(field, varied) or (field != "inputs" and within(varied, field))


def assemble(
    studied: ProcessRegistry,
    spec: StudySpec,
    children: ChildResults,
    files: ChildFiles,
    ctx: JobContext,
) -> JobOutcome:
    """The study's outcome from its chunks (the figures need matplotlib)."""
    # lazy: keeps the registry free of matplotlib (the study's figures)
    from worker.studies.outcome import study_outcome

    return study_outcome(spec, target_of(studied, spec), children, files, ctx)


def run_in_process(studied: ProcessRegistry, spec: StudySpec, ctx: JobContext) -> JobOutcome:
    """The whole study in this process: each chunk run here, then assembled."""
    chunks = chunk_inputs(spec, target_of(studied, spec))
    stored: dict[tuple[str, str], bytes] = {}

    def children() -> ChildResults:
        for n, inputs in enumerate(chunks):
            outcome = run_chunk(studied, ChunkSpec.model_validate(inputs), SilentContext())
            ctx.report_progress(90.0 * (n + 1) / len(chunks), f"chunk {n + 1} of {len(chunks)}")
            stored.clear()  # one chunk's files at a time, as the store streams them
            for artifact in outcome.artifacts:
                stored[(f"chunk-{n}", artifact.name)] = artifact.data
            yield ChildEnd(f"chunk-{n}", JobStatus.SUCCESSFUL, None), outcome.result

    def files(job_id: str, name: str) -> bytes | None:
        return stored.get((job_id, name))

    return assemble(studied, spec, children(), files, ctx)


def _on_target(
    check: Callable[[StudySpec, ProcessDefinition], Answer], studied: ProcessRegistry
) -> Callable[[StudySpec], Answer]:
    """``check(spec, process)`` as a function of the study's inputs alone."""
    return lambda spec: check(spec, target_of(studied, spec))


def design_study(studied: ProcessRegistry) -> ProcessDefinition:
    """``design-study`` over the single-design processes of ``studied``."""
    return ProcessDefinition(
        id="design-study",
        # 1.1.0: objectives' units in designs.csv and designs.npz (objective_units,
        # objective_symbols) and on the plots; the first varied input on x.
        # 2.0.0: the batched engine ('engine', 'engine_reason'); reason codes per design
        # (designs.npz reason_code/reason_field instead of a reason string per design, a
        # reason_code column in designs.csv), infeasible_reasons by code, field and message.
        version="2.0.0",
        unkeyed_inputs=("chunk_size",),
        result_paths=STUDY_RESULT_PATHS,
        title="Design study: one process over many designs, with the Pareto front",
        description=(
            "Evaluates any single-design process ('process', its other inputs in 'fixed') over "
            "a grid ('vary': input path -> [lo, hi, n]) or a Sobol / Latin-hypercube sample "
            "('sample') of designs, and reports every design's objectives (result paths -> "
            "'max' or 'min', a list reduced with |min, |max, |mean or |sum), the non-dominated "
            "designs and the best per objective. The designs are split into chunk jobs of about "
            "a second each that run on every worker at once; a design the process refuses, or "
            "that has no value for an objective, is kept as infeasible with its reason code. "
            "Where the process has a study kernel covering every objective and varied input "
            '(its result_paths say "kernel": true), the designs are evaluated many at once '
            "(engine 'batched', the same numbers); else by running the process per design. "
            "Cost: designs x a design's cost (the kernel's, or the first design's as a job), in "
            f"millionths of the process's cost limit; at most {STUDY_JOBS_LIMIT} jobs' worth."
        ),
        inputs_model=study_spec_for(studied.ids()),
        files=(
            ProcessFile("designs.csv", "Every design: parameters and objectives (CSV)"),
            ProcessFile("designs.npz", "Every design (NumPy arrays)"),
            *figure_files("objective_maps", "Each objective over the varied inputs"),
            *figure_files("pareto", "The objectives and the non-dominated designs"),
        ),
        method_doc="design-studies",
        run=partial(run_in_process, studied),
        examples=STUDY_EXAMPLES,
        outputs={
            "process": "The process evaluated.",
            "engine": "'batched' (the process's study kernel) or 'per-design' (the whole process "
            "once per design).",
            "engine_reason": "Why the study ran per design ('' when batched).",
            "count": "Designs in the study.",
            "evaluated": "Designs evaluated (count minus those of missing chunks).",
            "feasible": "Designs with a value for every objective.",
            "missing": "Designs of chunks that failed (allow_partial).",
            "missing_chunks": "The chunk jobs that failed.",
            "infeasible": "Infeasible designs per reason code: refused, no-value, failed.",
            "infeasible_reasons": "Why designs are infeasible, most frequent first: reason_code, "
            "reason_field (the field a refusal names), reason (each distinct message once) and "
            "designs.",
            "parameters": "The varied input paths, in column order.",
            "objectives": "The objectives (result path -> 'max' or 'min').",
            "pareto_size": "How many designs are non-dominated.",
            "pareto": "The non-dominated designs (at most 1000 listed): index, parameters, "
            "objectives.",
            "best": "Per objective, the best designs (best_count).",
            "paper_points": "The designs the process's paper reports that the study contains "
            "(marked on the plots), each with the study's design there if it evaluated it.",
            "chunks": "How many chunks ran.",
        },
        cost=_on_target(study_cost, studied),
        precheck=_on_target(dry_check, studied),
        cost_limit=STUDY_JOBS_LIMIT * _MILLIONTHS,
        cost_unit="designs x their cost in millionths of the process's cost limit",
        time_limit_s=1800.0,
        fan_out=FanOutSteps(
            child_process="design-study-chunk",
            split=_on_target(chunk_inputs, studied),
            assemble=partial(assemble, studied),
            allow_partial=lambda spec: bool(spec.allow_partial),
        ),
    )
