"""The isotropic design of eq (12) and the isotropic (or best-conditioned) point of a
2-DOF planar parallel robot (Huang et al. 2004 §III-B, eqs 10-12; docs/methods/planar-parallel.md).

Re-exported by :mod:`worker.families.planar_parallel.kinematics`; conventions as there.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq, minimize_scalar

from worker.common.parameter_errors import bad_parameter
from worker.families.planar_parallel.kinematics.model import (
    Architecture,
    FloatArray,
    Robot,
    chain_components,
    checked_mode,
    finite_real,
    inverse_condition_kernel,
)

__all__ = ["isotropic_architecture", "isotropic_point", "robot_isotropic_point"]

HALF_SQRT2 = math.sqrt(0.5)
PAPER_MODE = (1, -1)


def isotropic_architecture(l2: float, l1: float = 1.0) -> Architecture:
    """The proximal-arm design of eq (12): e = (sqrt 2 / 2)(l2 - l1), needs l2 >= l1.

    Its isotropic point (0, -H), H = (sqrt 2 / 2)(l1 + l2), has 1/kappa = 1 and
    sigma_1 = sigma_2 = 1 (eq 11) in the paper's working mode (+1, -1).
    """
    if not (finite_real(l1) and l1 > 0):
        raise bad_parameter("l1", "isotropic_architecture", "a finite positive length", l1)
    if not (finite_real(l2) and l2 >= l1):
        raise bad_parameter("l2", "isotropic_architecture", f"a finite length >= l1 = {l1}", l2)
    return Architecture("proximal-arm", float(l1), float(l2), HALF_SQRT2 * (l2 - l1))


def _is_eq12(arch: Architecture) -> bool:
    expected = HALF_SQRT2 * (arch.l2 - arch.l1)
    return arch.actuation == "proximal-arm" and math.isclose(
        arch.e, expected, rel_tol=1e-12, abs_tol=1e-12 * (arch.l1 + arch.l2)
    )


def isotropic_point(
    arch: Architecture, working_mode: tuple[int, int] = PAPER_MODE
) -> tuple[float, float]:
    """The isotropic (or best-conditioned) point on the y axis below the base, (x, y).

    Closed forms, 1/kappa = 1 there: the eq-(12) proximal arm in the paper's mode,
    (0, -H), H = (sqrt 2 / 2)(l1 + l2); the telescopic leg (e > 0), (0, -e) (the legs
    are perpendicular, eq 10); the linear drive with m2 = -m1, (0, -l2 / sqrt 2) (the
    links are perpendicular; |v_i| = 1/sqrt 2, eq 11's |v_i| = 1 is out of reach).
    Otherwise the point of largest 1/kappa on {x = 0, y < 0}: the best of 4001 samples,
    refined by a root of w1 . w2 (the cusp where 1/kappa = 1 if |v1| = |v2|, as on the
    axis of a mirror-symmetric mode) or else a bounded Brent search; 1/kappa < 1 in
    general; (nan, nan) if 1/kappa is 0 or undefined all along the axis.
    """
    if not isinstance(arch, Architecture):
        raise bad_parameter("arch", "isotropic_point", "an Architecture", arch)
    return robot_isotropic_point(Robot(arch, checked_mode(working_mode, "isotropic_point")))


def robot_isotropic_point(robot: Robot) -> tuple[float, float]:
    """:func:`isotropic_point` of a checked :class:`~.model.Robot` (no checks)."""
    arch, mode = robot.arch, robot.mode
    if _is_eq12(arch) and mode == PAPER_MODE:
        return 0.0, -HALF_SQRT2 * (arch.l1 + arch.l2)
    if arch.actuation == "telescopic-leg" and arch.e > 0:
        return 0.0, -arch.e
    if arch.actuation == "linear-drive" and mode[1] == -mode[0]:
        return 0.0, -arch.l2 * HALF_SQRT2
    depth = arch.l2 if arch.actuation == "linear-drive" else arch.l1 + arch.l2 + arch.e
    ys = np.linspace(-depth, 0.0, 4001)

    def value(y: ArrayLike) -> FloatArray:  # 1/kappa on the axis, -1 out of reach
        return np.nan_to_num(inverse_condition_kernel(arch, mode, 0.0, y), nan=-1.0)

    values = value(ys)
    best = int(np.argmax(values))
    if values[best] <= 0.0:
        return math.nan, math.nan
    lo, hi = ys[max(best - 1, 0)], ys[min(best + 1, ys.size - 1)]

    def legs_dot(y: float) -> float:  # w1 . w2 on the axis; 1/kappa has a cusp where it is 0
        first, second = chain_components(arch.actuation, (arch.l1, arch.l2, arch.e), mode, 0.0, y)
        return float(first[2] * second[2] + first[3] * second[3])

    # The root search needs both ends in reach: legs_dot is junk outside it.
    if min(value(lo), value(hi)) >= 0.0 and legs_dot(lo) * legs_dot(hi) < 0.0:
        refined = float(brentq(legs_dot, lo, hi, xtol=_axis_tolerance(1e-15, depth)))
    else:
        refined = float(minimize_scalar(
            lambda y: -float(value(y)), bounds=(lo, hi), method="bounded",
            options={"xatol": _axis_tolerance(1e-12, depth)},
        ).x)  # fmt: skip
    # A refinement that lost the sampled best (a band of reach thinner than the samples'
    # spacing) keeps the sample.
    return (0.0, refined) if value(refined) >= values[best] else (0.0, float(ys[best]))


def _axis_tolerance(tolerance: float, depth: float) -> float:
    """An absolute tolerance on the axis, shrunk with a robot smaller than the unit one
    (``depth`` < 1) so that it stays relative; larger robots have the solvers' relative
    tolerances."""
    return tolerance * min(depth, 1.0)
