"""Trajectories of the planar3r jobs: exact distance ranges, samples, and eq (4) means."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from worker.families.planar_serial.kinematics import trajectory as kin_trajectory
from worker.families.planar_serial.kinematics.study_kernel import trajectory_statistics
from worker.families.planar_serial.kinematics.trajectory import DistanceRange
from worker.families.planar_serial.specs import PolylineTrajectory, PolynomialTrajectory

__all__ = [
    "task_distance_range",
    "trajectory_distance_range",
    "trajectory_path",
    "trajectory_samples",
    "trajectory_summary",
]

#: Points drawn along a polynomial trajectory in the plots (at least).
PLOT_SAMPLES = 400

FloatArray = NDArray[np.float64]
TrajectorySpec = PolylineTrajectory | PolynomialTrajectory


def trajectory_distance_range(spec: TrajectorySpec) -> DistanceRange:
    """The exact min and max distance from the base along the whole trajectory."""
    if isinstance(spec, PolylineTrajectory):
        return kin_trajectory.polyline_distance_range(np.asarray(spec.points, dtype=float))
    return kin_trajectory.polynomial_distance_range(
        np.asarray(spec.polynomial, dtype=float), spec.x_start, spec.x_end
    )


def task_distance_range(
    trajectory: TrajectorySpec | None, task_points: Sequence[Sequence[float]] | None
) -> DistanceRange:
    """The task's exact distance range: the trajectory's if there is one (it sets the
    design, as in the paper's Example 1), else the task points'."""
    if trajectory is not None:
        return trajectory_distance_range(trajectory)
    return kin_trajectory.points_distance_range(np.asarray(task_points, dtype=float))


def trajectory_samples(spec: TrajectorySpec) -> FloatArray:
    """``spec.samples`` points (samples, 2) along the trajectory, ends included.

    A polyline is sampled evenly by arc length; a polynomial y(x) evenly in x (as
    :func:`worker.families.planar_serial.kinematics.trajectory.sample_polynomial` does).
    """
    if isinstance(spec, PolynomialTrajectory):
        return np.asarray(
            kin_trajectory.sample_polynomial(
                np.asarray(spec.polynomial, dtype=float), spec.x_start, spec.x_end, spec.samples
            ),
            dtype=float,
        )
    vertices = np.asarray(spec.points, dtype=float)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(vertices, axis=0).T))])
    targets = np.linspace(0.0, arc[-1], spec.samples)
    return np.stack(
        [np.interp(targets, arc, vertices[:, 0]), np.interp(targets, arc, vertices[:, 1])],
        axis=-1,
    )


def trajectory_path(spec: TrajectorySpec) -> FloatArray:
    """The trajectory as drawn, (m, 2): a polyline's own vertices, a polynomial densely."""
    if isinstance(spec, PolylineTrajectory):
        return np.asarray(spec.points, dtype=float)
    return np.asarray(
        kin_trajectory.sample_polynomial(
            np.asarray(spec.polynomial, dtype=float),
            spec.x_start,
            spec.x_end,
            max(spec.samples, PLOT_SAMPLES),
        ),
        dtype=float,
    )


def trajectory_summary(d_z: FloatArray) -> dict[str, float | int]:
    """Eq (4) over the samples: mean d_z and D = d_z/3, the minimum, the full fraction
    (the study kernel's :func:`~..kinematics.study_kernel.trajectory_statistics` of one
    design)."""
    stats = trajectory_statistics(d_z.reshape(1, -1))
    return {
        "samples": int(d_z.size),
        "d_z_mean": float(stats.d_z_mean[0]),
        "D_mean": float(stats.D_mean[0]),
        "d_z_min": float(stats.d_z_min[0]),
        "fully_dexterous_fraction": float(stats.fully_dexterous_fraction[0]),
    }
