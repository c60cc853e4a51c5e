"""Inverse kinematics of serial arms: rotation errors, damped least squares (FK of IK is
the target), limits, unreachable targets, reproducibility, and the planar 3R closed form
against the numerical solver."""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from worker.families.serial.arms import EXAMPLE_1_PLANAR, PANDA, PUMA_560, UR5, UR5_URDF
from worker.families.serial.kinematics.arm import SerialArm
from worker.families.serial.kinematics.chain import forward_kinematics
from worker.families.serial.kinematics.inverse import (
    PoseTargets,
    arm_scale,
    project_to_limits,
    seed_configurations,
    solve_damped_least_squares,
)
from worker.families.serial.kinematics.planar_3r import planar_3r_geometry, solve_planar_3r
from worker.families.serial.kinematics.rotations import rotation_angle, rotation_vector
from worker.families.serial.robot_input import RobotSpec

#: A SCARA: two revolute joints, a prismatic quill (metres) and a wrist turn.
SCARA = {
    "dh": [
        {"a": 0.4, "d": 0.3, "limits": [-150, 150]},
        {"a": 0.3, "alpha_deg": 180.0, "limits": [-140, 140]},
        {"type": "prismatic", "limits": [0.0, 0.2]},
        {"d": 0.05},
    ],
    "convention": "standard",
}
ARMS = {"UR5": UR5, "UR5 URDF": UR5_URDF, "Puma 560": PUMA_560, "Panda": PANDA,
        "SCARA": SCARA, "Example 1": EXAMPLE_1_PLANAR}  # fmt: skip


def arm_of(robot: dict[str, Any]) -> SerialArm:
    return RobotSpec.model_validate(robot).arm("m")


def limited_example_1(limits: list[tuple[float, float]]) -> dict[str, Any]:
    robot = copy.deepcopy(EXAMPLE_1_PLANAR)
    for row, limit in zip(robot["dh"], limits, strict=True):
        row["limits"] = list(limit)
    return robot


def targets_at(arm: SerialArm, tool: np.ndarray, oriented: bool) -> PoseTargets:
    t = tool.shape[0]
    return PoseTargets(
        positions=tool[:, :3, 3],
        rotations=tool[:, :3, :3],
        oriented=np.full(t, oriented),
        position_tolerance=np.full(t, 1e-6 * arm_scale(arm)),
        orientation_tolerance=np.full(t, np.radians(1e-3)),
    )


def solve(arm: SerialArm, targets: PoseTargets, seed: int = 0, seeds: int = 8) -> Any:
    rng = np.random.default_rng(seed)
    starts = seed_configurations(arm, targets.count, seeds, rng)
    return solve_damped_least_squares(arm, targets, starts, 200, restarts=rng)


def random_configurations(arm: SerialArm, count: int, seed: int) -> np.ndarray:
    unit = np.random.default_rng(seed).random((count, arm.joints))
    return arm.lower + unit * (arm.upper - arm.lower)


def test_rotation_vectors_agree_with_scipy_even_near_a_half_turn() -> None:
    rng = np.random.default_rng(3)
    vectors = rng.normal(size=(200, 3))
    vectors *= (rng.uniform(0.0, np.pi, 200) / np.linalg.norm(vectors, axis=1))[:, None]
    vectors[:5] *= np.pi / np.linalg.norm(vectors[:5], axis=1)[:, None] * (1 - 1e-12)
    vectors[5] = 0.0
    matrices = Rotation.from_rotvec(vectors).as_matrix()
    assert np.allclose(rotation_vector(matrices), vectors, atol=1e-9)
    assert np.allclose(rotation_angle(matrices), np.linalg.norm(vectors, axis=1), atol=1e-9)


@pytest.mark.parametrize("name", ["UR5", "UR5 URDF", "Puma 560", "Panda", "SCARA"])
@pytest.mark.parametrize("oriented", [True, False])
@settings(max_examples=4, deadline=None, derandomize=True)
@given(seed=st.integers(0, 2**16))
def test_ik_solutions_reproduce_their_targets(name: str, oriented: bool, seed: int) -> None:
    """Random configurations within the limits -> FK -> IK -> FK: every target reached,
    each solution within the limits and within the tolerances of its target."""
    arm = arm_of(ARMS[name])
    tool = forward_kinematics(arm, random_configurations(arm, 12, seed))
    targets = targets_at(arm, tool, oriented)
    solution = solve(arm, targets, seed)
    assert solution.reached.all()
    assert np.all((solution.q >= arm.lower) & (solution.q <= arm.upper))
    again = forward_kinematics(arm, solution.q)
    distance = np.linalg.norm(again[:, :3, 3] - tool[:, :3, 3], axis=1)
    assert np.all(distance <= targets.position_tolerance)
    assert np.allclose(distance, solution.position_residual, atol=1e-15)
    if oriented:
        angle = rotation_angle(tool[:, :3, :3] @ np.swapaxes(again[:, :3, :3], 1, 2))
        assert np.all(angle <= targets.orientation_tolerance)


def test_targets_beyond_reach_are_not_reached() -> None:
    arm = arm_of(UR5)
    directions = np.random.default_rng(0).normal(size=(6, 3))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    tool = np.tile(np.eye(4), (6, 1, 1))
    tool[:, :3, 3] = 1.5 * directions  # the UR5 reaches about 1 m
    solution = solve(arm, targets_at(arm, tool, False))
    assert not solution.reached.any()
    assert np.all(solution.position_residual > 0.3)
    assert np.all(solution.solutions == 0)


def test_solutions_respect_the_joint_limits_and_limits_can_make_a_pose_unreachable() -> None:
    """With a narrow range on joint 2, poses reached by elbow angles outside it are not
    reached; every answer, reached or not, lies within the limits."""
    free = arm_of(EXAMPLE_1_PLANAR)
    narrow = arm_of(limited_example_1([(-180, 180), (10, 60), (-180, 180)]))
    q = np.radians([[0.0, 30.0, 0.0], [0.0, 120.0, 0.0], [0.0, -90.0, 10.0], [40, 45, -20]])
    targets = targets_at(free, forward_kinematics(free, q), True)
    for arm in (free, narrow):
        solution = solve(arm, targets)
        assert np.all((solution.q >= arm.lower - 1e-15) & (solution.q <= arm.upper + 1e-15))
    assert solve(free, targets).reached.all()
    # the elbow angle of a pose with the tool angle given is ±θ2: 120 and ±90 are out
    assert solve(narrow, targets).reached.tolist() == [True, False, False, True]


def test_projection_wraps_full_turn_joints_and_clamps_the_others() -> None:
    arm = arm_of(limited_example_1([(-180, 180), (-90, 90), (-180, 180)]))
    q = np.radians([[190.0, 100.0, -200.0]])
    assert np.degrees(project_to_limits(arm, q))[0] == pytest.approx([-170.0, 90.0, 160.0])


def test_the_same_seed_gives_the_same_answer() -> None:
    arm = arm_of(PANDA)
    tool = forward_kinematics(arm, random_configurations(arm, 6, 1))
    targets = targets_at(arm, tool, True)
    first, second = solve(arm, targets, seed=7), solve(arm, targets, seed=7)
    assert np.array_equal(first.q, second.q)
    assert np.array_equal(first.reached, second.reached)
    other = solve(arm, targets, seed=8)
    assert not np.array_equal(first.q, other.q)  # a redundant arm: other seeds, other q


def test_the_planar_3r_geometry_is_recognised() -> None:
    assert planar_3r_geometry(arm_of(EXAMPLE_1_PLANAR)) is not None
    assert planar_3r_geometry(arm_of(UR5)) is None
    tilted = copy.deepcopy(EXAMPLE_1_PLANAR)
    tilted["dh"][1]["alpha_deg"] = 180.0  # a flipped axis: not this closed form
    assert planar_3r_geometry(arm_of(tilted)) is None


@pytest.mark.parametrize("oriented", [True, False])
def test_the_closed_form_agrees_with_the_numerical_solver(oriented: bool) -> None:
    """A planar 3R arm with offsets, a turned and lifted base and joint limits: random
    targets (many out of reach or of the limits) are reached by the closed form exactly
    when the numerical solver reaches them, and the closed form reproduces them."""
    robot = limited_example_1([(-90, 120), (-150, 150), (-100, 100)])
    robot["dh"][1]["theta_deg"] = 20.0
    robot["base"] = {"xyz": [1.0, 2.0, 3.0], "rpy_deg": [0.0, 0.0, 30.0]}
    arm = arm_of(robot)
    geometry = planar_3r_geometry(arm)
    assert geometry is not None
    rng = np.random.default_rng(11)
    count = 120
    tool = np.tile(np.eye(4), (count, 1, 1))
    tool[:, :2, 3] = rng.uniform(-40.0, 40.0, (count, 2))
    tool[:, 2, 3] = 3.0
    phi = rng.uniform(-np.pi, np.pi, count)
    tool[:, 0, 0], tool[:, 0, 1], tool[:, 1, 0], tool[:, 1, 1] = (
        np.cos(phi), -np.sin(phi), np.sin(phi), np.cos(phi))  # fmt: skip
    targets = targets_at(arm, tool, oriented)
    closed = solve_planar_3r(arm, geometry, targets)
    numerical = solve(arm, targets, seeds=8)
    assert 0.1 < closed.reached.mean() < 0.9
    assert closed.reached.tolist() == numerical.reached.tolist()
    reached = closed.reached
    again = forward_kinematics(arm, closed.q[reached])
    assert np.allclose(again[:, :3, 3], tool[reached, :3, 3], atol=1e-9)
    assert np.all((closed.q >= arm.lower - 1e-12) & (closed.q <= arm.upper + 1e-12))


@settings(max_examples=25, deadline=None, derandomize=True)
@given(
    links=st.tuples(*[st.floats(0.5, 20.0)] * 3),
    seed=st.integers(0, 2**16),
    oriented=st.booleans(),
)
def test_closed_form_solutions_reproduce_their_targets(
    links: tuple[float, float, float], seed: int, oriented: bool
) -> None:
    """Any planar 3R arm: random configurations within its limits -> FK -> closed form
    -> FK is the target (the tool angle too when given), within the limits."""
    robot = limited_example_1([(-150, 150), (-170, 170), (-120, 120)])
    for row, length in zip(robot["dh"], links, strict=True):
        row["a"] = length
    arm = arm_of(robot)
    geometry = planar_3r_geometry(arm)
    assert geometry is not None
    tool = forward_kinematics(arm, random_configurations(arm, 10, seed))
    targets = targets_at(arm, tool, oriented)
    solution = solve_planar_3r(arm, geometry, targets)
    if oriented:
        assert solution.reached.all()
        assert np.all(solution.orientation_residual <= targets.orientation_tolerance)
    else:  # by the 0.2° scan of the tool angle (no arc here is narrower than a step)
        assert solution.reached.all()
    assert np.all(solution.position_residual[solution.reached] <= 1e-9 * sum(links))
    assert np.all((solution.q >= arm.lower - 1e-12) & (solution.q <= arm.upper + 1e-12))
