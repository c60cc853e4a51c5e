"""The planar3r-design job: the paper's examples under their joint limits, the optimum
beating the paper's rule and a brute-force grid, checked against the independent
sampler; determinism, costs, the convergence record and the files.  The multi-start
search itself (agreement, the tool length held): test_design_search.py."""

from __future__ import annotations

import io
import itertools
import json
import math
from typing import Any

import numpy as np
import pytest
from pydantic import ValidationError

from tests.unit.families.conftest import RecordingContext, unrendered_artifacts
from worker.contract import JobOutcome
from worker.families.planar_serial import DESIGN
from worker.families.planar_serial.costs import (
    COST_LIMIT,
    design_calls,
    design_cost,
    design_evaluations,
)
from worker.families.planar_serial.design_spec import DesignSpec
from worker.families.planar_serial.examples import DESIGN_EXAMPLES, EXAMPLE_2_TASK_POINTS
from worker.families.planar_serial.jobs import optimum_artifacts
from worker.families.planar_serial.jobs.optimal_links import run_design
from worker.families.planar_serial.jobs.trajectories import trajectory_samples
from worker.families.planar_serial.kinematics import (
    exact_orientation_dexterity,
    limited_orientation_dexterity,
)
from worker.families.planar_serial.kinematics.limited_exact import (
    exact_limited_orientation_dexterity,
)

PAPER_LIMITS = np.radians([[-150.0, 150.0], [-150.0, 150.0], [-175.0, 175.0]])
EX1_TASK = [[14, 14], [12, 8], [10, -3], [9, -7], [8, -8]]
RESULT_KEYS = {
    "objective", "dz_target", "joint_limits_deg", "method", "optimum", "paper_rule",
    "improvement", "convergence", "search_space", "evaluation_points", "length_unit",
}  # fmt: skip


def run_example(index: int) -> tuple[JobOutcome, RecordingContext]:
    ctx = RecordingContext()
    spec = DesignSpec.model_validate(dict(DESIGN_EXAMPLES[index].inputs))
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(optimum_artifacts, "figure_artifacts", unrendered_artifacts)
        return DESIGN.run(spec, ctx), ctx


@pytest.fixture(scope="module")
def examples() -> list[tuple[JobOutcome, RecordingContext]]:
    return [run_example(index) for index in range(len(DESIGN_EXAMPLES))]


def independent_dz(links: list[float], base: list[float], points: Any) -> np.ndarray:
    """d_z by the sampler refined by bisection (not the events), 0.25 deg, 1e-12 rad."""
    relative = np.asarray(points, dtype=float) - np.asarray(base)
    return np.asarray(
        limited_orientation_dexterity(
            links, relative, PAPER_LIMITS, math.radians(0.25), refine_tol=1e-12
        )
    )


# -- the worked examples --------------------------------------------------------------
# The tool length is held at the paper rule's l3 for the budget by default (8 for 37
# units in Example 1, 15 for 60 in Example 2), so the optima are arms with that tool,
# not the point tools (l3 = 0.04 and 0.06) the search found when l3 was free.


def best_on_a_grid(
    points: Any, l3: float, total_max: float, lo: float, per_axis: int
) -> tuple[float, tuple[float, float]]:
    """The best smallest d_z of (l1, l2, l3) over a grid of l1, l2 in [lo, total_max - l3]
    within the budget: an independent brute force for the search."""
    values = np.linspace(lo, total_max - l3, per_axis)
    pairs = np.array([(a, b) for a in values for b in values if a + b + l3 <= total_max])
    links = np.column_stack([pairs, np.full(len(pairs), l3)])
    worst = np.array([
        exact_limited_orientation_dexterity(row, points, PAPER_LIMITS).min() for row in links
    ])  # fmt: skip
    best = int(np.argmax(worst))
    return float(worst[best]), (float(pairs[best, 0]), float(pairs[best, 1]))


def test_example_1_holds_the_rule_tool_and_beats_the_rule(examples) -> None:
    result = examples[0][0].result
    optimum, rule = result["optimum"], result["paper_rule"]
    assert rule["links"] == [15.0, 14.0, 8.0]
    assert rule["min_dz"] == pytest.approx(0.7269, abs=1e-4)  # E, and the trajectory near it
    assert min(e["d_z"] for e in rule["task_points"]) == pytest.approx(0.7273, abs=6e-5)
    # l3 held at the rule's l3 for 37 units: d_max + 2 l3 + 1 = 20 + 16 + 1
    assert result["search_space"]["l3_held"] == 8.0 and optimum["links"][2] == 8.0
    assert optimum["links"][:2] == pytest.approx([13.1813, 13.1813], abs=1e-3)
    assert optimum["min_dz"] == pytest.approx(0.77209, abs=1e-5)
    assert optimum["total_length"] <= 37.0 + 1e-9
    assert result["improvement"]["min_dz"] == pytest.approx(optimum["min_dz"] - rule["min_dz"])
    assert result["convergence"]["success"] is True


def test_example_1_optimum_beats_a_brute_force_grid(examples) -> None:
    # the task points and 200 samples of the cubic, every (l1, l2) on a 0.5-unit grid
    optimum = examples[0][0].result["optimum"]
    spec = DesignSpec.model_validate(dict(DESIGN_EXAMPLES[0].inputs))
    samples = trajectory_samples(spec.trajectory)
    points = np.concatenate([np.asarray(EX1_TASK, dtype=float), samples])
    grid_best, _ = best_on_a_grid(points, 8.0, 37.0, 0.5, 58)
    assert grid_best <= optimum["min_dz"] + 1e-9
    assert grid_best > optimum["min_dz"] - 0.01  # and the grid comes close


def test_example_1_with_the_tool_designed(examples) -> None:
    result = examples[1][0].result
    optimum = result["optimum"]
    assert result["search_space"]["l3_held"] is None
    assert result["search_space"]["free_variables"] == 3
    assert optimum["min_dz"] == pytest.approx(1.0, abs=1e-9)
    # the shortest fully dexterous arm ends in the shortest tool allowed
    assert optimum["links"][2] == pytest.approx(1.0, abs=1e-3)
    assert optimum["total_length"] == pytest.approx(21.834, abs=1e-2)
    assert result["convergence"]["success"] is True


def test_example_1_with_a_free_base(examples) -> None:
    result = examples[2][0].result
    optimum = result["optimum"]
    assert optimum["base"] != [0.0, 0.0]
    bx, by = optimum["base"]
    assert -5 <= bx <= 5 and -5 <= by <= 5
    assert optimum["links"][2] == 8.0 and optimum["total_length"] <= 37.0 + 1e-9
    assert optimum["min_dz"] == pytest.approx(1.0, abs=1e-9)
    assert result["search_space"]["free_variables"] == 4


def test_example_2_holds_the_rule_tool_and_beats_the_rule(examples) -> None:
    result = examples[3][0].result
    rule, optimum = result["paper_rule"], result["optimum"]
    assert rule["links"] == [23.0, 22.0, 15.0]
    assert rule["min_dz"] == pytest.approx(0.7766, abs=6e-5)  # at B
    assert optimum["links"][2] == 15.0  # (60 - 29 - 1) / 2
    assert optimum["min_dz"] == pytest.approx(0.79425, abs=1e-5)
    grid_best, (l1, l2) = best_on_a_grid(
        np.asarray(EXAMPLE_2_TASK_POINTS, dtype=float), 15.0, 60.0, 1.0, 89
    )
    assert grid_best <= optimum["min_dz"] + 1e-9
    assert optimum["links"][:2] == pytest.approx([l1, l2], abs=1.0)
    assert optimum["total_length"] <= 60.0 + 1e-9
    assert result["evaluation_points"] == {"task_points": 7, "trajectory_samples": 0}


def test_min_length_meets_the_target_with_a_shorter_arm(examples) -> None:
    result = examples[4][0].result
    optimum, rule = result["optimum"], result["paper_rule"]
    assert optimum["meets_target"] is True and rule["meets_target"] is False
    assert all(e["d_z"] >= 1.0 - 1e-12 for e in optimum["task_points"])
    assert optimum["links"][2] == 1.0
    assert optimum["total_length"] == pytest.approx(21.834, abs=1e-2)
    assert result["improvement"]["total_length"] == pytest.approx(37.0 - optimum["total_length"])
    assert result["convergence"]["success"] is True


@pytest.mark.parametrize("index", range(len(DESIGN_EXAMPLES)))
def test_reported_dz_agrees_with_the_independent_sampler(examples, index: int) -> None:
    # The optimum often sits on the edge of full dexterity (ties go to the shorter arm),
    # so the check is at the reported links, to the bisection's precision.
    result = examples[index][0].result
    for name in ("optimum", "paper_rule"):
        design = result[name]
        points = [[e["x"], e["y"]] for e in design["task_points"]]
        reported = [e["d_z"] for e in design["task_points"]]
        np.testing.assert_allclose(
            independent_dz(design["links"], design["base"], points), reported, atol=1e-8
        )


@pytest.mark.parametrize("index", range(len(DESIGN_EXAMPLES)))
def test_result_document(examples, index: int) -> None:
    outcome, ctx = examples[index]
    result = outcome.result
    assert set(result) == RESULT_KEYS
    json.dumps(result, allow_nan=False)
    assert result["method"] == "exact-events"
    convergence = result["convergence"]
    history = convergence["best_per_generation"]
    assert len(history) == convergence["generations"] == 100
    scores = [entry["score"] for entry in history]
    assert all(b <= a + 1e-15 for a, b in itertools.pairwise(scores))
    spec = DesignSpec.model_validate(dict(DESIGN_EXAMPLES[index].inputs))
    assert convergence["evaluations"] <= design_evaluations(spec)
    assert convergence["global_search"]["population"] == 15 * spec.free_variables
    starts = convergence["starts"]
    assert [s["start"] for s in starts] == list(range(8))
    assert len({s["seed"] for s in starts}) == 8
    kept = starts[convergence["kept_start"]]
    assert kept["score"] == min(s["score"] for s in starts)
    assert kept["links"] == result["optimum"]["links"]
    assert sum(s["evaluations"] for s in starts) == convergence["evaluations"]
    assert convergence["agreeing_starts"] == sum(s["agrees_with_best"] for s in starts) >= 2
    assert ctx.percents == sorted(ctx.percents) and ctx.percents[-1] == 100.0
    assert sum(1 for _, message in ctx.reports if message == "search") >= 10


# -- determinism, inputs, costs -----------------------------------------------------------


def quick(ctx: RecordingContext, **inputs: Any) -> JobOutcome:
    spec = DesignSpec.model_validate(
        {"task_points": EX1_TASK, "total_length_max": 37, "max_generations": 8, "plots": False,
         **inputs}
    )  # fmt: skip
    return run_design(spec, ctx)


def test_same_seed_same_result(ctx: RecordingContext) -> None:
    limits = [[-150, 150], [-150, 150], [-175, 175]]
    first = quick(ctx, joint_limits_deg=limits, seed=7).result
    again = quick(ctx, joint_limits_deg=limits, seed=7).result
    assert first == again
    other = quick(ctx, joint_limits_deg=limits, seed=8).result
    assert other["convergence"]["seed"] == 8


def test_without_joint_limits_the_closed_form_is_used(ctx: RecordingContext) -> None:
    result = quick(ctx).result
    assert result["method"] == "exact-closed-form" and result["joint_limits_deg"] is None
    optimum = result["optimum"]
    points = np.asarray(EX1_TASK, dtype=float) - np.asarray(optimum["base"])
    np.testing.assert_allclose(
        exact_orientation_dexterity(optimum["links"], points),
        [e["d_z"] for e in optimum["task_points"]],
    )


def test_no_paper_rule_when_no_l3_fits(ctx: RecordingContext) -> None:
    # Example 1's task points span 10.4..19.8 from the base: d_max + 2 l3 + 1 <= 20 needs
    # l3 <= 0 (without paper_l3); the design's tool is then given
    outcome = quick(ctx, total_length_max=20, l3=2.0, joint_limits_deg=[[-150, 150]] * 3)
    assert outcome.result["paper_rule"] is None and outcome.result["improvement"] is None
    assert any("paper's rule is not reported" in note for note in outcome.notes)
    assert outcome.result["optimum"]["links"][2] == 2.0


def test_unreachable_target_is_reported(ctx: RecordingContext) -> None:
    outcome = quick(ctx, objective="min_length", dz_target=1.0, total_length_max=8, l3=1,
                    joint_limits_deg=[[-150, 150]] * 3)  # fmt: skip
    convergence = outcome.result["convergence"]
    assert outcome.result["optimum"]["meets_target"] is False
    assert convergence["success"] is False
    assert "no design within the bounds keeps d_z >= 1" in convergence["message"]


@pytest.mark.usefixtures("fast_figures")
def test_files_describe_themselves(ctx: RecordingContext) -> None:
    outcome = quick(ctx, joint_limits_deg=[[-150, 150]] * 3, plots=True,
                    trajectory={"points": [[14, 14], [8, -8]], "samples": 20},
                    grid={"points_per_axis": 21})  # fmt: skip
    files = {a.name: a for a in outcome.artifacts}
    assert set(files) == {"design_maps.png", "design_maps.svg", "convergence.png",
                          "convergence.svg", "design_maps.npz", "convergence.csv"}  # fmt: skip
    with np.load(io.BytesIO(files["design_maps.npz"].data)) as npz:
        units = json.loads(str(npz["units"]))
        assert units["d_z_optimum"] == "-" and units["x"] == "units"
        assert npz["d_z_optimum"].shape == (21, 21)
        assert npz["trajectory_samples"].shape == (20, 2)
        assert json.loads(str(npz["metadata"]))["process"] == "planar3r-design"
        links, base = npz["links_optimum"], npz["base_optimum"]
        relative = np.stack(np.meshgrid(npz["x"], npz["y"]), axis=-1) - base
        expected = exact_limited_orientation_dexterity(
            links, relative, np.radians([[-150, 150]] * 3)
        )
        np.testing.assert_allclose(npz["d_z_optimum"], expected)
    lines = files["convergence.csv"].data.decode().splitlines()
    assert lines[0] == "start [-],generation [-],min_dz [-],total_length [units],score [-]"
    assert len(lines) == 1 + 8 * 8  # every start's 8 generations
    assert [line.split(",")[0] for line in lines[1::8]] == [str(i) for i in range(8)]


@pytest.mark.parametrize(
    ("inputs", "field"),
    [
        ({"task_points": None}, None),
        ({"link_bounds": [[1, 2], [3, 1], [1, 2]]}, "link_bounds"),
        ({"link_bounds": [[20, 37], [10, 37], [8, 37]]}, "link_bounds"),
        ({"base_box": [1, 1, 0, 2]}, "base_box"),
        ({"dz_target": 0}, "dz_target"),
        ({"max_generations": 0}, "max_generations"),
        ({"objective": "max_mean"}, "objective"),
        ({"starts": 0}, "starts"),
        ({"starts": 33}, "starts"),
        ({"l3": 36.99}, "l3"),  # no room left for l1 and l2
        ({"l3": 1e-6}, "l3"),  # the links would span more than 1e6
        ({"total_length_max": 20}, "total_length_max"),  # the rule leaves no l3 > 0
        ({"link_bounds": [[5, 5], [5, 5], [3, 3]]}, "link_bounds"),  # nothing to design
    ],
)
def test_bad_inputs_are_refused(inputs: dict[str, Any], field: str | None) -> None:
    body = {"task_points": EX1_TASK, "total_length_max": 37, **inputs}
    with pytest.raises(ValidationError) as error:
        DesignSpec.model_validate(body)
    if field is not None:
        assert field in {str(e["loc"][0]) for e in error.value.errors()}


def test_cost_counts_designs_points_and_sub_arcs() -> None:
    spec = DesignSpec.model_validate(dict(DESIGN_EXAMPLES[0].inputs))
    assert spec.free_variables == 2  # l3 held
    evaluations = 8 * (15 * 2 * 101 + 200 * 2 + 100)
    calls = 8 * (101 + 200 * 2 + 100)
    assert design_evaluations(spec) == evaluations
    assert design_calls(spec) == calls
    # 5 task points, 200 trajectory samples, 17 sub-arcs; 3400 units per call
    assert design_cost(spec) == evaluations * 205 * 17 + calls * 3400 + 2 * 201**2 * 17
    assert design_cost(spec) < COST_LIMIT
    body = {**dict(DESIGN_EXAMPLES[0].inputs), "max_generations": 1000, "population_size": 100}
    body["trajectory"] = {**body["trajectory"], "samples": 10_000}
    assert design_cost(DesignSpec.model_validate(body)) > COST_LIMIT
