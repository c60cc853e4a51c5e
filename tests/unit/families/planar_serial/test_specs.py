"""Inputs, costs and process definitions of the planar3r jobs."""

from __future__ import annotations

import json
import subprocess
import sys
from typing import Any

import pytest
from pydantic import ValidationError

from worker.families.planar_serial import DEXTERITY_MAP, SYNTHESIS
from worker.families.planar_serial.costs import COST_LIMIT, dexterity_map_cost, synthesis_cost
from worker.families.planar_serial.design_spec import DesignSpec
from worker.families.planar_serial.examples import PAPER_JOINT_LIMITS_DEG
from worker.families.planar_serial.specs import (
    DexterityMapSpec,
    PolylineTrajectory,
    PolynomialTrajectory,
    SynthesisSpec,
    default_task_labels,
)

LINKS = [15, 14, 8]
LIMITS = [list(pair) for pair in PAPER_JOINT_LIMITS_DEG]


def map_spec(**inputs: Any) -> DexterityMapSpec:
    return DexterityMapSpec.model_validate({"links": LINKS, **inputs})


def synthesis_spec(**inputs: Any) -> SynthesisSpec:
    return SynthesisSpec.model_validate({"l3": 8, "task_points": [[10, 2]], **inputs})


# -- valid inputs and defaults -------------------------------------------------------


def test_map_defaults() -> None:
    spec = map_spec()
    assert spec.links == (15.0, 14.0, 8.0)
    assert spec.joint_limits_deg is None
    assert spec.grid.bounds is None
    assert spec.grid.points_per_axis == 201
    assert spec.orientation_step_deg == 1.0
    assert spec.task_points is None and spec.trajectory is None
    assert spec.length_unit == "units"
    assert spec.labels == ()


def test_synthesis_defaults() -> None:
    spec = synthesis_spec()
    assert spec.round_distances is False
    assert spec.l3 == 8.0
    assert spec.labels == ("A",)


def test_default_labels_continue_past_z() -> None:
    labels = default_task_labels(28)
    assert labels[:3] == ("A", "B", "C")
    assert labels[25:] == ("Z", "AA", "AB")
    assert default_task_labels(26 * 27)[-1] == "ZZ"


def test_given_labels_are_kept() -> None:
    spec = map_spec(task_points=[[1, 2], [3, 4]], task_labels=["P", "Q"])
    assert spec.labels == ("P", "Q")


def test_trajectory_union_picks_the_model_by_key() -> None:
    polyline = map_spec(trajectory={"points": [[0, 0], [1, 1]]}).trajectory
    polynomial = map_spec(trajectory={"polynomial": [1, 0], "x_start": 0, "x_end": 1}).trajectory
    assert isinstance(polyline, PolylineTrajectory) and polyline.samples == 200
    assert isinstance(polynomial, PolynomialTrajectory) and polynomial.samples == 200


def test_models_are_frozen() -> None:
    spec = map_spec()
    with pytest.raises(ValidationError, match="frozen"):
        spec.length_unit = "mm"  # type: ignore[misc]


def test_specs_round_trip_through_json() -> None:
    spec = map_spec(
        joint_limits_deg=LIMITS,
        trajectory={"points": [[0, 0], [1, 1]], "samples": 5},
        task_points=[[1, 2]],
    )
    assert DexterityMapSpec.model_validate_json(spec.model_dump_json()) == spec


# -- invalid inputs ------------------------------------------------------------------

MAP_ERRORS = [
    ({"links": [15, 14, -8]}, r"links\.2\n  Input should be greater than or equal to 0.000001"),
    ({"links": [0, 14, 8]}, r"links\.0\n  Input should be greater than or equal to 0.000001"),
    ({"links": [15, 14]}, r"links needs three lengths \[l1, l2, l3\], not 2"),
    ({"links": [15, 14, float("nan")]}, "finite number"),
    ({"links": [15, float("inf"), 8]}, "finite number"),
    (
        {"joint_limits_deg": [[-150, 150], [160, 150], [-175, 175]]},
        r"joint_limits_deg\[1\]: lower limit 160 exceeds upper limit 150",
    ),
    (
        {"joint_limits_deg": [[-190, 150], [-150, 150], [-175, 175]]},
        r"joint_limits_deg\[0\]: lower limit -190 is outside \[-180, 180\]",
    ),
    ({"joint_limits_deg": [[-150, 150], [-150, 150]]}, r"one \[lo, hi\] pair per joint \(3\)"),
    ({"grid": {"points_per_axis": 2002}}, "less than or equal to 2001"),
    ({"grid": {"points_per_axis": 1}}, "greater than or equal to 2"),
    ({"grid": {"bounds": [5, -5, -5, 5]}}, "x_min 5 must be less than x_max -5"),
    ({"grid": {"bounds": [-5, 5, 1, 1]}}, "y_min 1 must be less than y_max 1"),
    ({"grid": {"spacing": 1}}, "Extra inputs are not permitted"),
    ({"orientation_step_deg": 0.05}, "greater than or equal to 0.1"),
    ({"orientation_step_deg": 31}, "less than or equal to 30"),
    ({"task_points": [[1, 2, 3]]}, "at most 2 items"),
    ({"task_points": []}, "at least 1 item"),
    ({"task_points": [[0, 0]] * 1001}, "at most 1000 items"),
    ({"task_points": [[0, 0]], "task_labels": ["A", "B"]}, "task_labels has 2 labels for 1"),
    ({"task_labels": ["A"]}, "task_labels given without task_points"),
    ({"task_points": [[0, 0]], "task_labels": [""]}, "at least 1 character"),
    ({"trajectory": {"points": [[0, 0]]}}, "at least 2 items"),
    ({"trajectory": {"points": [[1, 1], [1, 1]]}}, "the polyline has zero length"),
    ({"trajectory": {"points": [[0, 0], [1, 1]], "samples": 1}}, "greater than or equal to 2"),
    (
        {"trajectory": {"polynomial": [1, 2], "x_start": 3, "x_end": 3}},
        "x_start and x_end must differ",
    ),
    ({"trajectory": {"polynomial": [], "x_start": 0, "x_end": 1}}, "at least 1 item"),
    ({"trajectory": {"polynomial": [1] * 11, "x_start": 0, "x_end": 1}}, "at most 10 items"),
    (
        {"trajectory": {"polynomial": [1], "x_start": 0, "x_end": 1, "samples": 10001}},
        "less than or equal to 10000",
    ),
    ({"trajectory": {"polynomial": [1], "x_start": 0}}, r"x_end\n  Field required"),
    ({"trajectory": {"x_start": 0, "x_end": 1}}, "exactly one of 'points'"),
    (
        {"trajectory": {"points": [[0, 0], [1, 1]], "polynomial": [1]}},
        "exactly one of 'points'",
    ),
    ({"trajectory": [[0, 0], [1, 1]]}, "exactly one of 'points'"),
    ({"trajectory": {"points": [[0, 0], [1, 1]], "x_start": 0}}, "Extra inputs"),
    ({"length_unit": ""}, "at least 1 character"),
    ({"length_unit": "$x$"}, "should match pattern"),
    ({"length_unit": "a" * 17}, "at most 16 characters"),
    ({"colour": "red"}, "Extra inputs are not permitted"),
]


@pytest.mark.parametrize(("inputs", "message"), MAP_ERRORS)
def test_map_rejects(inputs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        map_spec(**inputs)


def test_trajectory_errors_name_the_branch() -> None:
    with pytest.raises(ValidationError) as info:
        map_spec(trajectory={"points": [[0, 0]]})
    assert info.value.errors()[0]["loc"] == ("trajectory", "polyline", "points")


SYNTHESIS_ERRORS = [
    ({"task_points": None}, "needs task_points or a trajectory"),
    ({"l3": 0}, "greater than or equal to 0.000001"),
    ({"l3": -1}, "greater than or equal to 0.000001"),
    ({"l3": float("inf")}, "finite number"),
    ({"round_distances": "sometimes"}, "valid boolean"),
    ({"links": LINKS}, "Extra inputs are not permitted"),
    (
        {"joint_limits_deg": [[-150, 150], [-150, 150], [175, -175]]},
        r"joint_limits_deg\[2\]: lower limit 175 exceeds upper limit -175",
    ),
]


@pytest.mark.parametrize(("inputs", "message"), SYNTHESIS_ERRORS)
def test_synthesis_rejects(inputs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        synthesis_spec(**inputs)


# -- issue 26, finding 4: joint limits typed in radians are refused -----------------

RADIANS = [[-2.618, 2.618], [-2.618, 2.618], [-3.054, 3.054]]


@pytest.mark.parametrize(
    "build",
    [
        lambda limits: map_spec(joint_limits_deg=limits),
        lambda limits: synthesis_spec(joint_limits_deg=limits),
        lambda limits: DesignSpec.model_validate(
            {"task_points": [[12, 8]], "total_length_max": 37, "joint_limits_deg": limits}
        ),
    ],
    ids=["planar3r-dexterity-map", "planar3r-synthesis", "planar3r-design"],
)
@pytest.mark.parametrize(
    "limits", [RADIANS, [[-1, 1], [0, 0], [-6.2832, 6.2832]], [[-5, 5]] * 3], ids=str
)
def test_limits_that_look_like_radians_are_refused(build: Any, limits: Any) -> None:
    with pytest.raises(ValidationError, match="degrees expected; these look like radians") as info:
        build(limits)
    assert [e["loc"] for e in info.value.errors()] == [("joint_limits_deg",)]


@pytest.mark.parametrize("limits", [[[-6.3, 6.3], [0, 0], [0, 0]], [[0, 90], [-1, 1], [-2, 2]]])
def test_one_value_beyond_2pi_is_degrees(limits: list[list[float]]) -> None:
    assert map_spec(joint_limits_deg=limits).joint_limits_deg is not None


def test_synthesis_accepts_a_trajectory_alone() -> None:
    spec = synthesis_spec(task_points=None, trajectory={"points": [[10, 0], [0, 12]]})
    assert spec.task_points is None and spec.labels == ()


# -- costs ---------------------------------------------------------------------------


def test_map_cost_is_grid_points_without_limits() -> None:
    assert dexterity_map_cost(map_spec(grid={"points_per_axis": 301})) == 301**2


def test_map_cost_counts_orientation_samples_under_limits() -> None:
    spec = map_spec(
        joint_limits_deg=LIMITS, orientation_step_deg=1.0, method="orientation-sampling"
    )
    assert dexterity_map_cost(spec) == 201**2 * 360


def test_exact_map_cost_counts_sub_arcs_under_limits() -> None:
    # 16 events (8 conditions, two roots each) and the cut at 0: 17 sub-arcs per point
    spec = map_spec(joint_limits_deg=LIMITS, orientation_step_deg=1.0)
    assert dexterity_map_cost(spec) == 201**2 * 17
    one_joint = map_spec(joint_limits_deg=[[-180, 180], [-90, 90], [-180, 180]])
    assert dexterity_map_cost(one_joint) == 201**2 * 9


def test_full_turn_limits_cost_like_no_limits() -> None:
    spec = map_spec(joint_limits_deg=[[-180, 180]] * 3, orientation_step_deg=0.1)
    assert dexterity_map_cost(spec) == 201**2


def test_cost_limit_admits_2001_squared_at_half_a_degree() -> None:
    spec = map_spec(
        joint_limits_deg=LIMITS, orientation_step_deg=0.5, grid={"points_per_axis": 2001},
        method="orientation-sampling",
    )  # fmt: skip
    assert dexterity_map_cost(spec) == 2001**2 * 720 <= COST_LIMIT
    finer = spec.model_copy(update={"orientation_step_deg": 0.4})
    assert dexterity_map_cost(finer) == 2001**2 * 900 > COST_LIMIT


def test_synthesis_cost() -> None:
    assert synthesis_cost(synthesis_spec()) == 2 * 201**2
    limited = synthesis_spec(joint_limits_deg=LIMITS, orientation_step_deg=2.0)
    assert synthesis_cost(limited) == (2 + 17) * 201**2
    sampled = limited.model_copy(update={"method": "orientation-sampling"})
    assert synthesis_cost(sampled) == (2 + 180) * 201**2
    full_turn = synthesis_spec(joint_limits_deg=[[-180, 180]] * 3)
    assert synthesis_cost(full_turn) == 3 * 201**2


# -- process definitions -------------------------------------------------------------


@pytest.mark.parametrize("process", [DEXTERITY_MAP, SYNTHESIS], ids=lambda p: p.id)
def test_process_definition(process: Any) -> None:
    assert process.id in {"planar3r-dexterity-map", "planar3r-synthesis"}
    assert process.cost_limit == 3_000_000_000
    assert process.time_limit_s == 1800
    description = json.loads(json.dumps(process.describe()))
    assert description["inputs"]["additionalProperties"] is False
    assert "3,000,000,000" in description["description"]
    assert process.examples
    for example in process.examples:
        spec = process.inputs_model.model_validate(dict(example.inputs))
        assert process.cost(spec) <= process.cost_limit


def test_public_field_names() -> None:
    assert set(DexterityMapSpec.model_json_schema()["properties"]) == {
        "links", "joint_limits_deg", "grid", "orientation_step_deg", "method",
        "task_points", "task_labels", "trajectory", "length_unit", "plots",
    }  # fmt: skip
    assert set(SynthesisSpec.model_json_schema()["properties"]) == {
        "task_points", "task_labels", "trajectory", "l3", "joint_limits_deg",
        "round_distances", "orientation_step_deg", "method", "grid", "length_unit", "plots",
    }  # fmt: skip


def test_field_descriptions_are_published() -> None:
    properties = DexterityMapSpec.model_json_schema()["properties"]
    assert all(p.get("description") for p in properties.values())


def test_import_does_no_heavy_work() -> None:
    code = (
        "import sys, worker.families.planar_serial; "
        "print(sorted(m for m in ('matplotlib', 'scipy', "
        "'worker.families.planar_serial.jobs.dexterity_map', "
        "'worker.families.planar_serial.jobs.synthesis') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
