"""The events of joint-limited d_z along a ray from the base, as functions of the distance.

Along the ray p = r u(theta) every event condition of :mod:`..limited_exact` reads
``a(r) . u(phi) = k(r)`` with ``a(r) = A0 + r A1`` (a vector affine in r) and
``k(r) = K0 + K1 r + K2 r^2``; its two roots phi(r) = centre(r) -+ half(r) with
centre = atan2(a) and half = atan2(sqrt(|a|^2 - k^2), k) are analytic wherever they
exist.  The pieces of d_z(r) end at the **breakpoints**, roots of polynomials in r:

* ``|a|^2 - k^2 = 0`` (degree 4): a condition's roots appear, meet or vanish;
* ``k' |a|^2 - k (a . A1) = 0`` (degree 3): half is stationary (it is arccos(k / |a|));
* ``a = 0``: the centre turns over (only where A0 and A1 are parallel); elsewhere the
  centre, the direction of a point moving on a line, turns one way;
* ``|k_i a_j - k_j a_i|^2 = (a_i x a_j)^2`` (degree 6): roots of two conditions meet,
  so the cyclic order of the roots is fixed in between.

When a x b vanishes identically the vectors stay on one line and the components of
``k_i a_j - k_j a_i`` are solved instead.  Between breakpoints every root exists
throughout or nowhere and keeps its place among the others, so the feasibility of every
sub-arc between them is fixed, and each condition's centre and half are monotone.  Lengths
here are scaled by l1 + l2 + l3 (the caller's job); conventions as in
:mod:`worker.families.planar_serial.kinematics`.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import polynomial as poly

from worker.families.planar_serial.kinematics.inputs import BoolArray, FloatArray, Links
from worker.families.planar_serial.kinematics.limited_exact import event_conditions

__all__ = [
    "ConditionPolynomials",
    "RayConditions",
    "condition_polynomials",
    "ray_breakpoints",
    "ray_conditions",
    "root_angles",
]

#: Coefficients (in scaled lengths) below this are zero: a condition or a cross product
#: that vanishes identically, or a vector a(r) through the base.
_ZERO = 1e-12
#: Complex roots whose imaginary part is below this (scaled) still give a breakpoint: a
#: spare breakpoint costs a little work, a missed one would cost correctness.
_NEAR_REAL = 1e-3
#: Polynomial coefficients below this fraction of the largest are rounding noise.
_TRIM = 1e-13


@dataclass(frozen=True)
class RayConditions:
    """The distinct event conditions along one ray, as polynomials in r (ascending).

    a0, a1: (C, 2) with a(r) = a0 + r a1; k: (C, 3) with k(r) = k[:, 0] + k[:, 1] r +
    k[:, 2] r^2.  ``constant_k`` holds the k of conditions with a = 0 throughout (no
    event: they hold for every phi or none, changing only where k = 0).
    """

    a0: FloatArray
    a1: FloatArray
    k: FloatArray
    constant_k: FloatArray

    @property
    def count(self) -> int:
        return int(self.a0.shape[0])

    def at(self, r: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(ax, ay, k), each (n, C), at the distances r (n,)."""
        a = self.a0 + r[:, None, None] * self.a1
        k = self.k[:, 0] + r[:, None] * (self.k[:, 1] + r[:, None] * self.k[:, 2])
        return a[..., 0], a[..., 1], k


def ray_conditions(links: Links, limits: FloatArray, angle: float) -> RayConditions:
    """The conditions of :func:`event_conditions` along the ray at ``angle`` (rad).

    links checked and scaled; limits checked (rad).  The polynomials are read off the
    conditions themselves at r = 0, 1, 2 (exact for degrees 1 and 2), so they cannot
    drift from the events the map uses; identical conditions (e.g. th2 limits +-t) are
    kept once.
    """
    r = np.array([0.0, 1.0, 2.0])
    ax, ay, k = event_conditions(links, limits, r * math.cos(angle), r * math.sin(angle))
    a0 = np.stack([ax[0], ay[0]], axis=-1)
    a1 = np.stack([ax[1] - ax[0], ay[1] - ay[0]], axis=-1)
    k2 = 0.5 * (k[2] - 2.0 * k[1] + k[0])
    coefficients = np.stack([k[0], k[1] - k[0] - k2, k2], axis=-1)
    rows = np.concatenate([a0, a1, coefficients], axis=-1)
    keep: list[int] = []
    for index, row in enumerate(rows):
        if not any(np.allclose(row, rows[j], rtol=0.0, atol=_ZERO) for j in keep):
            keep.append(index)
    chosen = np.array(keep, dtype=int)
    flat = np.hypot(a0[chosen], a1[chosen]).max(axis=-1) <= _ZERO
    moving = chosen[~flat]
    return RayConditions(a0[moving], a1[moving], coefficients[moving], coefficients[chosen[flat]])


def root_angles(
    conditions: RayConditions, r: FloatArray, side: float = 1.0
) -> tuple[FloatArray, FloatArray, BoolArray]:
    """(centre, half, exists), each (n, C), of the conditions' roots at distances r (n,).

    The roots are centre -+ half.  Where a(r) = 0 (the centre is undefined) the limit
    from above (``side`` = 1) or below (-1) is taken: a = (r' - r) A1 nearby, so the
    centre is the direction of side A1 and half = arccos(side k'(r) / |A1|).
    """
    ax, ay, k = conditions.at(r)
    discriminant = ax * ax + ay * ay - k * k
    centre = np.arctan2(ay, ax)
    half = np.arctan2(np.sqrt(np.maximum(discriminant, 0.0)), k)
    through = np.hypot(ax, ay) <= _ZERO
    if through.any():
        a1x, a1y = conditions.a1[:, 0], conditions.a1[:, 1]
        slope = conditions.k[:, 1] + 2.0 * conditions.k[:, 2] * r[:, None]
        norm = np.maximum(np.hypot(a1x, a1y), _ZERO)
        limit_centre = np.broadcast_to(np.arctan2(side * a1y, side * a1x), centre.shape)
        limit_half = np.arccos(np.clip(side * slope / norm, -1.0, 1.0))
        centre = np.where(through, limit_centre, centre)
        half = np.where(through, limit_half, half)
    return centre, half, discriminant >= 0.0


def _real_roots(coefficients: FloatArray, lo: float, hi: float) -> list[float]:
    """Real roots in (lo, hi) of a polynomial (ascending), near-real ones included."""
    # a leading coefficient at rounding level would throw the other roots far off
    size = np.abs(coefficients).max(initial=0.0)
    c = np.trim_zeros(np.where(np.abs(coefficients) > _TRIM * size, coefficients, 0.0), "b")
    if c.size < 2:
        return []
    roots = poly.polyroots(c)
    near = roots[np.abs(roots.imag) <= _NEAR_REAL * np.maximum(1.0, np.abs(roots.real))].real
    polished = []
    derivative = poly.polyder(c)
    for x in near[(near > lo) & (near < hi)]:
        for _ in range(3):  # Newton steps, kept only while they improve
            slope = poly.polyval(x, derivative)
            if slope == 0.0:
                break
            step = x - poly.polyval(x, c) / slope
            if not abs(poly.polyval(step, c)) < abs(poly.polyval(x, c)):
                break
            x = step
        polished.append(float(x))
    return [x for x in polished if lo < x < hi]


def _solve(
    vector: tuple[FloatArray, FloatArray], cross: FloatArray, scale: float
) -> list[FloatArray]:
    """Polynomials whose roots hold ``|vector| = |cross|``: ``vx^2 + vy^2 - cross^2``,
    or, when ``cross`` vanishes identically (relative to ``scale``), vx and vy."""
    vx, vy = vector
    if np.abs(cross).max(initial=0.0) > _ZERO * scale:
        square = poly.polyadd(poly.polymul(vx, vx), poly.polymul(vy, vy))
        return [np.asarray(poly.polysub(square, poly.polymul(cross, cross)), dtype=float)]
    return [v for v in (vx, vy) if np.abs(v).max(initial=0.0) > _ZERO]


@dataclass(frozen=True)
class ConditionPolynomials:
    """Per condition, coefficients in r (ascending): norm2 = |a|^2 (C, 3), discriminant
    = |a|^2 - k^2 (C, 5), turning = k' |a|^2 - k (a . A1) (C, 4, the sign of half'
    times -1), and cross = A0 x A1 (C,), so that centre' = cross / |a|^2."""

    norm2: FloatArray
    discriminant: FloatArray
    turning: FloatArray
    cross: FloatArray


def condition_polynomials(c: RayConditions) -> ConditionPolynomials:
    """The polynomials of every condition (see :class:`ConditionPolynomials`)."""
    norm2, discriminant, turning = (
        np.zeros((c.count, 3)),
        np.zeros((c.count, 5)),
        np.zeros((c.count, 4)),
    )
    for i in range(c.count):
        ax, ay = np.array([c.a0[i, 0], c.a1[i, 0]]), np.array([c.a0[i, 1], c.a1[i, 1]])
        square = poly.polyadd(poly.polymul(ax, ax), poly.polymul(ay, ay))
        along = poly.polyadd(ax * c.a1[i, 0], ay * c.a1[i, 1])  # a . A1
        norm2[i] = _padded(square, 3)
        discriminant[i] = _padded(poly.polysub(square, poly.polymul(c.k[i], c.k[i])), 5)
        slope = poly.polyder(c.k[i])
        turning[i] = _padded(
            poly.polysub(poly.polymul(slope, square), poly.polymul(c.k[i], along)), 4
        )
    cross = c.a0[:, 0] * c.a1[:, 1] - c.a0[:, 1] * c.a1[:, 0]
    return ConditionPolynomials(norm2, discriminant, turning, cross)


def _padded(coefficients: FloatArray, size: int) -> FloatArray:
    padded = np.zeros(size)
    padded[: coefficients.size] = coefficients
    return padded


def _condition_breakpoints(c: RayConditions, p: ConditionPolynomials, i: int) -> list[FloatArray]:
    polynomials = [p.discriminant[i], p.turning[i]]
    scale = max(float(np.hypot(*c.a0[i])), float(np.hypot(*c.a1[i]))) ** 2
    if abs(float(p.cross[i])) <= _ZERO * scale and np.hypot(*c.a1[i]) > _ZERO:
        # a(r) moves on a line through the base: it passes through it at most once
        turn = -float(np.dot(c.a0[i], c.a1[i])) / float(np.dot(c.a1[i], c.a1[i]))
        polynomials.append(np.array([-turn, 1.0]))
    return polynomials


def _pair_polynomials(c: RayConditions, i: int, j: int) -> list[FloatArray]:
    aix, aiy = np.array([c.a0[i, 0], c.a1[i, 0]]), np.array([c.a0[i, 1], c.a1[i, 1]])
    ajx, ajy = np.array([c.a0[j, 0], c.a1[j, 0]]), np.array([c.a0[j, 1], c.a1[j, 1]])
    cross = poly.polysub(poly.polymul(aix, ajy), poly.polymul(aiy, ajx))
    vector = (poly.polysub(poly.polymul(c.k[i], ajx), poly.polymul(c.k[j], aix)),
              poly.polysub(poly.polymul(c.k[i], ajy), poly.polymul(c.k[j], aiy)))  # fmt: skip
    scale = float(np.abs(c.a0[[i, j]]).max() + np.abs(c.a1[[i, j]]).max()) ** 2
    return _solve(vector, cross, scale)


def ray_breakpoints(
    conditions: RayConditions,
    polynomials: ConditionPolynomials,
    edges: FloatArray,
) -> FloatArray:
    """Sorted distances from edges[0] to edges[-1] where d_z(r) may change form, every
    one of the ``edges`` (sorted) among them; others closer than 1e-12 to one dropped."""
    lo, hi = float(edges[0]), float(edges[-1])
    equations: list[FloatArray] = [np.asarray(k) for k in conditions.constant_k]
    for i in range(conditions.count):
        equations.extend(_condition_breakpoints(conditions, polynomials, i))
    for i, j in itertools.combinations(range(conditions.count), 2):
        equations.extend(_pair_polynomials(conditions, i, j))
    required = np.unique(edges)
    radii = [x for coefficients in equations for x in _real_roots(coefficients, lo, hi)]
    found = np.sort(np.asarray(radii, dtype=float))
    near = np.abs(found[:, None] - required[None, :]).min(axis=1, initial=np.inf) <= _ZERO
    merged: list[float] = []
    for x in found[~near].tolist():
        if not merged or x - merged[-1] > _ZERO:
            merged.append(x)
    return np.union1d(required, merged)
