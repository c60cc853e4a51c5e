"""A study's infeasible designs grouped by reason, the numbers their messages quote
left out (worker.studies.reason_groups); one design of a study as its process's
inputs (worker.studies.evaluation.one_design_inputs)."""

from __future__ import annotations

from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st

from worker.registry import worker_registry
from worker.studies.evaluation import one_design_inputs
from worker.studies.reason_groups import reason_groups, reason_text
from worker.studies.spec import StudySpec


def refusal(angle: float, designs: int, field: str = "inputs.angles") -> dict[str, Any]:
    message = f"angle {angle}° exceeds the joint limit '{angle / 2}'"
    return {"reason_code": "refused", "reason_field": field, "reason": message,
            "designs": designs}  # fmt: skip


def test_reasons_differing_only_in_quoted_numbers_are_one_group() -> None:
    reasons = [refusal(10.0 + k, 3 + k) for k in range(24)]
    failed = {"reason_code": "failed", "reason_field": "", "reason": "singular", "designs": 1}
    reasons += [refusal(5.0, 2, field="inputs.links"), failed]
    groups = reason_groups(reasons)
    assert [g["designs"] for g in groups] == [sum(3 + k for k in range(24)), 2, 1]
    first = groups[0]
    assert first["messages"] == 24 and first["reason_field"] == "inputs.angles"
    assert first["reason"] == "angle … exceeds the joint limit …"
    assert first["example"] == refusal(33.0, 26)["reason"]  # the most frequent message


@given(st.floats(allow_nan=False, allow_infinity=False), st.integers(-(10**9), 10**9))
def test_any_number_a_message_quotes_is_left_out(x: float, n: int) -> None:
    assert reason_text(f"value {x!r} and {n} in {x:.3g} m") == reason_text("value 1 and 2 in 3 m")


def test_a_design_of_a_grid_study_is_its_process_inputs_with_plots_on() -> None:
    registry = worker_registry()
    study = {"process": "planar3r-dexterity-map",
             "fixed": {"links": [15, 14, 8], "task_points": [[14, 14]]},
             "vary": {"links[0]": [-5, 20, 6], "links[2]": [2, 10, 5]},
             "objectives": {"links|sum": "min"}}  # fmt: skip
    process = registry.require("planar3r-dexterity-map")
    spec = StudySpec.model_validate(study)
    seen = {tuple(one_design_inputs(spec, process, i)["links"]) for i in range(30)}
    assert seen == {(a, 14.0, c) for a in (-5, 0, 5, 10, 15, 20) for c in (2, 4, 6, 8, 10)}
    inputs = one_design_inputs(spec, process, 7)
    assert inputs["plots"] is True and inputs["task_points"] == [[14, 14]]
    assert study["fixed"]["links"] == [15, 14, 8]  # the study's inputs are left alone
    for index in (-1, 30):
        with pytest.raises(IndexError):
            one_design_inputs(spec, process, index)
