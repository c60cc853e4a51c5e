"""Patel & Sobh's Example 1 arm through the workspace map (planar, φ bins) against the
exact d_z of the planar 3R family, with and without joint limits
(docs/methods/serial.md, "Agreement with the exact d_z").

At an interior pixel (its 3 x 3 neighbourhood all inside the reach) the index must be
within ``(e + 1) / K + s`` of d_z at the node: e the number of feasible-arc ends at the
node, K the bins, and s the share of the circle that the pixel's cell adds to the
node's feasible arcs (the union of the feasible tool angles over a 3 x 3 probe lattice
of the cell, on a 1° grid, minus those at the node). The issue's bound ``(e + 1) / K``
is s = 0; it holds wherever the cell adds less than the slack it leaves.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from worker.families.planar_serial.kinematics import exact_orientation_dexterity
from worker.families.planar_serial.kinematics.inputs import checked_joint_limits, checked_links
from worker.families.planar_serial.kinematics.joint_limits import feasible_orientations
from worker.families.planar_serial.kinematics.limited_exact import (
    exact_limited_orientation_dexterity,
    feasible_arcs,
)
from worker.families.serial.arms import EXAMPLE_1_PLANAR
from worker.families.serial.kinematics.voxel_grid import voxel_grid
from worker.families.serial.kinematics.workspace_map import MapSettings, workspace_map
from worker.families.serial.robot_input import RobotSpec

LINKS = (15.0, 14.0, 8.0)
PIXEL = 2.0
BINS = 36
SAMPLES = 300_000
PHI_STEP_DEG = 1.0


def ends_at(point: np.ndarray, limits: np.ndarray) -> int:
    arcs = feasible_arcs(LINKS, point, limits)
    full = len(arcs) == 1 and arcs[0][1] - arcs[0][0] >= 2 * math.pi - 1e-12
    return 0 if full else 2 * len(arcs)


def cell_excess(nodes: np.ndarray, limits: np.ndarray) -> np.ndarray:
    """(pixels,) the share of the circle of tool angles feasible somewhere on the 3 x 3
    probe lattice of each pixel's cell but not at its node (a 1° grid of angles)."""
    offsets = np.array([(a, b) for a in (-0.5, 0.0, 0.5) for b in (-0.5, 0.0, 0.5)]) * PIXEL
    phi = np.radians(np.arange(-180.0, 180.0, PHI_STEP_DEG))
    probes = nodes[:, None, None, :] + offsets[None, :, None, :]  # (p, 9, 1, 2)
    shape = (nodes.shape[0], offsets.shape[0], phi.shape[0])
    px = np.broadcast_to(probes[..., 0], shape).ravel()
    py = np.broadcast_to(probes[..., 1], shape).ravel()
    angles = np.broadcast_to(phi, shape).ravel()
    links, bounds = checked_links(LINKS, "t"), checked_joint_limits(limits, "t")
    ok = feasible_orientations(links, bounds, px, py, angles).reshape(shape)
    at_node = ok[:, 4]
    union = ok.any(axis=1)
    excess: np.ndarray = (union & ~at_node).mean(axis=1)
    return excess


@pytest.mark.parametrize("limit_deg", [None, 120.0])
def test_example_1_map_agrees_with_the_exact_dexterity(limit_deg: float | None) -> None:
    robot = EXAMPLE_1_PLANAR
    limits = np.radians([[-180.0, 180.0]] * 3)
    if limit_deg is not None:
        robot = {**robot, "dh": [{**r, "limits": [-limit_deg, limit_deg]} for r in robot["dh"]]}
        limits = np.radians([[-limit_deg, limit_deg]] * 3)
    arm = RobotSpec.model_validate(robot).arm("units")
    grid = voxel_grid(arm, PIXEL, None, True)
    result = workspace_map(arm, grid, MapSettings(SAMPLES, "sobol", 0, BINS))
    nodes = np.stack(np.meshgrid(*grid.axes, indexing="ij"), axis=-1)
    if limit_deg is None:
        d_z = exact_orientation_dexterity(LINKS, nodes)
    else:
        d_z = exact_limited_orientation_dexterity(LINKS, nodes, limits)
    inside = d_z > 0.0
    interior = inside.copy()
    interior[[0, -1], :] = interior[:, [0, -1]] = False
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            interior &= np.roll(inside, (dx, dy), axis=(0, 1))
    at = np.nonzero(interior)
    assert at[0].size > 500
    index, exact = result.reachability_index[at], d_z[at]
    ends = np.array([ends_at(nodes[i, j], limits) for i, j in zip(*at, strict=True)])
    excess = cell_excess(nodes[at], limits)
    error = np.abs(index - exact)
    assert np.all(error <= (ends + 1) / BINS + excess + 1e-9)
    # the bound, (ends + 1) / K, wherever the cell adds less than one bin's slack
    # beyond the node's partial end bins
    calm = excess <= 0.5 / BINS
    assert np.all(error[calm] <= (ends[calm] + 1) / BINS + 1e-9)
    # sampling misses little: never a whole bin below the node's arcs
    assert np.all(exact - index <= (ends + 1) / BINS)
