"""d_z on grids and at points: exact for revolute joints, sampled under joint limits.

With fully revolute joints d_z has a closed form (docs/methods/planar-serial.md); under
joint limits it is counted over sampled orientations, inverse kinematics over both elbow
branches.  The grid is evaluated by plain sampling, task points and trajectory samples
with their transitions refined by bisection to :data:`REFINE_TOL_RAD`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from worker.common.grids import WorkspaceGrid
from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.specs import GridSpec, JointLimitsDeg

__all__ = [
    "FULL_DEXTERITY_TOL",
    "REFINE_TOL_RAD",
    "OrientationSampling",
    "WorkspaceGrid",
    "grid_dexterity",
    "orientation_sampling",
    "point_dexterity",
    "workspace_grid",
]

Links = tuple[float, float, float]
FloatArray = NDArray[np.float64]

#: Bisection tolerance (rad) on the orientation transitions at task points.
REFINE_TOL_RAD = 1e-10
#: d_z within this of 1 counts as full dexterity.
FULL_DEXTERITY_TOL = 1e-12
#: Default half-width of the grid, as a multiple of the full reach l1 + l2 + l3.
DEFAULT_GRID_MARGIN = 1.05
#: Row blocks of the exact map (so that progress moves on large grids).
EXACT_ROW_BLOCKS = 10


def workspace_grid(spec: GridSpec, links: Links) -> WorkspaceGrid:
    """The requested grid, or the square ±1.05·(l1 + l2 + l3) by default."""
    if spec.bounds is not None:
        return WorkspaceGrid(spec.bounds, spec.points_per_axis)
    half = DEFAULT_GRID_MARGIN * math.fsum(links)
    return WorkspaceGrid((-half, half, -half, half), spec.points_per_axis)


@dataclass(frozen=True)
class OrientationSampling:
    """Joint limits (rad, (3, 2)) and the orientation step used under them."""

    joint_limits_rad: FloatArray
    requested_step_rad: float
    samples: int
    effective_step_rad: float

    @property
    def effective_step_deg(self) -> float:
        return math.degrees(self.effective_step_rad)


def orientation_sampling(
    joint_limits_deg: JointLimitsDeg | None, step_deg: float
) -> OrientationSampling | None:
    """The sampling for limited joints, or None when every joint turns fully."""
    if joint_limits_deg is None or all(lo <= -180.0 and hi >= 180.0 for lo, hi in joint_limits_deg):
        return None
    step_rad = math.radians(step_deg)
    samples, effective = planar_serial.orientation_samples(step_rad)
    return OrientationSampling(
        joint_limits_rad=np.radians(np.asarray(joint_limits_deg, dtype=float)),
        requested_step_rad=step_rad,
        samples=int(samples),
        effective_step_rad=float(effective),
    )


def grid_dexterity(
    links: Links,
    grid: WorkspaceGrid,
    sampling: OrientationSampling | None,
    on_progress: Callable[[int, int], None],
) -> FloatArray:
    """d_z at every node, (ny, nx); ``on_progress(done, total)`` after each chunk."""
    points = grid.points()
    if sampling is None:
        ny = points.shape[0]
        d_z = np.empty(points.shape[:2])
        edges = np.linspace(0, ny, min(EXACT_ROW_BLOCKS, ny) + 1).astype(int)
        for start, stop in itertools.pairwise(edges.tolist()):
            d_z[start:stop] = planar_serial.exact_orientation_dexterity(links, points[start:stop])
            on_progress(stop, ny)
        return d_z
    return np.asarray(
        planar_serial.limited_orientation_dexterity(
            links,
            points,
            sampling.joint_limits_rad,
            sampling.requested_step_rad,
            on_chunk=on_progress,
        ),
        dtype=float,
    )


def point_dexterity(
    links: Links, points: FloatArray, sampling: OrientationSampling | None
) -> FloatArray:
    """d_z at ``points`` (n, 2) -> (n,): exact, or sampled and bisection-refined."""
    if points.shape[0] == 0:
        return np.zeros(0)
    if sampling is None:
        return np.asarray(planar_serial.exact_orientation_dexterity(links, points), dtype=float)
    return np.asarray(
        planar_serial.limited_orientation_dexterity(
            links,
            points,
            sampling.joint_limits_rad,
            sampling.requested_step_rad,
            refine_tol=REFINE_TOL_RAD,
        ),
        dtype=float,
    )


def point_method(sampling: OrientationSampling | None) -> str:
    """How task points are evaluated, as reported in ``discretisation``."""
    if sampling is None:
        return "exact-closed-form"
    return f"bisection-refined (tol {REFINE_TOL_RAD:g} rad)"
