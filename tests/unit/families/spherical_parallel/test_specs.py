"""Inputs, costs and process definitions of the spm jobs."""

from __future__ import annotations

import json
import subprocess
import sys
from typing import Any

import pytest
from pydantic import ValidationError

from worker.families.spherical_parallel import CONDITIONING_MAP, DESIGN_SPACE, OPTIMISATION
from worker.families.spherical_parallel.costs import (
    CONDITIONING_MAP_COST_LIMIT,
    CONDITIONING_MAP_SYNC_COST_LIMIT,
    DESIGN_OVERHEAD,
    DESIGN_SPACE_SYNC_COST_LIMIT,
    LIMITED_WIDTH_COST,
    WORKSPACE_MINIMUM_COST,
    conditioning_map_cost,
    design_space_cost,
    optimisation_cost,
)
from worker.families.spherical_parallel.optimisation_spec import SCREEN_PER_START, OptimisationSpec
from worker.families.spherical_parallel.specs import BetaRange, ConditioningMapSpec, DesignSpaceSpec
from worker.registry import default_registry

CONE_120 = {"tilt_max_deg": 60}
DESIGN = {"alpha1_deg": 60, "alpha2_deg": 90, "beta_deg": 90}
PROCESSES = [CONDITIONING_MAP, DESIGN_SPACE, OPTIMISATION]


def map_spec(**inputs: Any) -> ConditioningMapSpec:
    return ConditioningMapSpec.model_validate({**DESIGN, "workspace": CONE_120, **inputs})


def space_spec(**inputs: Any) -> DesignSpaceSpec:
    return DesignSpaceSpec.model_validate({"workspace": CONE_120, "beta_deg": [75], **inputs})


def optimisation_spec(**inputs: Any) -> OptimisationSpec:
    return OptimisationSpec.model_validate({"workspace": CONE_120, **inputs})


# -- valid inputs and defaults -------------------------------------------------------


def test_map_defaults_are_the_papers_sampling() -> None:
    spec = map_spec()
    assert spec.gamma_deg == 0.0 and spec.branch == -1 and spec.plots is True
    ws = spec.workspace
    assert ws.torsion_deg == (0.0, 360.0) and ws.full_turn
    assert (ws.samples.azimuth, ws.samples.tilt, ws.samples.torsion) == (4, 12, 3)
    assert ws.samples.count == 144
    assert spec.map_torsions == (0.0, 30.0, 60.0)
    assert spec.sweeps == ((35.0, 20.0), (35.0, 40.0), (35.0, 60.0))


def test_map_defaults_for_a_limited_torsion_range() -> None:
    spec = map_spec(workspace={"tilt_max_deg": 45, "torsion_deg": [-15, 15]})
    assert not spec.workspace.full_turn
    assert spec.map_torsions == (-15.0, 0.0, 15.0)
    assert spec.sweeps == ((35.0, 15.0), (35.0, 30.0), (35.0, 45.0))  # the paper's Fig. 7


def test_a_full_turn_may_start_anywhere() -> None:
    assert map_spec(workspace={"tilt_max_deg": 60, "torsion_deg": [-180, 180]}).workspace.full_turn
    assert not map_spec(workspace={"tilt_max_deg": 60, "torsion_deg": [0, 359]}).workspace.full_turn


def test_beta_list_and_range() -> None:
    assert space_spec(beta_deg=[60, 75, 90]).betas == (60.0, 75.0, 90.0)
    spec = space_spec(beta_deg={"start": 20, "stop": 70, "step": 5})
    assert isinstance(spec.beta_deg, BetaRange)
    assert spec.betas == tuple(float(b) for b in range(20, 71, 5))
    assert space_spec(beta_deg={"start": 60, "stop": 61, "step": 0.3}).betas == (
        60.0, 60.3, 60.6, 60.9,
    )  # fmt: skip
    assert space_spec(beta_deg={"start": 75, "stop": 75, "step": 1}).betas == (75.0,)


def test_gamma_for_each_beta() -> None:
    assert space_spec().gamma_for(75.0) == 0.0
    assert space_spec(gamma_deg=20).gamma_for(75.0) == 20.0
    assert space_spec(identical_platforms=True).gamma_for(33.3) == 33.3


def test_optimisation_defaults_hold_gamma_at_zero() -> None:
    spec = optimisation_spec()
    assert spec.free == ("alpha1", "alpha2", "beta")
    assert spec.held == {"gamma": 0.0}
    assert spec.solver_variables == 3
    assert (spec.starts, spec.seed, spec.max_evaluations_per_start) == (8, 0, 100)
    assert spec.singularity_tolerance is None and spec.branch == -1


def test_optimisation_held_values() -> None:
    identical = optimisation_spec(identical_platforms=True, free=["alpha1", "alpha2"],
                                  beta_deg=33.3)  # fmt: skip
    assert identical.held == {"beta": 33.3}
    held = optimisation_spec(free=["alpha1", "beta", "gamma"], alpha2_deg=90)
    assert held.held == {"alpha2": 90.0} and held.solver_variables == 3


@pytest.mark.parametrize(
    "spec",
    [
        map_spec(orientations=[[0, 30, 0]], map_torsions_deg=[10], torsion_sweeps=[[0, 10]]),
        space_spec(beta_deg={"start": 60, "stop": 90, "step": 15}, index_map={"beta_deg": 75}),
        space_spec(identical_platforms=True),
        optimisation_spec(identical_platforms=True, bounds={"beta_deg": [20, 60]}),
        optimisation_spec(free=["alpha1"], alpha2_deg=90, beta_deg=90, gamma_deg=10),
    ],
    ids=["map", "space", "identical", "optimisation", "held"],
)
def test_specs_round_trip_through_json(spec: Any) -> None:
    assert type(spec).model_validate_json(spec.model_dump_json()) == spec


def test_models_are_frozen() -> None:
    spec = map_spec()
    with pytest.raises(ValidationError, match="frozen"):
        spec.branch = 1  # type: ignore[misc]


# -- invalid inputs ------------------------------------------------------------------

MAP_ERRORS = [
    ({"alpha1_deg": 180}, r"alpha1_deg\n  Input should be less than or equal to 179\.999999"),
    ({"alpha1_deg": 179.9999995}, r"alpha1_deg\n  Input should be less than or equal to 179"),
    ({"beta_deg": 0}, r"beta_deg\n  Input should be greater than or equal to 0.000001"),
    ({"beta_deg": 5e-324}, r"beta_deg\n  Input should be greater than or equal to 0.000001"),
    ({"gamma_deg": 179.9999995}, r"gamma_deg\n  Input should be less than or equal to 179"),
    ({"gamma_deg": -1}, r"gamma_deg\n  Input should be greater than or equal to 0"),
    ({"alpha2_deg": float("nan")}, "finite number"),
    ({"branch": 0}, r"branch\n  Input should be -1 or 1"),
    ({"workspace": {"tilt_max_deg": 0}},
     r"tilt_max_deg\n  Input should be greater than or equal to 0.000001"),
    ({"workspace": {"tilt_max_deg": 180}}, "less than or equal to 179.999999"),
    ({"workspace": {"tilt_max_deg": 60, "torsion_deg": [10, 10.0000001]}},
     r"workspace\.torsion_deg\n.*spans 1e-07°, less than 1e-06°"),
    ({"workspace": {"tilt_max_deg": 60, "torsion_deg": [10, 10]}},
     r"workspace\.torsion_deg\n.*lo 10 must be less than hi 10"),
    ({"workspace": {"tilt_max_deg": 60, "torsion_deg": [30, -30]}}, "lo 30 must be less than hi"),
    ({"workspace": {"tilt_max_deg": 60, "torsion_deg": [-200, 200]}},
     r"hi - lo = 400 exceeds a full turn \(360\)"),
    ({"workspace": {"tilt_max_deg": 60, "torsion_deg": [0, 400]}}, r"hi 400 is outside \[-360"),
    ({"workspace": {"tilt_max_deg": 60, "torsion_deg": [0]}}, r"two angles \[lo, hi\], not 1"),
    ({"workspace": {"tilt_max_deg": 60, "samples": {"azimuth": 0}}},
     r"samples\.azimuth\n  Input should be greater than or equal to 1"),
    ({"workspace": {"tilt_max_deg": 60, "samples": {"tilt": 361}}}, "less than or equal to 360"),
    ({"workspace": {"tilt_max_deg": 60, "samples": {"spin": 3}}}, "Extra inputs"),
    ({"workspace": {"tilt_max_deg": 60, "opening_deg": 120}}, "Extra inputs"),
    ({"orientations": [[0, 200, 0]]}, r"orientations\[0\]: tilt psi2 200 is outside \[0, 180\]"),
    ({"orientations": [[0, 20, 0], [400, 20, 0]]}, r"orientations\[1\]: azimuth psi1 400"),
    ({"orientations": [[0, 20]]}, r"an orientation needs \[psi1, psi2, psi3\], not 2"),
    ({"orientations": []}, "at least 1 item"),
    ({"orientations": [[0, 0, 0]] * 1001}, "at most 1000 items"),
    ({"map_torsions_deg": [0] * 7}, "at most 6 items"),
    ({"map_torsions_deg": [500]}, r"map_torsions_deg\[0\]: 500 is outside"),
    ({"torsion_sweeps": [[0, -5]]}, r"torsion_sweeps\[0\]: tilt psi2 -5 is outside"),
    ({"map_grid": {"azimuth": 4}}, "greater than or equal to 5"),
    ({"colour": "red"}, "Extra inputs are not permitted"),
]  # fmt: skip


@pytest.mark.parametrize(("inputs", "message"), MAP_ERRORS)
def test_map_rejects(inputs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        map_spec(**inputs)


SPACE_ERRORS = [
    ({"beta_deg": 75}, r"beta_deg\n  beta_deg must be a list of angles \[b1, b2, \.\.\.\] or a "
     r"range \{'start', 'stop', 'step'\}"),
    ({"beta_deg": "75"}, "must be a list of angles"),
    ({"beta_deg": []}, "beta_deg holds 0 angles; give 1 to 721"),
    ({"beta_deg": [0]}, r"beta_deg\.BetaList\.0\n  Input should be greater than or equal to 0.0"),
    ({"beta_deg": [75] * 722}, "holds 722 angles"),
    ({"beta_deg": {"start": 80, "stop": 60, "step": 5}}, "stop 60 must not be less than start 80"),
    ({"beta_deg": {"start": 60, "stop": 80}}, r"beta_deg\.BetaRange\.step\n  Field required"),
    ({"beta_deg": {"start": 1, "stop": 179, "step": 0.1}},
     r"beta_deg\.BetaRange\.step\n.*\[1, 179\] at step 0.1 holds more than 721 betas"),
    ({"beta_deg": {"start": 60, "stop": 80, "step": 0}}, "greater than or equal to 0.000001"),
    ({"beta_deg": {"start": 1, "stop": 2, "step": 5e-324}}, "greater than or equal to 0.000001"),
    ({"beta_deg": {"start": 1, "stop": 179, "step": 1e-6}}, "holds more than 721 betas"),
    ({"beta_deg": {"start": 60, "stop": 80, "step": 5, "end": 9}}, "Extra inputs"),
    ({"identical_platforms": True, "gamma_deg": 10},
     r"gamma_deg\n  Value error, gamma_deg and identical_platforms exclude each other"),
    ({"gamma_deg": 180}, "less than or equal to 179.999999"),
    ({"index_map": {"beta_deg": 75, "points_per_side": 2}}, "greater than or equal to 3"),
    ({"index_map": {}}, r"index_map\.beta_deg\n  Field required"),
]  # fmt: skip


@pytest.mark.parametrize(("inputs", "message"), SPACE_ERRORS)
def test_design_space_rejects(inputs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        space_spec(**inputs)


OPTIMISATION_ERRORS = [
    ({"identical_platforms": True, "gamma_deg": 10},
     r"gamma_deg\n  Value error, gamma_deg and identical_platforms exclude each other"),
    ({"identical_platforms": True, "free": ["alpha1", "alpha2", "gamma"], "beta_deg": 30},
     r"free\n  Value error, 'gamma' cannot be free with identical_platforms"),
    ({"free": ["alpha1", "alpha2"]}, r"beta_deg\n  Value error, beta is not free: give beta_deg"),
    ({"alpha1_deg": 60}, r"alpha1_deg\n  Value error, alpha1_deg is given but alpha1 is free"),
    ({"free": ["alpha1", "alpha1"]}, r"free\n  Value error, free lists a parameter twice"),
    ({"free": ["delta"]}, r"free\.0\n  Input should be 'alpha1', 'alpha2', 'beta' or 'gamma'"),
    ({"free": []}, "at least 1 item"),
    ({"free": ["alpha1", "alpha2", "beta", "gamma"], "gamma_deg": 0},
     "gamma_deg is given but gamma is free"),
    ({"bounds": {"gamma_deg": [0, 10]}}, r"bounds\n  Value error, bounds.gamma_deg is given but "
     "gamma is not free"),
    ({"bounds": {"beta_deg": [0, 10]}}, "beta's lower bound 0 must be at least 1e-06"),
    ({"bounds": {"beta_deg": [50, 10]}}, r"\[50, 10\] must satisfy 0 <= lo < hi <= 179.999999"),
    ({"bounds": {"beta_deg": [50, 180]}}, r"\[50, 180\] must satisfy 0 <= lo < hi <= 179"),
    ({"bounds": {"beta_deg": [50, 50.0000001]}}, r"spans 1e-07°, less than 1e-06°: hold"),
    ({"bounds": {"beta_deg": [50]}}, r"a search range needs two angles \[lo, hi\], not 1"),
    ({"starts": 0}, "greater than or equal to 1"),
    ({"starts": 65}, "less than or equal to 64"),
    ({"max_evaluations_per_start": 2001}, "less than or equal to 2000"),
    ({"singularity_tolerance": 0}, "greater than or equal to 0.000000000001"),
    ({"singularity_tolerance": 5e-324}, "greater than or equal to 0.000000000001"),
    ({"singularity_tolerance": 1.5}, "less than 1"),
    ({"seed": -1}, "greater than or equal to 0"),
    ({"seed": 1.5}, "valid integer"),
]  # fmt: skip


@pytest.mark.parametrize(("inputs", "message"), OPTIMISATION_ERRORS)
def test_optimisation_rejects(inputs: dict[str, Any], message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        optimisation_spec(**inputs)


# -- costs ---------------------------------------------------------------------------


def test_conditioning_map_cost() -> None:
    maps = 3 * 121 * 41
    assert conditioning_map_cost(map_spec()) == 144 + maps + 3 * 361 + WORKSPACE_MINIMUM_COST + 1
    assert conditioning_map_cost(map_spec()) <= CONDITIONING_MAP_SYNC_COST_LIMIT
    dense = map_spec(workspace={"tilt_max_deg": 60, "samples": {"azimuth": 100, "tilt": 50,
                                                                "torsion": 90}})  # fmt: skip
    assert conditioning_map_cost(dense) <= CONDITIONING_MAP_COST_LIMIT
    denser = map_spec(workspace={"tilt_max_deg": 60, "samples": {"azimuth": 100, "tilt": 50,
                                                                 "torsion": 100}})  # fmt: skip
    assert conditioning_map_cost(denser) > CONDITIONING_MAP_COST_LIMIT


def test_design_space_cost() -> None:
    assert design_space_cost(space_spec(beta_deg=[60, 75, 90])) == 3
    limited = {"tilt_max_deg": 45, "torsion_deg": [-15, 15]}
    assert design_space_cost(space_spec(workspace=limited)) == LIMITED_WIDTH_COST
    mapped = space_spec(beta_deg=[60, 75, 90], index_map={"beta_deg": 75})
    assert design_space_cost(mapped) == 3 + 31**2 * (144 + DESIGN_OVERHEAD)
    assert design_space_cost(mapped) <= DESIGN_SPACE_SYNC_COST_LIMIT


def test_optimisation_cost_counts_starts_samples_and_budget() -> None:
    base = optimisation_cost(optimisation_spec(plots=False))
    per_start = 100 * 4 + SCREEN_PER_START  # budget x (1 + 3 variables) + the screen
    assert base == 8 * per_start * (144 + DESIGN_OVERHEAD) + 4 * 144 + WORKSPACE_MINIMUM_COST
    assert optimisation_cost(optimisation_spec(plots=False, starts=16)) > 1.9 * base
    assert optimisation_cost(optimisation_spec(plots=False, max_evaluations_per_start=200)) > (
        1.9 * base
    )
    limited = optimisation_spec(workspace={"tilt_max_deg": 45, "torsion_deg": [-15, 15]},
                                identical_platforms=True, plots=False)  # fmt: skip
    per_evaluation = 144 + DESIGN_OVERHEAD + LIMITED_WIDTH_COST
    assert optimisation_cost(limited) == (
        8 * per_start * per_evaluation + 4 * 144 + WORKSPACE_MINIMUM_COST
    )


# -- process definitions -------------------------------------------------------------


@pytest.mark.parametrize("process", PROCESSES, ids=lambda p: p.id)
def test_process_definition(process: Any) -> None:
    description = json.loads(json.dumps(process.describe()))
    assert description["inputs"]["additionalProperties"] is False
    assert f"{process.cost_limit:,}" in description["description"]
    assert description["limits"]["cost_unit"].startswith("pose evaluations")
    assert all(p.get("description") for p in description["inputs"]["properties"].values())
    assert process.examples
    for example in process.examples:
        spec = process.inputs_model.model_validate(dict(example.inputs))
        assert process.cost(spec) <= process.cost_limit


def test_sync_limits() -> None:
    assert CONDITIONING_MAP.sync_cost_limit and DESIGN_SPACE.sync_cost_limit
    assert OPTIMISATION.sync_cost_limit == 0
    for process in (CONDITIONING_MAP, DESIGN_SPACE):
        for example in process.examples:
            spec = process.inputs_model.model_validate(dict(example.inputs))
            assert process.cost(spec) <= process.sync_cost_limit


def test_registered() -> None:
    ids = default_registry().ids()
    assert {"spm-conditioning-map", "spm-design-space", "spm-optimisation"} <= set(ids)


def test_public_field_names() -> None:
    assert set(ConditioningMapSpec.model_json_schema()["properties"]) == {
        "alpha1_deg", "alpha2_deg", "beta_deg", "gamma_deg", "workspace", "branch",
        "orientations", "map_torsions_deg", "map_grid", "torsion_sweeps", "plots",
    }  # fmt: skip
    assert set(DesignSpaceSpec.model_json_schema()["properties"]) == {
        "workspace", "gamma_deg", "identical_platforms", "beta_deg", "index_map", "plots",
    }  # fmt: skip
    assert set(OptimisationSpec.model_json_schema()["properties"]) == {
        "workspace", "free", "identical_platforms", "alpha1_deg", "alpha2_deg", "beta_deg",
        "gamma_deg", "bounds", "starts", "max_evaluations_per_start", "singularity_tolerance",
        "seed", "branch", "plots",
    }  # fmt: skip
    workspace = ConditioningMapSpec.model_json_schema()["$defs"]["WorkspaceSpec"]["properties"]
    assert set(workspace) == {"tilt_max_deg", "torsion_deg", "samples"}


def test_import_does_no_heavy_work() -> None:
    code = (
        "import sys, worker.families.spherical_parallel; "
        "print(sorted(m for m in ('matplotlib', 'scipy', "
        "'worker.families.spherical_parallel.kinematics', "
        "'worker.families.spherical_parallel.jobs.conditioning_map', "
        "'worker.families.spherical_parallel.jobs.optimisation') "
        "if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
