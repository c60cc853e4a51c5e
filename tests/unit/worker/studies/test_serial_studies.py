"""Design studies over the serial family, unchanged: a DH row's length varied by its
indexed path ``robot.dh[1].a``, end to end through ``serial-indices`` and
``serial-reach``."""

from __future__ import annotations

import copy
from typing import Any

import pytest

from tests.unit.families.conftest import RecordingContext
from tests.unit.worker.studies.registry import STUDY, dry_check
from worker.families.serial.arms import EXAMPLE_1_PLANAR
from worker.studies.spec import StudySpec


def example_1_without_l2() -> dict[str, Any]:
    """Example 1's arm with row 1's ``a`` left to the study (varied, so not fixed)."""
    robot = copy.deepcopy(EXAMPLE_1_PLANAR)
    del robot["dh"][1]["a"]
    return robot


def run_study(body: dict[str, Any]) -> dict[str, Any]:
    study = StudySpec.model_validate({**body, "plots": False})
    assert dry_check(study) == []
    result: dict[str, Any] = STUDY.run(study, RecordingContext()).result
    return result


def test_a_study_varies_a_dh_length_of_serial_indices() -> None:
    """At θ2 = 90° the planar arm's manipulability is l1 l2: linear in the varied l2."""
    result = run_study({
        "process": "serial-indices",
        "fixed": {"robot": example_1_without_l2(), "configurations": [[0, 90, -90]],
                  "length_unit": "units"},
        "vary": {"robot.dh[1].a": [10, 14, 3]},
        "objectives": {"poses[].manipulability|min": "max"},
    })  # fmt: skip
    assert (result["count"], result["feasible"]) == (3, 3)
    best = result["best"]["poses[].manipulability|min"]
    assert [b["parameters"]["robot.dh[1].a"] for b in best] == [14.0, 12.0, 10.0]
    assert [b["objectives"]["poses[].manipulability|min"] for b in best] == pytest.approx(
        [15.0 * 14.0, 15.0 * 12.0, 15.0 * 10.0]
    )


def test_a_study_varies_a_dh_length_of_serial_reach() -> None:
    """Targets at 30 and 33 from the base: l1 + l2 + 8 must reach them, so l2 = 4 reaches
    none, 8 the first, 12 both (the closed form answers each design)."""
    targets = [{"position": [30.0, 0.0]}, {"position": [0.0, 33.0]}]
    result = run_study({
        "process": "serial-reach",
        "fixed": {"robot": example_1_without_l2(), "targets": targets, "length_unit": "units"},
        "vary": {"robot.dh[1].a": [4, 12, 3]},
        "objectives": {"summary.reached_share": "max"},
    })  # fmt: skip
    rows = {
        b["parameters"]["robot.dh[1].a"]: b["objectives"]["summary.reached_share"]
        for b in result["best"]["summary.reached_share"]
    }
    assert rows == {4.0: 0.0, 8.0: 0.5, 12.0: 1.0}


def test_a_dh_length_fixed_and_varied_is_refused_at_its_place() -> None:
    with pytest.raises(ValueError, match="both fixed and varied"):
        StudySpec.model_validate({
            "process": "serial-reach",
            "fixed": {"robot": copy.deepcopy(EXAMPLE_1_PLANAR),
                      "targets": [{"position": [9, 9]}]},
            "vary": {"robot.dh[1].a": [4, 12, 3]},
            "objectives": {"summary.reached_share": "max"},
        })  # fmt: skip
