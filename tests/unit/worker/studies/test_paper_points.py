"""The paper's designs a study contains: found by their varied inputs (within the
study's bounds) and their other inputs (equal to the study's, defaults included),
listed in the result with the study's design there, and reproduced where the study
evaluates them (Bai 2010, Table 1)."""

from __future__ import annotations

import dataclasses
from typing import Any

import pytest

from tests.unit.families.conftest import RecordingContext
from tests.unit.worker.studies.registry import STUDY
from worker.processes import PaperPoint
from worker.registry import default_registry
from worker.studies.paper_points import paper_marks
from worker.studies.spec import StudySpec

SPM = default_registry().get("spm-conditioning-map")
assert SPM is not None
EXAMPLE_I = {"tilt_max_deg": 60, "torsion_deg": [0, 360]}
OBJECTIVES = {"indices.rms_inverse_condition": "max", "indices.min_inverse_condition": "max"}


def study(fixed: dict[str, Any], **space: Any) -> StudySpec:
    space = space or {"vary": {"alpha1_deg": [50, 70, 3], "alpha2_deg": [80, 100, 3]}}
    return StudySpec.model_validate(
        {"process": "spm-conditioning-map", "fixed": fixed, "objectives": OBJECTIVES, **space}
    )


def labels(spec: StudySpec) -> list[str]:
    assert SPM is not None
    return [m.label for m in paper_marks(spec, SPM)]


def test_table_1_is_in_a_study_of_its_workspace_and_beta() -> None:
    spec = study({"beta_deg": 90, "gamma_deg": 0, "workspace": EXAMPLE_I})
    assert SPM is not None
    (mark,) = paper_marks(spec, SPM)
    assert mark.label == "Table 1 optimum (60°, 90°)"
    assert mark.parameters == (60.0, 90.0)
    assert mark.row == 4  # the middle of the 3 x 3 grid


def test_a_default_counts_as_given() -> None:
    """gamma_deg is not among the fixed inputs: the process's default (0) is Table 1's."""
    assert labels(study({"beta_deg": 90, "workspace": EXAMPLE_I})) == ["Table 1 optimum (60°, 90°)"]


@pytest.mark.parametrize(
    ("fixed", "space"),
    [
        ({"beta_deg": 75, "gamma_deg": 0, "workspace": EXAMPLE_I}, {}),  # another beta
        ({"beta_deg": 90, "gamma_deg": 0,  # another workspace (Example II's)
          "workspace": {"tilt_max_deg": 45, "torsion_deg": [0, 360]}}, {}),
        ({"beta_deg": 90, "gamma_deg": 0, "workspace": EXAMPLE_I},  # 60 outside [65, 80]
         {"vary": {"alpha1_deg": [65, 80, 4], "alpha2_deg": [80, 100, 3]}}),
        ({"alpha2_deg": 90, "gamma_deg": 0, "workspace": EXAMPLE_I},  # beta varied: not
         {"vary": {"alpha1_deg": [50, 70, 3], "beta_deg": [80, 100, 3]}}),  # a point there
    ],
)  # fmt: skip
def test_a_point_outside_the_study_is_not_marked(
    fixed: dict[str, Any], space: dict[str, Any]
) -> None:
    marks = labels(study(fixed, **space))
    if "beta_deg" in space.get("vary", {}):
        assert marks == ["Table 1 optimum (60°, 90°)"]  # beta = 90 is in [80, 100]
    else:
        assert marks == []


def test_a_sample_contains_a_point_but_has_no_design_there() -> None:
    spec = study(
        {"beta_deg": 90, "gamma_deg": 0, "workspace": EXAMPLE_I},
        sample={"method": "sobol", "count": 4, "seed": 1,
                "bounds": {"alpha1_deg": [45, 135], "alpha2_deg": [60, 120]}},
    )  # fmt: skip
    assert SPM is not None
    marks = paper_marks(spec, SPM)
    assert [m.label for m in marks] == [
        "Table 1 optimum (60°, 90°)",
        "Table 1 optimum's twin (120°, 90°)",
    ]
    assert all(m.row is None for m in marks)


def test_a_point_off_the_grid_has_no_row() -> None:
    spec = study(
        {"beta_deg": 90, "gamma_deg": 0, "workspace": EXAMPLE_I},
        vary={"alpha1_deg": [55, 75, 3], "alpha2_deg": [80, 100, 3]},  # 55, 65, 75
    )
    assert SPM is not None
    (mark,) = paper_marks(spec, SPM)
    assert mark.row is None


def test_a_point_whose_inputs_the_process_refuses_is_not_marked() -> None:
    spec = study({"beta_deg": 90, "gamma_deg": 0, "workspace": EXAMPLE_I})
    assert SPM is not None
    odd = PaperPoint("odd", {"alpha1_deg": 60, "alpha2_deg": 90, "workspace.tilt_max_deg": 500})
    refused = PaperPoint("refused", {"alpha1_deg": 60, "alpha2_deg": 90, "branch": "sideways"})
    assert paper_marks(spec, dataclasses.replace(SPM, paper_points=(odd, refused))) == []


def test_the_study_reproduces_table_1_at_its_design() -> None:
    """Bai 2010, Table 1: (60, 90, 90, 0) over Example I; the paper prints the square of
    C_n, 0.28 for 0.2974 (docs/methods/spherical-parallel.md), so C_n = 0.5453 on the
    default 144 samples; it is the study's best design."""
    spec = study({"beta_deg": 90, "gamma_deg": 0, "workspace": EXAMPLE_I})
    outcome = STUDY.run(spec.model_copy(update={"plots": False}), RecordingContext())
    (point,) = outcome.result["paper_points"]
    assert point["label"] == "Table 1 optimum (60°, 90°)"
    assert point["parameters"] == {"alpha1_deg": 60.0, "alpha2_deg": 90.0}
    c_n = point["design"]["objectives"]["indices.rms_inverse_condition"]
    assert c_n == pytest.approx(0.5453, abs=5e-5)
    assert c_n**2 == pytest.approx(0.2974, abs=5e-5)
    best = outcome.result["best"]["indices.rms_inverse_condition"][0]
    assert best["parameters"] == {"alpha1_deg": 60.0, "alpha2_deg": 90.0}
