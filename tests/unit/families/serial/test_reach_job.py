"""The ``serial-reach`` job: its worked examples, refused inputs, and agreement with the
exact planar 3R family (worker/families/planar_serial) on Patel & Sobh's Example 1 arm:
reach radii without limits, d_z > 0 with limits, feasible tool-angle arcs."""

from __future__ import annotations

import copy
import math
import re
from typing import Any

import numpy as np
import pytest

from tests.unit.families.conftest import RecordingContext
from worker.errors import InvalidInputs
from worker.families.planar_serial.kinematics import reach_radii
from worker.families.planar_serial.kinematics.limited_exact import (
    exact_limited_orientation_dexterity,
    feasible_arcs,
)
from worker.families.serial.arms import EXAMPLE_1_PLANAR, UR5
from worker.registry import default_registry
from worker.submission import validate_inputs

PROCESS = default_registry().get("serial-reach")
LIMITS_DEG = [(-120.0, 120.0), (-150.0, 150.0), (-100.0, 100.0)]


def run(inputs: dict[str, Any], plots: bool = False) -> Any:
    assert PROCESS is not None
    return PROCESS.run(validate_inputs(PROCESS, {**inputs, "plots": plots}), RecordingContext())


def problems(inputs: dict[str, Any]) -> list[tuple[str, str]]:
    assert PROCESS is not None
    with pytest.raises(InvalidInputs) as caught:
        validate_inputs(PROCESS, inputs)
    return [(e["field"], e["message"]) for e in caught.value.errors]


def planar_arm(links: tuple[float, float, float], limits: bool) -> dict[str, Any]:
    robot = copy.deepcopy(EXAMPLE_1_PLANAR)
    for row, length, limit in zip(robot["dh"], links, LIMITS_DEG, strict=True):
        row["a"] = length
        if limits:
            row["limits"] = list(limit)
    return robot


def test_the_worked_examples_run_and_say_what_they_promise() -> None:
    assert PROCESS is not None
    shares = []
    for example in PROCESS.examples:
        outcome = run(dict(example.inputs), plots=True)
        result = outcome.result
        assert [a.name for a in outcome.artifacts] == ["reach.png", "reach.svg"]
        summary = result["summary"]
        assert summary["reached"] == sum(t["reached"] for t in result["targets"])
        for target in result["targets"]:
            residual, tolerance = target["residual"], target["tolerance"]
            if target["reached"]:
                assert residual["position"] <= tolerance["position"]
                assert target["manipulability"] > 0.0
            else:
                assert target["manipulability"] is None
        shares.append(summary["reached_share"])
    assert shares == [pytest.approx(0.8), pytest.approx(5 / 6), pytest.approx(0.8)]


def test_the_ur5_example_uses_the_numerical_solver_and_the_planar_one_the_closed_form() -> None:
    assert PROCESS is not None
    ur5, planar, _ = (run(dict(e.inputs)).result for e in PROCESS.examples)
    assert ur5["solver"] == "damped least squares" and ur5["seeds"] == 8
    assert ur5["characteristic_length"] == 0.5
    assert [t["reached"] for t in ur5["targets"]] == [True, True, True, True, False]
    assert ur5["targets"][4]["residual"]["position"] > 0.9  # 2 m out, reach about 1 m
    assert ur5["targets"][3]["residual"]["orientation_deg"] is None  # position only
    assert planar["solver"] == "closed-form planar 3R"
    assert planar["arm"]["task_space"] == ["x", "y", "phi"]
    # the point (40, 0) lies 3 beyond the reach 37: the closest answer is stretched out
    assert planar["targets"][5]["residual"]["position"] == pytest.approx(3.0, abs=1e-9)


def test_a_target_beyond_a_planar_arms_reach_reports_its_closest_configuration() -> None:
    """The closed form leaves it; damped least squares finds the arm stretched toward it."""
    targets = [{"position": [0.0, -45.0]}, {"position": [-30.0, 30.0]}]
    result = run({"robot": EXAMPLE_1_PLANAR, "targets": targets}).result
    assert result["solver"] == "closed-form planar 3R"
    residuals = [t["residual"]["position"] for t in result["targets"]]
    assert residuals == pytest.approx([45.0 - 37.0, math.hypot(30, 30) - 37.0], abs=1e-6)
    assert not any(t["reached"] for t in result["targets"])


def test_the_same_seed_gives_the_same_result() -> None:
    assert PROCESS is not None
    inputs = {**dict(PROCESS.examples[0].inputs), "seed": 5}
    assert run(inputs).result == run(inputs).result


@pytest.mark.parametrize(
    ("change", "field", "message"),
    [
        ({"targets": [{"position": [0.1, 0.2]}]}, "inputs.targets[0].position",
         r"needs \[x, y, z\]"),
        ({"targets": [{"position": [0.1, 0.2, 0.3], "rpy_deg": [0, 0, 400]}]},
         "inputs.targets[0].rpy_deg", "angles must lie"),
        ({"targets": [{"position": [0.1, 0.2, 0.3], "tolerance": {"position": 0}}]},
         "inputs.targets[0].tolerance.position", "greater than 0"),
        ({"seeds": 0}, "inputs.seeds", "greater than or equal to 1"),
        ({"targets": []}, "inputs.targets", "at least one target"),
    ],
)  # fmt: skip
def test_bad_targets_are_refused_at_their_field(
    change: dict[str, Any], field: str, message: str
) -> None:
    found = problems({"robot": UR5, "targets": [{"position": [0.3, 0.1, 0.2]}], **change})
    assert [f for f, _ in found] == [field]
    assert re.search(message, found[0][1])


def test_a_planar_target_turns_about_z_only() -> None:
    body = {"robot": EXAMPLE_1_PLANAR, "targets": [{"position": [10, 5], "rpy_deg": [5, 0, 0]}]}
    ((field, message),) = problems(body)
    assert field == "inputs.targets[0].rpy_deg" and "about z only" in message


def test_the_cost_is_checked_before_queuing() -> None:
    assert PROCESS is not None
    many = {"robot": UR5, "targets": [{"position": [0.3, 0.1, 0.2]}] * 2000,
            "seeds": 64, "max_iterations": 2000}  # fmt: skip
    spec = validate_inputs(PROCESS, many)
    assert PROCESS.cost(spec) == 2000 * 64 * 2000 * 6 > PROCESS.cost_limit


def grid_points(radius: float, count: int, seed: int) -> np.ndarray:
    return np.random.default_rng(seed).uniform(-radius, radius, (count, 2))


@pytest.mark.parametrize("links", [(15.0, 14.0, 8.0), (15.0, 4.0, 3.0)])
def test_position_targets_without_limits_agree_with_the_reach_annulus(
    links: tuple[float, float, float],
) -> None:
    """Without limits a point is reachable iff d_min <= |p| <= d_max (points within 1e-3
    of either circle left out)."""
    inner, outer = reach_radii(links)
    points = grid_points(outer + 5.0, 300, 1)
    distance = np.hypot(points[:, 0], points[:, 1])
    points = points[(np.abs(distance - outer) > 1e-3) & (np.abs(distance - inner) > 1e-3)]
    distance = np.hypot(points[:, 0], points[:, 1])
    result = run({"robot": planar_arm(links, False),
                  "targets": [{"position": p.tolist()} for p in points]}).result  # fmt: skip
    expected = (distance >= inner) & (distance <= outer)
    assert 0.2 < expected.mean() < 0.9
    assert [t["reached"] for t in result["targets"]] == expected.tolist()


def test_position_targets_with_limits_agree_with_the_exact_dexterity() -> None:
    """With joint limits a point is reachable iff d_z > 0 (exact, from the 3R family);
    points with 0 < d_z < 0.003 (arcs narrower than the 0.2° scan could miss) left out."""
    links = (15.0, 14.0, 8.0)
    points = grid_points(38.0, 400, 2)
    dz = exact_limited_orientation_dexterity(links, points, np.radians(LIMITS_DEG))
    keep = (dz == 0.0) | (dz >= 0.003)
    points, dz = points[keep], dz[keep]
    result = run({"robot": planar_arm(links, True),
                  "targets": [{"position": p.tolist()} for p in points]}).result  # fmt: skip
    expected = dz > 0.0
    assert 0.2 < expected.mean() < 0.9
    assert [t["reached"] for t in result["targets"]] == expected.tolist()


@pytest.mark.parametrize("solver", ["auto", "numerical"])
def test_oriented_targets_with_limits_agree_with_the_feasible_arcs(solver: str) -> None:
    """A point with a tool angle φ is reachable within the limits iff φ lies on one of
    its feasible arcs (the 3R family's events); angles within 1e-4 rad of an arc's end
    left out."""
    links = (15.0, 14.0, 8.0)
    rng = np.random.default_rng(4)
    targets, expected = [], []
    while len(targets) < 50:
        point = rng.uniform(-30.0, 30.0, 2)
        phi = float(rng.uniform(0.0, 2.0 * math.pi))
        arcs = feasible_arcs(links, point, np.radians(LIMITS_DEG))
        turns = [phi + k * 2.0 * math.pi for k in (0, 1)]  # arcs may run past 2π
        if any(abs(t - end) < 1e-4 for t in turns for arc in arcs for end in arc):
            continue
        targets.append({"position": point.tolist(), "rpy_deg": [0, 0, math.degrees(phi)]})
        expected.append(any(a <= t <= b for t in turns for a, b in arcs))
    result = run({"robot": planar_arm(links, True), "targets": targets, "solver": solver,
                  "seeds": 16}).result  # fmt: skip
    assert result["solver"] == ("closed-form planar 3R" if solver == "auto" else
                                "damped least squares")  # fmt: skip
    assert 0.1 < np.mean(expected) < 0.9
    assert [t["reached"] for t in result["targets"]] == expected
