"""The study builder on the ``design-study`` process page (no JavaScript needed).

Four steps, each a GET form that draws the page again with the choices so far as query
parameters (``/v1/processes/design-study?process=...&example=0#builder``): the process,
one of its worked examples, the example's numbers to vary (``vary.<path>=on`` with
``from.<path>``, ``to.<path>``, ``count.<path>``; ``design=sample`` with
``sample_count``, ``sample_method``, ``seed`` for a sample), then the objectives
(``objective.<path>=on`` with ``reduce.<path>`` for a path through a list and
``goal.<path>``), whose form posts everything to ``POST
/pages/processes/design-study/build`` (:mod:`service.pages.actions`).  The action
builds the study's inputs (:func:`worker.studies.builder.study_inputs`) and submits
them as an API request would be; a refusal comes back on this form with its fields.
What the form offers comes from the registry (:mod:`worker.studies.builder`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from fastapi import Request
from fastapi.responses import HTMLResponse

from service.pages.renderer import Pages
from service.pages.views import ExampleForm, process_page
from worker.processes import ProcessDefinition, ProcessRegistry
from worker.result_paths import plain_symbol
from worker.studies.builder import (
    BuilderOptions,
    NumericInput,
    ObjectiveChoice,
    VariedInput,
    builder_options,
    studied_processes,
    study_inputs,
)

__all__ = [
    "BUILD_ACTION",
    "MAX_BUILDER_FIELDS",
    "STUDY_PROCESS",
    "builder_state",
    "chosen_study",
    "study_builder_page",
]

STUDY_PROCESS = "design-study"
BUILD_ACTION = f"/pages/processes/{STUDY_PROCESS}/build"
#: Fields the builder's form may post at most (four per number, three per objective).
MAX_BUILDER_FIELDS = 600
_METHODS = ("sobol", "latin_hypercube")
_STEP_FIELDS = ("from.", "to.", "count.", "vary.")
_GOAL_FIELDS = ("objective.", "reduce.", "goal.")


def _example_index(value: str | None, count: int) -> int | None:
    try:
        index = int(value or "")
    except ValueError:
        return None
    return index if 0 <= index < count else None


def _shown(value: float) -> str:
    return f"{value:.6g}"


def _default_range(number: NumericInput) -> tuple[str, str]:
    """From 20 % below to 20 % above the example's value (-1 to 1 around zero), whole
    numbers for a whole number."""
    value = number.value
    if value == 0:
        return "-1", "1"
    low, high = sorted((value * 0.8, value * 1.2))
    if number.whole:
        return str(round(low)), str(round(high))
    return _shown(low), _shown(high)


def _input_row(number: NumericInput, params: Mapping[str, str]) -> dict[str, Any]:
    low, high = _default_range(number)
    path = number.path
    return {
        "path": path,
        "unit": number.unit,
        "value": _shown(number.value),
        "checked": params.get(f"vary.{path}") == "on",
        "low": params.get(f"from.{path}", low),
        "high": params.get(f"to.{path}", high),
        "count": params.get(f"count.{path}", "3"),
    }


def _objective_rows(options: BuilderOptions, params: Mapping[str, str]) -> list[dict[str, Any]]:
    return [
        {
            "path": o.path,
            "description": o.description,
            "unit": o.unit,
            "symbol": plain_symbol(o.symbol) if o.symbol else "",
            "listed": o.listed,
            "checked": params.get(f"objective.{o.path}") == "on",
            "reduction": params.get(f"reduce.{o.path}", "min"),
            "goal": params.get(f"goal.{o.path}", "max"),
        }
        for o in options.objectives
    ]


def _carried(params: Mapping[str, str], prefixes: tuple[str, ...]) -> list[tuple[str, str]]:
    """The fields of other steps a step's form carries on: those of a chosen input or
    objective (``vary.<path>`` / ``objective.<path>`` is on)."""
    chosen = {
        name.partition(".")[2]
        for name, value in params.items()
        if name.startswith(("vary.", "objective.")) and value == "on"
    }
    return [
        (name, value)
        for name, value in params.items()
        if name.startswith(prefixes) and name.partition(".")[2] in chosen
    ]


def builder_state(registry: ProcessRegistry, params: Mapping[str, str]) -> dict[str, Any]:
    """The builder's context from the choices so far (query parameters or the posted
    form): the step reached, what each step offers and what was chosen."""
    processes = [{"id": d.id, "title": d.title} for d in studied_processes(registry)]
    process_id = params.get("process", "")
    state: dict[str, Any] = {
        "action": BUILD_ACTION,
        "processes": processes,
        "process": "",
        "examples": [],
        "example": None,
        "inputs": [],
        "objectives": [],
        "step": 1,
    }
    options = builder_options(registry, process_id) if process_id else None
    if options is None:
        return state
    examples = [{"index": i, "title": e.title} for i, e in enumerate(options.examples)]
    state.update(process=process_id, step=2, examples=examples)
    example = _example_index(params.get("example"), len(options.examples))
    if example is None:
        return state
    options = builder_options(registry, process_id, example)
    assert options is not None
    design = "sample" if params.get("design") == "sample" else "grid"
    inputs = [_input_row(n, params) for n in options.examples[example].numeric]
    state.update(
        example=example,
        step=4 if params.get("step") == "objectives" else 3,
        inputs=inputs,
        chosen_inputs=[row for row in inputs if row["checked"]],
        objectives=_objective_rows(options, params),
        design=design,
        sample_count=params.get("sample_count", "12"),
        sample_method=params.get("sample_method", "sobol"),
        sample_methods=_METHODS,
        seed=params.get("seed", "0"),
        reductions=options.reductions,
        max_varied=options.max_varied,
        max_objectives=options.max_objectives,
        carried_objectives=_carried(params, _GOAL_FIELDS),
        carried_inputs=_carried(params, _STEP_FIELDS),
    )
    return state


def _number(text: str | None) -> Any:
    """A form's number as JSON takes it; a text that is none is passed on as it is, for
    the submission to refuse at its field."""
    text = (text or "").strip()
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            continue
    return text


def chosen_study(registry: ProcessRegistry, params: Mapping[str, str]) -> dict[str, Any] | None:
    """The inputs of ``design-study`` the posted choices spell; None if the process or
    the example is not one the builder offers."""
    options = builder_options(registry, params.get("process", ""))
    if options is None:
        return None
    example = _example_index(params.get("example"), len(options.examples))
    if example is None:
        return None
    chosen = options.examples[example]
    varied = [
        VariedInput(n.path, _number(params.get(f"from.{n.path}")),
                    _number(params.get(f"to.{n.path}")), _number(params.get(f"count.{n.path}")))
        for n in chosen.numeric
        if params.get(f"vary.{n.path}") == "on"
    ]  # fmt: skip
    objectives = [
        ObjectiveChoice(o.path, params.get(f"reduce.{o.path}", "min") if o.listed else "",
                        params.get(f"goal.{o.path}", "max"))
        for o in options.objectives
        if params.get(f"objective.{o.path}") == "on"
    ]  # fmt: skip
    sample = None
    if params.get("design") == "sample":
        sample = {"method": params.get("sample_method", "sobol"),
                  "count": _number(params.get("sample_count")),
                  "seed": _number(params.get("seed", "0"))}  # fmt: skip
    return study_inputs(options.process_id, chosen.inputs, varied, objectives, sample=sample)


def _invalid_paths(problem: Mapping[str, Any] | None) -> set[str]:
    """The input and objective paths the problem's field errors name."""
    fields = [str(e.get("field", "")) for e in (problem or {}).get("errors", [])]
    names: set[str] = set()
    for field in fields:
        for marker in (".vary.", ".bounds.", ".objectives."):
            if marker in field:
                names.add(field.split(marker, 1)[1])
    return names


def study_builder_page(
    request: Request,
    pages: Pages,
    registry: ProcessRegistry,
    definition: ProcessDefinition,
    params: Mapping[str, str],
    *,
    problem: dict[str, Any] | None = None,
    examples: Sequence[ExampleForm] | None = None,
    status_code: int | None = None,
) -> HTMLResponse:
    """The ``design-study`` page with the builder at the choices ``params``; a refused
    study's ``problem`` shown on it (its status the page's).  ``examples`` and
    ``status_code``: a refused JSON form's, drawn below the builder."""
    state = builder_state(registry, params)
    invalid = _invalid_paths(problem)
    for row in state["inputs"]:
        row["invalid"] = row["path"] in invalid
    for row in state["objectives"]:
        row["invalid"] = any(name.split("|")[0] == row["path"] for name in invalid)
    state["problem"] = problem
    if status_code is None:
        status_code = int(problem.get("status", 422)) if problem else 200
    return process_page(request, pages, registry, definition, examples=examples,
                        status_code=status_code, template="study_process.html",
                        extra={"builder": state})  # fmt: skip
