"""1/kappa, pressure angles and joints of a checked :class:`~.model.Robot`, at points and
on a grid: what a job calls with the one Robot it built (no checks here; the checked
fronts are :mod:`worker.families.planar_parallel.kinematics`' functions of the same
meaning). Conventions as there."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from worker.families.planar_parallel.kinematics.model import (
    BoolArray,
    FloatArray,
    Robot,
    chain_components,
    chain_terms,
    inverse_condition_kernel,
    inverse_condition_of_components,
    joints_of_components,
)
from worker.families.planar_parallel.kinematics.pressure import pressure_angles_at

__all__ = [
    "ConditioningMap",
    "robot_inverse_condition",
    "robot_inverse_kinematics",
    "robot_map",
    "robot_pressure_angles",
]


@dataclass(frozen=True)
class ConditioningMap:
    """1/kappa and pressure angles on the grid x (nx,) by y (ny,); arrays are (ny, nx, ...).

    reachable (ny, nx) bool; inverse_condition (ny, nx), NaN where unreachable;
    pressure_angles (ny, nx, 2) rad; min_pressure_angle (ny, nx) = min(beta_1, beta_2) rad
    (the paper's beta_min, printed "min(beta_1 - beta_2)"); joints (ny, nx, 2) as
    :func:`robot_inverse_kinematics`.
    """

    x: FloatArray
    y: FloatArray
    reachable: BoolArray
    inverse_condition: FloatArray
    pressure_angles: FloatArray
    min_pressure_angle: FloatArray
    joints: FloatArray


def robot_inverse_kinematics(robot: Robot, points: FloatArray) -> tuple[FloatArray, BoolArray]:
    """Actuated joints at finite points (..., 2): (joints (..., 2), reachable (...))."""
    terms = chain_terms(robot.arch, robot.mode, points)
    return terms.joints, terms.reachable


def robot_inverse_condition(robot: Robot, points: FloatArray) -> FloatArray:
    """1/kappa (...) by eq (7) at finite points (..., 2); NaN where unreachable."""
    return inverse_condition_kernel(robot.arch, robot.mode, points[..., 0], points[..., 1])


def robot_pressure_angles(robot: Robot, points: FloatArray) -> FloatArray:
    """Pressure angles (beta_1, beta_2) (..., 2), rad, at finite points (..., 2)."""
    x, y = points[..., 0], points[..., 1]
    reachable = np.isfinite(inverse_condition_kernel(robot.arch, robot.mode, x, y))
    return pressure_angles_at(robot.arch, x, y, reachable)


def robot_map(robot: Robot, xs: FloatArray, ys: FloatArray) -> ConditioningMap:
    """Everything per node of the grid xs (nx,) by ys (ny,) (finite, non-empty), in one
    vectorised pass."""
    arch, mode = robot.arch, robot.mode
    shape = (ys.size, xs.size)
    lengths = (arch.l1, arch.l2, arch.e)
    chains = chain_components(arch.actuation, lengths, mode, xs[None, :], ys[:, None])
    reachable = np.broadcast_to(chains[0][0] & chains[1][0], shape)
    inverse = np.where(reachable, inverse_condition_of_components(*chains), np.nan)
    joints = np.stack(
        [np.broadcast_to(q, shape) for q in joints_of_components(arch.actuation, chains)], -1
    )
    joints[~reachable] = np.nan
    angles = pressure_angles_at(arch, xs[None, :], ys[:, None], reachable)
    return ConditioningMap(
        xs, ys, reachable, inverse, angles, np.fmin(angles[..., 0], angles[..., 1]), joints
    )
