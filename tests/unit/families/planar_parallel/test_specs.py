"""Inputs, costs and process definitions of the planar2dof jobs."""

from __future__ import annotations

import itertools
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from pydantic import ValidationError

from worker.errors import CostLimitExceeded, InvalidInputs
from worker.families.planar_parallel import CONDITIONING_MAP, OPTIMISATION
from worker.families.planar_parallel.costs import (
    CONDITIONING_MAP_COST_LIMIT,
    OPTIMISATION_COST_LIMIT,
    RECTANGLE_SEARCH_COST,
    conditioning_map_cost,
    optimisation_cost,
)
from worker.families.planar_parallel.specs import (
    ConditioningMapSpec,
    OptimisationSpec,
    sweep_deltas,
)
from worker.registry import default_registry
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.submission import submit, validate_inputs


def map_spec(**inputs: Any) -> ConditioningMapSpec:
    return ConditioningMapSpec.model_validate({"l2": 1.7, "architecture": "isotropic", **inputs})


def opt_spec(**inputs: Any) -> OptimisationSpec:
    return OptimisationSpec.model_validate({"allowable_pressure_angle_deg": 30, **inputs})


# -- valid inputs and defaults -------------------------------------------------------


def test_map_defaults() -> None:
    spec = map_spec()
    assert spec.actuation == "proximal-arm"
    assert spec.l1 == 1.0 and spec.l2 == 1.7 and spec.e is None
    assert spec.working_mode == (1, -1)
    assert spec.grid.bounds is None and spec.grid.points_per_axis == 201
    assert spec.inverse_condition_limit is None and spec.points is None
    assert spec.length_unit == "units" and spec.plots is True


def test_map_accepts_each_type() -> None:
    assert map_spec(architecture=None, e=0.3).e == 0.3
    telescopic = ConditioningMapSpec.model_validate({"actuation": "telescopic-leg", "e": 0.5})
    assert telescopic.l2 is None
    drive = ConditioningMapSpec.model_validate({"actuation": "linear-drive", "l2": 2})
    assert drive.e is None
    assert map_spec(working_mode=[-1, 1]).working_mode == (-1, 1)


def test_optimisation_defaults() -> None:
    spec = opt_spec()
    assert spec.inverse_condition_limit is None and spec.delta is None
    assert spec.aspect_ratio == 4.0 and spec.mean_mesh == 101
    # the sweep's defaults are resolved, not stored: a dumped spec validates again
    assert spec.delta_range is None and spec.delta_step is None
    assert spec.sweep_range == (1.0, 2.5) and spec.sweep_step == 0.01
    assert spec.sweep_size == 151


def test_single_delta_spec() -> None:
    spec = OptimisationSpec.model_validate({"inverse_condition_limit": 0.526, "delta": 1.7})
    assert spec.delta == 1.7 and spec.allowable_pressure_angle_deg is None


@pytest.mark.parametrize(
    "spec",
    [
        map_spec(points=[[0, -1.9]], inverse_condition_limit=0.5, working_mode=[1, 1]),
        opt_spec(delta_range=[1.2, 2], delta_step=0.05),
        OptimisationSpec.model_validate({"inverse_condition_limit": 0.5, "delta": 2}),
    ],
)
def test_specs_round_trip_through_json(spec: ConditioningMapSpec | OptimisationSpec) -> None:
    dumped = json.loads(spec.model_dump_json())  # what the job store keeps
    assert type(spec).model_validate(dumped) == spec


def test_models_are_frozen() -> None:
    with pytest.raises(ValidationError, match="frozen"):
        opt_spec().aspect_ratio = 2  # type: ignore[misc]


@pytest.mark.parametrize(
    ("lo", "hi", "step", "expected"),
    [
        (1.0, 2.5, 0.01, 151),
        (1.0, 2.5, 0.4, 5),  # 1, 1.4, 1.8, 2.2 and the end 2.5
        (1.0, 1.3, 0.1, 4),
        (1.0, 1.05, 0.1, 2),
    ],
)
def test_sweep_deltas_end_on_hi(lo: float, hi: float, step: float, expected: int) -> None:
    deltas = sweep_deltas(lo, hi, step)
    assert len(deltas) == expected
    assert deltas[0] == lo and deltas[-1] == hi
    assert all(b > a for a, b in itertools.pairwise(deltas))
    assert (
        OptimisationSpec.model_validate(
            {"inverse_condition_limit": 0.5, "delta_range": [lo, hi], "delta_step": step}
        ).sweep_size
        == expected
    )


def test_sweep_deltas_are_the_papers_grid() -> None:
    deltas = sweep_deltas(1.0, 2.5, 0.01)
    assert deltas[70] == 1.7 and deltas[85] == 1.85


# -- invalid inputs ------------------------------------------------------------------

MAP_ERRORS = [
    ({"architecture": None}, "exactly one of 'e'"),
    ({"e": 0.5}, "exactly one of 'e'"),
    ({"architecture": "optimal"}, "Input should be 'isotropic'"),
    ({"l2": 0.5}, r"isotropic' needs l2 >= l1"),
    ({"l2": None}, "l2 is required for the proximal-arm type"),
    ({"l2": -1}, "greater than or equal to 0.000001"),
    ({"l1": 0}, "greater than or equal to 0.000001"),
    ({"l1": 5e-324}, r"l1\n  Input should be greater than or equal to 0.000001"),
    ({"l2": 1e6 + 1}, r"l2\n  Input should be less than or equal to 1000000"),
    ({"l1": 1e-6, "l2": 1.01}, r"l2\n.*the longest \(1.01\) is 1.01e\+06 times the shortest"),
    ({"architecture": None, "e": 1e-7}, r"e\n.*e is 0 \(coincident actuated joints\) or a "),
    ({"architecture": None, "e": 2e6}, r"e\n  Input should be less than or equal to 1000000"),
    ({"architecture": None, "l2": 2, "e": 2.1e6}, r"e\n  Input should be less than or equal"),
    ({"architecture": None, "l2": 2, "e": 1.5e-6}, r"e\n.*1.33e\+06 times the shortest"),
    ({"l2": float("nan")}, "finite number"),
    ({"architecture": None, "e": -0.1}, "greater than or equal to 0"),
    ({"actuation": "cable"}, "'proximal-arm', 'telescopic-leg' or 'linear-drive'"),
    ({"actuation": "telescopic-leg"}, r"'isotropic' \(eq 12\) is the proximal-arm type's"),
    ({"actuation": "telescopic-leg", "architecture": None}, "telescopic-leg type needs 'e'"),
    ({"actuation": "linear-drive", "architecture": None, "l2": None}, "l2 is required"),
    ({"working_mode": [1, 0]}, r"working_mode entries must be \+1 or -1; got 0"),
    ({"working_mode": [1, 2]}, r"working_mode entries must be \+1 or -1; got 2"),
    ({"working_mode": [True, -1]}, r"must be \+1 or -1; got True"),
    ({"working_mode": [1, -1, 1]}, r"two signs \[sgn1, sgn2\], not 3"),
    ({"grid": {"points_per_axis": 2002}}, "less than or equal to 2001"),
    ({"grid": {"points_per_axis": 1}}, "greater than or equal to 2"),
    ({"grid": {"bounds": [1, -1, -2, 0]}}, "x_min 1 must be less than x_max -1"),
    ({"grid": {"bounds": [-1, 1, 0, 0]}}, "y_min 0 must be less than y_max 0"),
    ({"grid": {"bounds": [-2e6, 1, 0, 1]}}, r"grid\.bounds\.0\n.*than or equal to -1000000"),
    (
        {"grid": {"bounds": [0, 1e-4, 0, 1]}},
        r"grid\.bounds\n.*the grid's x step 5e-07 is below 1e-06: widen the bounds",
    ),
    ({"grid": {"bounds": [0, 1, 0, 2e-4], "points_per_axis": 2001}}, "y step 1e-07 is below"),
    (
        {"grid": {"bounds": [0, 1e-6, 0, 1], "points_per_axis": 2}},
        r"grid\.bounds\n.*x side 1e-06 and the robot's longest length 1.7 differ by more than",
    ),
    ({"l1": 1e-6, "l2": 1e-6, "grid": {"bounds": [-1e6, 1e6, -1, 1]}}, r"x side 2e\+06 and"),
    ({"grid": {"step": 0.1}}, "Extra inputs are not permitted"),
    ({"inverse_condition_limit": 0}, "greater than or equal to 0.000001"),
    ({"inverse_condition_limit": 5e-324}, "greater than or equal to 0.000001"),
    ({"inverse_condition_limit": 1}, "less than 1"),
    ({"points": []}, "at least 1 item"),
    ({"points": [[0, 0, 0]]}, "at most 2 items"),
    ({"points": [[0, float("inf")]]}, "finite number"),
    ({"points": [[0, 1e300]]}, r"points\.0\.1\n  Input should be less than or equal to 1000000"),
    ({"points": [[0, 0]] * 1001}, "at most 1000 items"),
    ({"length_unit": "$x$"}, "should match pattern"),
    ({"delta": 1.7}, "Extra inputs are not permitted"),
]


@pytest.mark.parametrize(("inputs", "message"), MAP_ERRORS)
def test_map_rejects(inputs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        map_spec(**inputs)


OPT_ERRORS = [
    ({"inverse_condition_limit": 0.5}, "exactly one of 'allowable_pressure_angle_deg'"),
    ({"allowable_pressure_angle_deg": None}, "exactly one of 'allowable_pressure_angle_deg'"),
    ({"allowable_pressure_angle_deg": 0}, "greater than or equal to 1"),
    ({"allowable_pressure_angle_deg": 0.5}, "greater than or equal to 1"),
    ({"allowable_pressure_angle_deg": 90}, "less than 90"),
    ({"allowable_pressure_angle_deg": float("nan")}, "finite number"),
    ({"delta": 1.7, "delta_range": [1, 2]}, "give either 'delta' or a sweep"),
    ({"delta": 1.7, "delta_step": 0.1}, "give either 'delta' or a sweep"),
    ({"delta": 0.5}, "greater than or equal to 1"),
    ({"delta": 11}, "less than or equal to 10"),
    ({"delta_range": [2, 1]}, "delta_range: lo 2 must be less than hi 1"),
    ({"delta_range": [1.5, 1.5]}, "lo 1.5 must be less than hi 1.5"),
    ({"delta_range": [0.5, 2]}, r"must lie within \[1, 10\]: the isotropic architecture"),
    ({"delta_range": [1, 12]}, r"delta_range \[1, 12\] must lie within \[1, 10\]"),
    ({"delta_range": [1, 2, 3]}, r"delta_range needs two values \[lo, hi\], not 3"),
    ({"delta_step": 0}, "greater than or equal to 0.000001"),
    ({"delta_step": 5e-324}, r"delta_step\n  Input should be greater than or equal to 0.000001"),
    (
        {"delta_range": [1, 10], "delta_step": 0.0005},
        r"delta_step\n.*\[1, 10\] at step 0.0005 holds more than 10001 deltas",
    ),
    (
        {"delta_range": [3.6, 4]},
        r"delta_range\n.*\[beta\] = 30°, eq \(17\)'s point is out of "
        r"reach for delta >= 3.58726",
    ),
    ({"aspect_ratio": 0}, "greater than or equal to 0.01"),
    ({"aspect_ratio": 0.009}, "greater than or equal to 0.01"),
    ({"aspect_ratio": 101}, "less than or equal to 100"),
    ({"mean_mesh": 1}, "greater than or equal to 2"),
    ({"mean_mesh": 1002}, "less than or equal to 1001"),
    ({"mean_mesh": 10.5}, "valid integer"),
    ({"working_mode": [1, -1]}, "Extra inputs are not permitted"),
]


@pytest.mark.parametrize(("inputs", "message"), OPT_ERRORS)
def test_optimisation_rejects(inputs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        opt_spec(**inputs)


def test_field_errors_name_the_field() -> None:
    with pytest.raises(InvalidInputs) as info:
        validate_inputs(OPTIMISATION, {"allowable_pressure_angle_deg": 30, "mean_mesh": 1})
    assert info.value.errors[0]["field"] == "inputs.mean_mesh"
    with pytest.raises(InvalidInputs) as info:
        validate_inputs(CONDITIONING_MAP, {"l2": 1.5, "e": 0.2, "working_mode": [1, 3]})
    assert info.value.errors[0]["field"] == "inputs.working_mode"


# -- costs ---------------------------------------------------------------------------


def test_map_cost() -> None:
    assert conditioning_map_cost(map_spec()) == 201**2
    assert conditioning_map_cost(map_spec(points=[[0, -1]] * 3)) == 201**2 + 3
    with_limit = map_spec(inverse_condition_limit=0.5, grid={"points_per_axis": 301})
    assert conditioning_map_cost(with_limit) == 301**2 + 801 * 321


def test_map_cost_limit_admits_2001_squared() -> None:
    spec = map_spec(inverse_condition_limit=0.5, grid={"points_per_axis": 2001},
                    points=[[0, -1]] * 1000)  # fmt: skip
    assert conditioning_map_cost(spec) <= CONDITIONING_MAP_COST_LIMIT == 5_000_000


def test_optimisation_cost_of_the_default_sweep() -> None:
    figures = 201**2 + 301**2
    assert optimisation_cost(opt_spec()) == 151 * (101**2 + RECTANGLE_SEARCH_COST) + figures
    assert optimisation_cost(opt_spec(mean_mesh=201)) == 151 * (201**2 + 60_000) + figures


def test_optimisation_cost_of_a_single_delta() -> None:
    spec = OptimisationSpec.model_validate({"inverse_condition_limit": 0.526, "delta": 1.7})
    # the design, plus S_max's 151 rectangles over the paper's range on a 2 x 2 mesh
    expected = 101**2 + 60_000 + 151 * (4 + 60_000) + 201**2 + 301**2
    assert optimisation_cost(spec) == expected


def test_optimisation_cost_limit_allows_the_default_sweep_and_more() -> None:
    assert optimisation_cost(opt_spec()) * 10 < OPTIMISATION_COST_LIMIT
    # the paper's range at step 0.001 on the default mesh fits; on a 401² mesh it does not
    fine = opt_spec(delta_step=0.001)
    assert optimisation_cost(fine) <= OPTIMISATION_COST_LIMIT
    assert optimisation_cost(fine.model_copy(update={"mean_mesh": 401})) > OPTIMISATION_COST_LIMIT


def test_submission_refuses_work_over_the_limit(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'jobs.db'}")
    registry = default_registry()
    inputs = {"allowable_pressure_angle_deg": 30, "delta_step": 0.001, "mean_mesh": 401}
    with pytest.raises(CostLimitExceeded, match="1/kappa evaluations, above the limit of"):
        submit(store, registry, WorkerSettings(), "planar2dof-optimisation", inputs)
    job, created = submit(store, registry, WorkerSettings(), "planar2dof-optimisation",
                          {"allowable_pressure_angle_deg": 30})  # fmt: skip
    assert created and job.time_limit_s == 600.0
    assert job.inputs == {
        "allowable_pressure_angle_deg": 30.0, "inverse_condition_limit": None,
        "aspect_ratio": 4.0, "delta_range": None, "delta_step": None, "delta": None,
        "mean_mesh": 101, "plots": True,
    }  # fmt: skip


# -- process definitions -------------------------------------------------------------


@pytest.mark.parametrize("process", [CONDITIONING_MAP, OPTIMISATION], ids=lambda p: p.id)
def test_process_definition(process: Any) -> None:
    description = json.loads(json.dumps(process.describe()))
    assert description["inputs"]["additionalProperties"] is False
    assert description["limits"]["cost_unit"] == "1/kappa evaluations"
    assert f"{process.cost_limit:,}" in description["description"]
    assert all(p.get("description") for p in description["inputs"]["properties"].values())
    assert process.examples
    for example in process.examples:
        spec = process.inputs_model.model_validate(dict(example.inputs))
        assert process.cost(spec) <= process.cost_limit


def test_processes_are_registered_after_planar3r() -> None:
    ids = default_registry().ids()
    assert ids.index("planar2dof-conditioning-map") == ids.index("planar3r-design") + 1
    assert ids.index("planar2dof-optimisation") == ids.index("planar3r-design") + 2


def test_public_field_names() -> None:
    assert set(ConditioningMapSpec.model_json_schema()["properties"]) == {
        "actuation", "l1", "l2", "e", "architecture", "working_mode", "grid",
        "inverse_condition_limit", "points", "length_unit", "plots",
    }  # fmt: skip
    assert set(OptimisationSpec.model_json_schema()["properties"]) == {
        "allowable_pressure_angle_deg", "inverse_condition_limit", "aspect_ratio",
        "delta_range", "delta_step", "delta", "mean_mesh", "plots",
    }  # fmt: skip


def test_import_does_no_heavy_work() -> None:
    code = (
        "import sys, worker.families.planar_parallel; "
        "print(sorted(m for m in ('matplotlib', 'scipy', "
        "'worker.families.planar_parallel.kinematics', "
        "'worker.families.planar_parallel.jobs.conditioning_map', "
        "'worker.families.planar_parallel.jobs.optimisation') "
        "if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
