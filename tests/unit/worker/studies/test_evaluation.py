"""A study's designs evaluated by the single-design process: the same numbers as the
process run alone, refusals kept with their reasons."""

from __future__ import annotations

from typing import Any

import pytest
from pydantic import ValidationError

from tests.unit.families.conftest import RecordingContext
from tests.unit.worker.studies.registry import STUDY_INPUTS
from worker.registry import default_registry
from worker.studies.evaluation import design_inputs, evaluate_block
from worker.studies.spec import StudySpec

MAP = default_registry().get("planar3r-dexterity-map")
LIMITS = [[-150, 150], [-150, 150], [-175, 175]]
STUDY: dict[str, Any] = {
    "process": "planar3r-dexterity-map",
    "fixed": {"links": [15, 14, 8], "joint_limits_deg": LIMITS, "grid": {"points_per_axis": 5},
              "task_points": [[14, 14], [8, -8]]},
    "vary": {"links[2]": [6, 10, 3], "links[0]": [14, 16, 2]},
    "objectives": {"task_points[].d_z|min": "max", "links|sum": "min"},
}  # fmt: skip


def test_objectives_are_the_single_process_values() -> None:
    spec = StudySpec.model_validate(STUDY)
    assert spec.designs.count == 6
    rows = evaluate_block(spec, MAP, 0, 6)
    assert [r.index for r in rows] == list(range(6))
    for row in rows:
        assert row.feasible
        inputs = design_inputs(spec, row.parameters)
        alone = MAP.run(MAP.inputs_model.model_validate({**inputs, "plots": False}),
                        RecordingContext()).result  # fmt: skip
        assert inputs["links"][2] == row.parameters[0] and inputs["links"][0] == row.parameters[1]
        assert row.objectives == (
            min(e["d_z"] for e in alone["task_points"]),
            sum(alone["links"]),
        )


def test_refusals_and_missing_values_are_kept_with_reasons() -> None:
    spec = StudySpec.model_validate({
        **STUDY, "vary": {"links[2]": [-1, 8, 2]},
        "objectives": {"task_points[].d_z|min": "max", "trajectory.d_z_min": "max"},
    })  # fmt: skip
    refused, missing = evaluate_block(spec, MAP, 0, 2)
    assert not refused.feasible and refused.reason is not None
    assert refused.reason.startswith("refused: Invalid value for 'inputs.links[2]'")
    assert refused.objectives == (None, None)
    assert not missing.feasible and missing.reason == "no value for trajectory.d_z_min"
    assert missing.objectives[0] is not None and missing.objectives[1] is None


def test_a_block_is_the_slice_of_the_whole() -> None:
    spec = StudySpec.model_validate(
        {**STUDY, "vary": None, "sample": {"count": 7, "bounds": {"links[2]": [5, 9]}, "seed": 3}}
    )
    whole = evaluate_block(spec, MAP, 0, 7)
    assert evaluate_block(spec, MAP, 3, 5) == whole[3:5]


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"process": "no-such"}, "is not a process a study can run"),
        ({"process": "design-study"}, "is not a process a study can run"),
        ({"sample": {"count": 3, "bounds": {"links[2]": [5, 9]}}}, "exactly one of"),
        ({"vary": None}, "exactly one of"),
        ({"vary": {"links[2]": [9, 5, 3]}}, "lo <= hi"),
        ({"vary": {"a": [0, 1, 1001], "b": [0, 1, 1001]}}, "more than 1,000,000"),
        ({"vary": {"links[]": [0, 1, 2]}}, "result paths only"),
        ({"objectives": {"task_points[].d_z": "max"}}, "reduce them"),
        ({"objectives": {}}, "at least 1"),
        ({"vary": {"grid": [1, 2, 2]}}, "both fixed and varied"),
    ],
)
def test_bad_studies_are_refused(change: dict[str, Any], message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        STUDY_INPUTS.model_validate({**STUDY, **change})
