"""Nothing a study accepts dies in the worker: for random accepted studies, the stored
inputs validate again as the worker reads them, the split into chunks succeeds and each
chunk validates as a job of its own, and designs evaluate to rows (an infeasible
design is a row with its reason, never an exception)."""

from __future__ import annotations

import json
import math
from typing import Any

from hypothesis import event, example, given

from tests.unit.worker.studies.registry import STUDY, dry_check
from tests.unit.worker.studies.study_requests import (
    property_settings,
    sound_study_bodies,
    study_bodies,
)
from worker.errors import InvalidInputs
from worker.registry import default_registry
from worker.studies.chunk import ChunkSpec
from worker.studies.evaluation import evaluate_block
from worker.studies.spec import StudySpec
from worker.submission import validate_inputs

#: Refusal reasons a design may carry: the process refused it, its cost is above the
#: process's limit, or it reports no value for an objective.  ``failed:`` (the process
#: raised on inputs it had validated) is no reason a sound process gives.
REASONS = ("refused: ", "no value for ")


def accepted(inputs: dict[str, Any]) -> StudySpec | None:
    """The study as the service would accept it (model, schema, cost, dry check), or None."""
    try:
        spec = validate_inputs(STUDY, inputs)
    except InvalidInputs:
        return None
    assert isinstance(spec, StudySpec)
    if STUDY.cost(spec) > STUDY.cost_limit or dry_check(spec):
        return None
    return spec


def check_in_the_worker(spec: StudySpec) -> None:
    stored = json.loads(json.dumps(spec.model_dump(mode="json")))
    again = STUDY.inputs_model.model_validate(stored)  # what the worker validates
    assert again == spec
    assert STUDY.fan_out is not None
    chunks = STUDY.fan_out.split(again)
    count = again.designs.count
    assert [c["start"] for c in chunks] == [0, *(c["stop"] for c in chunks[:-1])]
    assert chunks[-1]["stop"] == count
    for chunk in chunks:
        ChunkSpec.model_validate(json.loads(json.dumps(chunk)))  # each chunk job's inputs
    process = default_registry().get(again.process)
    assert process is not None
    for index in sorted({0, count // 2, count - 1}):
        (row,) = evaluate_block(again, process, index, index + 1)
        assert row.index == index and len(row.objectives) == len(again.objectives)
        assert all(math.isfinite(p) for p in row.parameters)
        if row.feasible:
            assert all(v is not None and math.isfinite(v) for v in row.objectives)
        else:
            assert row.reason is not None and row.reason.startswith(REASONS), row.reason
        event("feasible design" if row.feasible else (row.reason or "")[:12])


@property_settings(60)
@given(inputs=sound_study_bodies())
@example(  # a grid through a list fixed gives: the list elements are set, never created
    inputs={"process": "fourbar-grashof", "fixed": {"lengths": [30, 17, 18, 25], "ground": 0},
            "vary": {"lengths[0]": [1, 40, 3]}, "objectives": {"criterion.margin": "max"},
            "plots": False}
)  # fmt: skip
def test_an_accepted_study_runs_in_the_worker(inputs: dict[str, Any]) -> None:
    spec = accepted(inputs)
    event("accepted" if spec is not None else "refused")
    if spec is not None:
        check_in_the_worker(spec)


@property_settings(60)
@given(inputs=study_bodies())
@example(  # a grid wider than a float: its designs were infinite or NaN
    inputs={"process": "fourbar-grashof", "fixed": {"lengths": [30, 17, 18, 25], "ground": 0},
            "vary": {"lengths[0]": [-1e308, 1.7e308, 3]}, "objectives": {"criterion.margin": "max"}}
)  # fmt: skip
def test_any_accepted_study_runs_in_the_worker(inputs: dict[str, Any]) -> None:
    spec = accepted(inputs)
    event("accepted" if spec is not None else "refused")
    if spec is not None:
        check_in_the_worker(spec)
