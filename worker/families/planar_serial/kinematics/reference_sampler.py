"""The per-point reference sampler of orientation dexterity for three-link planar arms.

A plain loop over the orientation samples, with the math module only and no shared
kernel with :mod:`.joint_limits`, kept for property tests and the
benchmark. Conventions as in :mod:`worker.families.planar_serial.kinematics`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from worker.common.parameter_errors import bad_parameter

__all__ = ["sampled_orientation_dexterity"]


def _wrap(angle: float) -> float:
    """Angle wrapped to (-pi, pi]."""
    return math.pi - (math.pi - angle) % (2.0 * math.pi)


def _within_limits(
    lengths: tuple[float, float],
    wrist: tuple[float, float],
    phi: float,
    limits: Sequence[Sequence[float]],
) -> bool:
    l1, l2 = lengths
    wx, wy = wrist
    c2 = (wx * wx + wy * wy - l1 * l1 - l2 * l2) / (2.0 * l1 * l2)
    if not -1.0 <= c2 <= 1.0:
        return False
    for th2 in (math.acos(c2), -math.acos(c2)):
        th1 = math.atan2(wy, wx) - math.atan2(l2 * math.sin(th2), l1 + l2 * math.cos(th2))
        angles = (_wrap(th1), _wrap(th2), _wrap(phi - th1 - th2))
        if all(lo <= a <= hi for a, (lo, hi) in zip(angles, limits, strict=True)):
            return True
    return False


def sampled_orientation_dexterity(
    links: Sequence[float],
    point: Sequence[float],
    step: float,
    joint_limits: Sequence[Sequence[float]] | None = None,
) -> float:
    """Reference d_z at ONE point: a plain loop over the samples phi_k = k 2 pi / n.

    The straightforward per-point implementation (math module only), kept independent of
    the vectorised code for property tests and the benchmark. Unlimited joints: phi_k
    counts iff |l1 - l2| <= |w| <= l1 + l2; with limits (rad, (3, 2)) it counts iff an
    elbow branch has every wrapped joint angle within its limits. Returns count / n.
    """
    function = "sampled_orientation_dexterity"
    if len(links) != 3 or not all(math.isfinite(v) and v > 0 for v in links):
        raise bad_parameter("links", function, "three finite positive lengths (l1, l2, l3)", links)
    if len(point) != 2 or not all(math.isfinite(v) for v in point):
        raise bad_parameter("point", function, "finite (x, y) coordinates", point)
    if not (step > 0 and math.isfinite(2.0 * math.pi / step)):
        raise bad_parameter("step", function, "a finite positive angle in radians", step)
    if joint_limits is not None and (
        len(joint_limits) != 3
        or not all(
            len(lim) == 2 and -math.pi <= lim[0] <= lim[1] <= math.pi for lim in joint_limits
        )
    ):
        limits_rule = "(3, 2) radians [[lo, hi], ...] with -pi <= lo <= hi <= pi"
        raise bad_parameter("joint_limits", function, limits_rule, joint_limits)
    l1, l2, l3 = (float(v) for v in links)
    x, y = (float(v) for v in point)
    n = max(1, round(2.0 * math.pi / step))
    count = 0
    for k in range(n):
        phi = k * (2.0 * math.pi / n)
        wrist = (x - l3 * math.cos(phi), y - l3 * math.sin(phi))
        if joint_limits is None:
            count += abs(l1 - l2) <= math.hypot(*wrist) <= l1 + l2
        else:
            count += _within_limits((l1, l2), wrist, phi, joint_limits)
    return count / n
