"""Bounds of joint-limited d_z over an interval of a ray, inside one piece.

On a piece (between the breakpoints of :mod:`.events`) each event condition i has
roots centre_i -+ half_i, and the feasibility of every sub-arc between roots is fixed,
so with c_i-, c_i+ in {-1, 0, 1} (the change of feasibility across each root, read off
the arrangement at one distance):

    2 pi d_z(r) = const + sum_i (c_i- + c_i+) centre_i(r) + (c_i+ - c_i-) half_i(r).

Centre and half are monotone on a piece, so over [x, y] each term moves by at most its
change between the ends: d_z lies within ``d_z(x) + [sum of the negative moves, sum of
the positive ones] / 2 pi`` (first order; exact when all moves agree in sign, and when
a pair of roots turns rigidly, as on the plateaus of an arm limited in th3 only).  The
slope, centre' = (A0 x A1) / |a|^2 and half' = -(k' |a|^2 - k a . A1) / (|a|^2 sqrt(D))
with D = |a|^2 - k^2, is bounded by interval arithmetic on these polynomials; from both
ends it bounds d_z to second order (Piyavskii's bound), which is what closes the gap
around a smooth extremum.  All lengths scaled by l1 + l2 + l3.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.polynomial import polynomial as poly

from worker.families.planar_serial.kinematics.inputs import BoolArray, FloatArray
from worker.families.planar_serial.kinematics.ray.events import (
    ConditionPolynomials,
    RayConditions,
    root_angles,
)

__all__ = ["dexterity_bounds"]

TWO_PI = 2.0 * math.pi


def _ranges(
    coefficients: FloatArray, x: FloatArray, y: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Enclosures (n, C) of polynomials (C, deg + 1) over each [x, y] (n,): the value at
    the middle +- the sum of |p^(k)(m) / k!| h^k (a Taylor expansion, exact for these)."""
    middle, half = 0.5 * (x + y), 0.5 * (y - x)
    value = poly.polyval(middle[:, None], coefficients.T, tensor=False)
    spread = np.zeros_like(value)
    derivative, factorial = coefficients, 1.0
    for order in range(1, coefficients.shape[1]):
        derivative = np.asarray(poly.polyder(derivative, axis=1), dtype=float)
        factorial *= order
        term = poly.polyval(middle[:, None], derivative.T, tensor=False) / factorial
        spread += np.abs(term) * half[:, None] ** order
    return value - spread, value + spread


def _quotient(top: tuple[FloatArray, FloatArray], bottom: tuple[FloatArray, FloatArray]
              ) -> tuple[FloatArray, FloatArray]:  # fmt: skip
    """[top] / [bottom] with bottom > 0 (+-inf where bottom may reach 0)."""
    (t_lo, t_hi), (b_lo, b_hi) = top, bottom
    positive = b_lo > 0.0
    safe_lo, safe_hi = np.where(positive, b_lo, 1.0), np.where(positive, b_hi, 1.0)
    corners = np.stack([t_lo / safe_lo, t_lo / safe_hi, t_hi / safe_lo, t_hi / safe_hi])
    return (np.where(positive, corners.min(axis=0), -np.inf),
            np.where(positive, corners.max(axis=0), np.inf))  # fmt: skip


def _scaled(weight: FloatArray, low: FloatArray, high: FloatArray) -> tuple[FloatArray, FloatArray]:
    """weight (n, C) times [low, high], 0 where weight is 0 (even if unbounded)."""
    with np.errstate(invalid="ignore"):
        a, b = weight * low, weight * high
    used = weight != 0.0
    return np.where(used, np.minimum(a, b), 0.0), np.where(used, np.maximum(a, b), 0.0)


def _slope_bounds(
    polynomials: ConditionPolynomials, turn_weight: FloatArray, half_weight: FloatArray,
    x: FloatArray, y: FloatArray,
) -> tuple[FloatArray, FloatArray]:  # fmt: skip
    """Bounds (n,) of d_z' over each [x, y], -inf / inf where a root may turn round."""
    norm_lo, norm_hi = _ranges(polynomials.norm2, x, y)
    disc_lo, disc_hi = _ranges(polynomials.discriminant, x, y)
    cross = np.broadcast_to(polynomials.cross, norm_lo.shape)
    centre = _quotient((cross, cross), (norm_lo, norm_hi))
    root_lo = np.sqrt(np.maximum(disc_lo, 0.0))
    root_hi = np.sqrt(np.maximum(disc_hi, 0.0))
    turning_lo, turning_hi = _ranges(polynomials.turning, x, y)
    half = _quotient((-turning_hi, -turning_lo),
                     (np.maximum(norm_lo, 0.0) * root_lo, norm_hi * root_hi))  # fmt: skip
    centre_lo, centre_hi = _scaled(turn_weight, *centre)
    half_lo, half_hi = _scaled(half_weight, *half)
    return ((centre_lo + half_lo).sum(axis=1) / TWO_PI,
            (centre_hi + half_hi).sum(axis=1) / TWO_PI)  # fmt: skip


def dexterity_bounds(
    conditions: RayConditions, polynomials: ConditionPolynomials, coefficient: FloatArray,
    x: FloatArray, y: FloatArray, anchor: FloatArray, anchored_left: BoolArray,
) -> tuple[FloatArray, FloatArray]:  # fmt: skip
    """Lower and upper bounds (n,) of d_z on each [x, y] (module docstring).

    coefficient: (n, C, 2) c_i-, c_i+ of the piece holding [x, y]; anchor: d_z (n,) at x
    where ``anchored_left``, else at y (the other end may be a breakpoint, where d_z
    need not continue the piece's formula: its value is taken from the formula).
    """
    centre_x, half_x, _ = root_angles(conditions, x, 1.0)
    centre_y, half_y, _ = root_angles(conditions, y, -1.0)
    turn = np.mod(centre_y - centre_x + math.pi, TWO_PI) - math.pi
    widen = half_y - half_x
    turn_weight = coefficient[..., 0] + coefficient[..., 1]
    half_weight = coefficient[..., 1] - coefficient[..., 0]
    moves = np.concatenate([turn_weight * turn, half_weight * widen], axis=1)
    down = np.minimum(moves, 0.0).sum(axis=1) / TWO_PI
    up = np.maximum(moves, 0.0).sum(axis=1) / TWO_PI
    left = np.where(anchored_left, anchor, anchor - up - down)
    right = np.where(anchored_left, anchor + up + down, anchor)
    lower, upper = left + down, left + up
    low, high = _slope_bounds(polynomials, turn_weight, half_weight, x, y)
    # d_z >= left + low (r - x) and >= right - high (y - r): the least of the larger
    width = y - x
    fall, rise = np.maximum(-low, 0.0), np.maximum(high, 0.0)
    usable = np.isfinite(fall) & np.isfinite(rise) & (fall + rise > 0.0)
    fall, rise = np.where(usable, fall, 0.0), np.where(usable, rise, 1.0)
    at_low = np.clip((left - right + rise * width) / (fall + rise), 0.0, width)
    at_high = np.clip((right - left + fall * width) / (fall + rise), 0.0, width)
    lower = np.where(usable, np.maximum(lower, left - fall * at_low), lower)
    upper = np.where(usable, np.minimum(upper, left + rise * at_high), upper)
    return np.clip(lower, 0.0, 1.0), np.clip(upper, 0.0, 1.0)
