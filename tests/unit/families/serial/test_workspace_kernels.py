"""The workspace-map kernels: samplers, grids and bins, the fast kinematics against
:mod:`chain`/:mod:`indices`, and the accumulated map against a per-sample loop."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from worker.families.serial.arms import EXAMPLE_1_PLANAR, PANDA, PUMA_560, UR5, UR5_URDF
from worker.families.serial.kinematics.arm import SerialArm
from worker.families.serial.kinematics.chain import forward_kinematics, jacobian
from worker.families.serial.kinematics.indices import (
    inverse_condition,
    manipulability,
    task_jacobian,
)
from worker.families.serial.kinematics.joint_samples import (
    grid_points_per_joint,
    joint_sample_chunks,
    sample_count,
)
from worker.families.serial.kinematics.map_kinematics import gram_indices, map_poses, z_axis_form
from worker.families.serial.kinematics.voxel_grid import (
    sphere_bin_layout,
    tool_angle_bins,
    tool_axis_bins,
    voxel_grid,
)
from worker.families.serial.kinematics.workspace_map import (
    MapSettings,
    checkpoints,
    relative_changes,
    workspace_map,
)
from worker.families.serial.robot_input import RobotSpec

ARMS = {"ur5": UR5, "ur5_urdf": UR5_URDF, "puma": PUMA_560, "panda": PANDA,
        "example1": EXAMPLE_1_PLANAR}  # fmt: skip


def make_arm(robot: dict[str, Any]) -> SerialArm:
    return RobotSpec.model_validate(robot).arm("m")


@pytest.mark.parametrize("name", sorted(ARMS))
@pytest.mark.parametrize("scale", [None, 0.4])
def test_fast_kinematics_match_the_chain_and_indices(name: str, scale: float | None) -> None:
    arm = make_arm(ARMS[name])
    q = np.random.default_rng(1).uniform(arm.lower, arm.upper, (300, arm.joints))
    poses = map_poses(z_axis_form(arm), q)
    tool, jac = forward_kinematics(arm, q), jacobian(arm, q)
    np.testing.assert_allclose(poses.rotation, tool[:, :3, :3], atol=1e-12)
    np.testing.assert_allclose(poses.position, tool[:, :3, 3], atol=1e-12)
    np.testing.assert_allclose(poses.jacobian, jac, atol=1e-12)
    measure, kappa = gram_indices(poses.jacobian, arm.planar, scale)
    task = task_jacobian(jac, arm.planar)
    np.testing.assert_allclose(measure, manipulability(task), rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(kappa, inverse_condition(task, scale), atol=1e-7)


def test_a_general_axis_is_turned_into_z() -> None:
    """A URDF-like arm with axes along x, -z and a slanted one, a prismatic among them."""
    axes = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 0.6, 0.8], [0.0, 1.0, 0.0]])
    fixed = np.tile(np.eye(4), (5, 1, 1))
    fixed[1:, :3, 3] = [[0.1, 0.2, 0.3], [0.3, 0.0, 0.1], [0.0, 0.2, 0.0], [0.05, 0.0, 0.1]]
    arm = SerialArm(fixed=fixed, axes=axes, prismatic=np.array([False, False, True, False]),
                    lower=-np.ones(4), upper=np.ones(4), names=("a", "b", "c", "d"))  # fmt: skip
    q = np.random.default_rng(2).uniform(-1.0, 1.0, (50, 4))
    poses = map_poses(z_axis_form(arm), q)
    np.testing.assert_allclose(poses.position, forward_kinematics(arm, q)[:, :3, 3], atol=1e-12)
    np.testing.assert_allclose(poses.jacobian, jacobian(arm, q), atol=1e-12)


@pytest.mark.parametrize("sampler", ["sobol", "uniform", "grid"])
def test_samples_lie_within_the_limits_and_chunking_does_not_matter(sampler: Any) -> None:
    lower, upper = np.array([-1.0, 0.0, 2.0]), np.array([1.0, 0.5, 3.0])
    total = sample_count(1000, 3, sampler)
    whole = np.concatenate(list(joint_sample_chunks(lower, upper, sampler, 7, [total])))
    parts = np.concatenate(list(joint_sample_chunks(lower, upper, sampler, 7, [10, 300, total])))
    assert whole.shape == (total, 3)
    np.testing.assert_array_equal(whole, parts)
    assert np.all((whole >= lower) & (whole < upper))
    if sampler == "grid":
        m = grid_points_per_joint(1000, 3)
        assert m == 10 and len({tuple(row) for row in whole.tolist()}) == m**3


@given(st.integers(1, 720))
@settings(max_examples=20, deadline=None)
def test_sphere_bins_are_equal_area_and_cover_every_index(bins: int) -> None:
    bands, cells = sphere_bin_layout(bins)
    assert bands * cells == bins
    # uniform directions on the sphere (z uniform, longitude uniform) fill bins evenly
    rng = np.random.default_rng(bins)
    n = 1000 * bins
    z, lon = rng.uniform(-1, 1, n), rng.uniform(-math.pi, math.pi, n)
    axis = np.stack([np.sqrt(1 - z**2) * np.cos(lon), np.sqrt(1 - z**2) * np.sin(lon), z], -1)
    counts = np.bincount(tool_axis_bins(axis, bins), minlength=bins)
    assert counts.shape == (bins,)
    assert np.all(np.abs(counts / 1000.0 - 1.0) < 0.2)


def test_tool_angle_bins_start_at_minus_180() -> None:
    phi = np.radians([-180.0, -170.0001, -169.9999, 179.9999, 180.0])
    assert tool_angle_bins(phi, 36).tolist() == [0, 0, 1, 35, 0]


def test_the_grid_is_node_centred_on_multiples_of_the_voxel_size() -> None:
    arm = make_arm(EXAMPLE_1_PLANAR)
    grid = voxel_grid(arm, 2.0, None, True)
    assert grid.axes[0][0] == -36.0 and grid.axes[0][-1] == 36.0 and 0.0 in grid.axes[1]
    points = np.array([[0.99, -0.99], [1.01, 0.0], [-36.9, 0.0], [37.1, 0.0]])
    flat = grid.flat_index(points)
    i0 = int(np.argmin(np.abs(grid.axes[0])))
    assert flat[0] == i0 * grid.shape[1] + i0
    assert flat[1] == (i0 + 1) * grid.shape[1] + i0
    assert flat[2] == i0 and flat[3] == -1
    bounded = voxel_grid(make_arm(UR5), 0.05, ((-0.2, 0.2), (0.0, 0.5), (-0.1, 0.1)), False)
    assert bounded.shape == (9, 11, 5)


def test_relative_changes_and_checkpoints() -> None:
    assert checkpoints(1000) == (125, 250, 500, 1000)
    assert relative_changes((1.0, 2.0, 2.0, 0.0)) == [0.5, 0.0, 1.0]
    assert relative_changes((0.0, 0.0)) == [0.0]


def reference_map(arm: SerialArm, q: np.ndarray, grid: Any, bins: int) -> dict[str, Any]:
    """The map by a per-sample loop over chain.py and indices.py."""
    planar = arm.planar
    reached: dict[int, set[int]] = {}
    values: dict[int, list[tuple[float, float]]] = {}
    for sample in q:
        tool = forward_kinematics(arm, sample)
        task = task_jacobian(jacobian(arm, sample), planar)
        point = tool[:2, 3] if planar else tool[:3, 3]
        k = [round((point[d] - grid.axes[d][0]) / grid.size) for d in range(point.shape[0])]
        if any(not 0 <= k[d] < grid.shape[d] for d in range(len(k))):
            continue
        flat = int(np.ravel_multi_index(tuple(k), grid.shape))
        if planar:
            phi = math.atan2(tool[1, 0], tool[0, 0])
            b = math.floor((phi + math.pi) / (2 * math.pi) * bins) % bins
        else:
            bands, cells = sphere_bin_layout(bins)
            z = tool[:3, 2]
            band = min(bands - 1, max(0, math.floor((z[2] + 1) / 2 * bands)))
            lon = math.atan2(z[1], z[0])
            b = band * cells + math.floor((lon + math.pi) / (2 * math.pi) * cells) % cells
        reached.setdefault(flat, set()).add(b)
        indices = (float(manipulability(task)), float(inverse_condition(task)))
        values.setdefault(flat, []).append(indices)
    return {"reached": reached, "values": values}


@pytest.mark.parametrize("name", ["ur5", "example1"])
def test_the_map_matches_a_per_sample_loop(name: str) -> None:
    arm = make_arm(ARMS[name])
    planar = arm.planar
    grid = voxel_grid(arm, 3.0 if planar else 0.15, None, planar)
    result = workspace_map(arm, grid, MapSettings(1500, "uniform", 3, 36), chunk=200)
    q = np.concatenate(list(joint_sample_chunks(arm.lower, arm.upper, "uniform", 3, [1500])))
    ref = reference_map(arm, q, grid, 36)
    flat_reached = result.reached.ravel()
    assert set(np.flatnonzero(flat_reached).tolist()) == set(ref["reached"])
    index = result.reachability_index.ravel()
    for voxel, bins_hit in ref["reached"].items():
        assert index[voxel] == pytest.approx(len(bins_hit) / 36)
        w, k = np.array(ref["values"][voxel]).T
        stats = {key: v.ravel()[voxel] for key, v in result.statistics.items()}
        assert result.samples.ravel()[voxel] == w.size
        assert stats["manipulability_min"] == pytest.approx(w.min(), rel=1e-9, abs=1e-8)
        assert stats["manipulability_max"] == pytest.approx(w.max(), rel=1e-9, abs=1e-8)
        assert stats["manipulability_mean"] == pytest.approx(w.mean(), rel=1e-9, abs=1e-8)
        assert stats["inverse_condition_min"] == pytest.approx(k.min(), abs=1e-7)
        assert stats["inverse_condition_mean"] == pytest.approx(k.mean(), abs=1e-7)
        assert stats["inverse_condition_max"] == pytest.approx(k.max(), abs=1e-7)
    assert np.all(np.isnan(result.statistics["manipulability_mean"][~result.reached]))
