"""d_z on grids and at points: exact for revolute joints, exact or sampled under limits.

With fully revolute joints d_z has a closed form (docs/methods/planar-serial.md).  Under
joint limits the default ``exact-events`` method sums the feasible arcs between the
closed-form events (:mod:`..kinematics.limited_exact`); ``orientation-sampling`` counts
sampled orientations (inverse kinematics over both elbow branches), the grid by plain
sampling, task points and trajectory samples with their transitions refined by
bisection to :data:`REFINE_TOL_RAD`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from worker.common.grids import WorkspaceGrid
from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.kinematics.limited_exact import (
    event_count,
    exact_limited_orientation_dexterity,
)
from worker.families.planar_serial.kinematics.study_kernel import (
    FULL_DEXTERITY_TOL,
    closed_form_dexterity,
    designs_point_dexterity,
)
from worker.families.planar_serial.specs import GridSpec, JointLimitsDeg

__all__ = [
    "FULL_DEXTERITY_TOL",
    "RADIAL_ANGLE_DEG",
    "RADIAL_SAMPLES",
    "REFINE_TOL_RAD",
    "LimitedJoints",
    "LimitedMethod",
    "WorkspaceGrid",
    "grid_dexterity",
    "limited_joints",
    "map_method",
    "orientations",
    "point_dexterity",
    "point_method",
    "radial_reach",
    "workspace_grid",
]

Links = tuple[float, float, float]
FloatArray = NDArray[np.float64]

#: Bisection tolerance (rad) on the orientation transitions at task points.
REFINE_TOL_RAD = 1e-10
#: Default half-width of the grid, as a multiple of the full reach l1 + l2 + l3.
DEFAULT_GRID_MARGIN = 1.05
#: Distances sampled along the radial section (the paper's Fig 7).
RADIAL_SAMPLES = 2001
#: Angle (deg) of the radial section's ray; d_z depends on it only under joint limits.
RADIAL_ANGLE_DEG = 0.0
#: Row blocks of the exact map (so that progress moves on large grids).
EXACT_ROW_BLOCKS = 10


def workspace_grid(spec: GridSpec, links: Links) -> WorkspaceGrid:
    """The requested grid, or the square ±1.05·(l1 + l2 + l3) by default."""
    if spec.bounds is not None:
        return WorkspaceGrid(spec.bounds, spec.points_per_axis)
    half = DEFAULT_GRID_MARGIN * math.fsum(links)
    return WorkspaceGrid((-half, half, -half, half), spec.points_per_axis)


def radial_reach(links: Links) -> float:
    """How far the radial section runs: 1.05 (l1 + l2 + l3), like the default grid."""
    return DEFAULT_GRID_MARGIN * math.fsum(links)


LimitedMethod = Literal["exact-events", "orientation-sampling"]


@dataclass(frozen=True)
class LimitedJoints:
    """Joint limits (rad, (3, 2)), the method under them and the orientation sampling.

    The sampling (requested and effective step, sample count) drives only the
    ``orientation-sampling`` method; ``exact-events`` reports it unused.
    """

    joint_limits_rad: FloatArray
    method: LimitedMethod
    requested_step_rad: float
    samples: int
    effective_step_rad: float

    @property
    def sampled(self) -> bool:
        return self.method == "orientation-sampling"

    @property
    def effective_step_deg(self) -> float:
        return math.degrees(self.effective_step_rad)

    @property
    def events_per_point(self) -> int:
        """Closed-form events per point (two per condition) under these limits."""
        return event_count(self.joint_limits_rad)

    @property
    def evaluations_per_point(self) -> int:
        """Orientations tested per point: samples, or one per sub-arc between events."""
        return self.samples if self.sampled else self.events_per_point + 1

    def describe(self) -> dict[str, object]:
        """The ``discretisation`` entries of the orientations under joint limits."""
        if self.sampled:
            return {
                "orientation_step_deg": self.effective_step_deg,
                "orientation_samples": self.samples,
                "elbow_branches": 2,
            }
        return {
            "orientation_step_deg": None,
            "orientation_samples": None,
            "elbow_branches": 2,
            "events_per_point": self.events_per_point,
            "unused_inputs": ["orientation_step_deg"],
        }


def limited_joints(
    joint_limits_deg: JointLimitsDeg | None,
    step_deg: float,
    method: LimitedMethod = "exact-events",
) -> LimitedJoints | None:
    """The evaluation under joint limits, or None when every joint turns fully."""
    if joint_limits_deg is None or all(lo <= -180.0 and hi >= 180.0 for lo, hi in joint_limits_deg):
        return None
    step_rad = math.radians(step_deg)
    samples, effective = planar_serial.orientation_samples(step_rad)
    return LimitedJoints(
        joint_limits_rad=np.radians(np.asarray(joint_limits_deg, dtype=float)),
        method=method,
        requested_step_rad=step_rad,
        samples=int(samples),
        effective_step_rad=float(effective),
    )


def grid_dexterity(
    links: Links,
    grid: WorkspaceGrid,
    limited: LimitedJoints | None,
    on_progress: Callable[[int, int], None],
) -> FloatArray:
    """d_z at every node, (ny, nx); ``on_progress(done, total)`` after each chunk.

    The links are the job's, validated (an :class:`~..kinematics.inputs.Arm`).  With
    revolute joints the closed form takes them as a row of designs (1, 1, 3), as the
    study kernel's tiles of maps do, so that both compute each node alike."""
    points = grid.points()
    if limited is None:
        ny = points.shape[0]
        d_z = np.empty(points.shape[:2])
        row = np.asarray(links, dtype=np.float64).reshape(1, 1, 3)
        edges = np.linspace(0, ny, min(EXACT_ROW_BLOCKS, ny) + 1).astype(int)
        for start, stop in itertools.pairwise(edges.tolist()):
            d_z[start:stop] = closed_form_dexterity(row, points[start:stop])
            on_progress(stop, ny)
        return d_z
    if not limited.sampled:
        return exact_limited_orientation_dexterity(
            links, points, limited.joint_limits_rad, on_chunk=on_progress
        )
    return np.asarray(
        planar_serial.limited_orientation_dexterity(
            links,
            points,
            limited.joint_limits_rad,
            limited.requested_step_rad,
            on_chunk=on_progress,
        ),
        dtype=float,
    )


def point_dexterity(links: Links, points: FloatArray, limited: LimitedJoints | None) -> FloatArray:
    """d_z at ``points`` (n, 2) -> (n,): closed form, exact events, or sampled and refined.

    The exact methods are the study kernel's own arithmetic with one design
    (:func:`~..kinematics.study_kernel.designs_point_dexterity`), so a study reads the
    numbers a job reports."""
    if points.shape[0] == 0:
        return np.zeros(0)
    if limited is None or not limited.sampled:
        limits = None if limited is None else limited.joint_limits_rad
        rows = designs_point_dexterity(np.asarray([links], dtype=float), points, limits)
        return np.asarray(rows[0], dtype=np.float64)
    return np.asarray(
        planar_serial.limited_orientation_dexterity(
            links,
            points,
            limited.joint_limits_rad,
            limited.requested_step_rad,
            refine_tol=REFINE_TOL_RAD,
        ),
        dtype=float,
    )


def orientations(limited: LimitedJoints | None) -> dict[str, object]:
    """The ``discretisation`` entries of the orientations (all null without limits)."""
    if limited is None:
        return {"orientation_step_deg": None, "orientation_samples": None, "elbow_branches": None}
    return limited.describe()


def map_method(limited: LimitedJoints | None) -> str:
    """How the map was computed, as reported in ``method``."""
    return "exact-closed-form" if limited is None else limited.method


def point_method(limited: LimitedJoints | None) -> str:
    """How task points are evaluated, as reported in ``discretisation``."""
    if limited is None or not limited.sampled:
        return map_method(limited)
    return f"bisection-refined (tol {REFINE_TOL_RAD:g} rad)"
