"""Exact values at the points a request names: 1/kappa, pressure angles, actuated joints.

Each point is evaluated on its own (closed forms, eqs 2, 7 and 15), not read off the
grid, so the values do not depend on the grid's resolution.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.families.planar_parallel import kinematics as pp

__all__ = ["finite_or_none", "point_entries", "unreachable_note"]


def finite_or_none(value: float) -> float | None:
    """``value`` as a float, or None (JSON null) when it is NaN or infinite."""
    return float(value) if math.isfinite(value) else None


def _list(values: NDArray[np.float64]) -> list[float | None] | None:
    entries = [finite_or_none(float(v)) for v in values]
    return None if all(v is None for v in entries) else entries


def point_entries(robot: pp.Robot, points: NDArray[np.float64]) -> list[dict[str, Any]]:
    """One entry per (validated, finite) point (k, 2) of the job's robot, in order.

    Keys: x, y, reachable, inverse_condition (eq 7), pressure_angles_deg [beta_1, beta_2]
    (eq 15), min_pressure_angle_deg, joint_angles_deg [th_11, th_12] (eq 2; proximal arm,
    else null) and joint_displacements [q1, q2] (leg lengths or slider positions on the x
    axis, in the length unit; null for the proximal arm). Unreachable: nulls.
    """
    if points.shape[0] == 0:
        return []
    inverse = pp.robot_inverse_condition(robot, points)
    angles = np.degrees(pp.robot_pressure_angles(robot, points))
    joints, reachable = pp.robot_inverse_kinematics(robot, points)
    proximal = robot.arch.actuation == "proximal-arm"
    entries = []
    for k, (x, y) in enumerate(points.tolist()):
        ok = bool(reachable[k])
        entries.append(
            {
                "x": x,
                "y": y,
                "reachable": ok,
                "inverse_condition": finite_or_none(float(inverse[k])) if ok else None,
                "pressure_angles_deg": _list(angles[k]) if ok else None,
                "min_pressure_angle_deg": finite_or_none(float(angles[k].min())) if ok else None,
                "joint_angles_deg": _list(np.degrees(joints[k])) if ok and proximal else None,
                "joint_displacements": _list(joints[k]) if ok and not proximal else None,
            }
        )
    return entries


def unreachable_note(entries: list[dict[str, Any]], working_mode: tuple[int, int]) -> list[str]:
    """A note naming the given points out of reach in the working mode (first 10)."""
    missing = [k for k, entry in enumerate(entries) if not entry["reachable"]]
    if not missing:
        return []
    shown = ", ".join(f"#{k + 1} ({entries[k]['x']:g}, {entries[k]['y']:g})" for k in missing[:10])
    more = f" and {len(missing) - 10} more" if len(missing) > 10 else ""
    m1, m2 = working_mode
    return [
        f"{len(missing)} of the {len(entries)} given points are out of reach in working "
        f"mode [{m1:+d}, {m2:+d}] (their values are null): {shown}{more}."
    ]
