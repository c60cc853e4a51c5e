"""Distance ranges of task points and trajectories from a base at the origin.

Step 1 of the synthesis algorithm (Patel & Sobh §4): d_min <= d <= d_max over the region
of operation, fed to eqs (10)-(11). For the paper's cubic (eq 12) the exact range is
10.3923 <= d <= 19.7673, not the printed 10 and 20 (docs/methods/planar-serial.md, "The paper's
errata").
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from worker.common.parameter_errors import bad_parameter

__all__ = [
    "DistanceRange",
    "points_distance_range",
    "polyline_distance_range",
    "polynomial_distance_range",
    "sample_polynomial",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class DistanceRange:
    """Smallest and largest distance from the origin, and where each is attained (x, y)."""

    d_min: float
    d_max: float
    at_min: tuple[float, float]
    at_max: tuple[float, float]


def _xy(point: FloatArray) -> tuple[float, float]:
    return float(point[0]), float(point[1])


def _finite_array(value: object, parameter: str, function: str, requirement: str) -> FloatArray:
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise bad_parameter(parameter, function, requirement, value) from None
    if not np.all(np.isfinite(arr)):
        raise bad_parameter(parameter, function, requirement, value)
    return arr


def _point_array(points: ArrayLike, parameter: str, function: str) -> FloatArray:
    requirement = "finite (x, y) coordinates of shape (n, 2), n >= 1"
    arr = _finite_array(points, parameter, function, requirement)
    if arr.ndim != 2 or arr.shape[0] < 1 or arr.shape[1] != 2:
        raise bad_parameter(parameter, function, requirement, points)
    return arr


def points_distance_range(points: ArrayLike) -> DistanceRange:
    """d_min, d_max over (n, 2) task points (first point on ties)."""
    p = _point_array(points, "points", "points_distance_range")
    d = np.hypot(p[:, 0], p[:, 1])
    lo, hi = int(np.argmin(d)), int(np.argmax(d))
    return DistanceRange(float(d[lo]), float(d[hi]), _xy(p[lo]), _xy(p[hi]))


def polyline_distance_range(vertices: ArrayLike) -> DistanceRange:
    """Exact range over the segments joining (n, 2) vertices in order.

    d_min: the origin projected onto each segment, clipped to it; d_max: at a vertex
    (distance is convex along a segment).
    """
    v = _point_array(vertices, "vertices", "polyline_distance_range")
    hi = int(np.argmax(np.hypot(v[:, 0], v[:, 1])))
    start, delta = v[:-1], np.diff(v, axis=0)
    if len(delta) == 0:
        closest = v
    else:
        length2 = np.sum(delta * delta, axis=1)
        along = -np.sum(start * delta, axis=1) / np.where(length2 > 0, length2, 1.0)
        closest = start + np.clip(along, 0.0, 1.0)[:, None] * delta
    d = np.hypot(closest[:, 0], closest[:, 1])
    lo = int(np.argmin(d))
    return DistanceRange(float(d[lo]), float(np.hypot(*v[hi])), _xy(closest[lo]), _xy(v[hi]))


def _coefficients(coefficients: ArrayLike, function: str) -> FloatArray:
    requirement = "a 1-D sequence of finite coefficients, highest power first"
    c = _finite_array(coefficients, "coefficients", function, requirement)
    if c.ndim != 1 or c.size < 1:
        raise bad_parameter("coefficients", function, requirement, coefficients)
    return c


def _interval(x_start: float, x_end: float, function: str) -> tuple[float, float]:
    for name, value in (("x_start", x_start), ("x_end", x_end)):
        if not (isinstance(value, numbers.Real) and math.isfinite(value)):
            raise bad_parameter(name, function, "a finite number", value)
    return float(x_start), float(x_end)


def _real_roots_within(poly: FloatArray, a: float, b: float) -> list[float]:
    """Real roots in [a, b] of a polynomial (highest power first), near-real ones included.

    In t = x / s with s = max(|a|, |b|, 1), terms below 1e-13 of the largest coefficient
    are negligible on the interval and dropped, so a tiny leading coefficient cannot blow
    up the companion matrix; the roots move by a negligible amount at most.
    """
    scale = max(abs(a), abs(b), 1.0)
    with np.errstate(over="ignore", invalid="ignore"):
        in_t = poly * scale ** np.arange(poly.size - 1, -1, -1.0)
    if not np.all(np.isfinite(in_t)):
        in_t, scale = poly, 1.0
    significant = np.flatnonzero(np.abs(in_t) > 1e-13 * np.max(np.abs(in_t)))
    roots = np.roots(in_t[significant[0] :]) * scale if significant.size else np.array([])
    return [
        float(r.real) for r in roots if abs(r.imag) <= 1e-7 * (1.0 + abs(r)) and a <= r.real <= b
    ]


def polynomial_distance_range(
    coefficients: ArrayLike, x_start: float, x_end: float
) -> DistanceRange:
    """Exact range of d(x) = sqrt(x^2 + y(x)^2) on y = polyval(coefficients, x).

    x runs between x_start and x_end (either order). Candidates are both end points and
    the real roots in the interval of d/dx (x^2 + y^2) / 2 = x + y y' (from the companion
    matrix; near-real roots are kept, which is safe since every candidate is a point of
    the curve, and x + y y' never vanishes identically). Paper Example 1 (eq 12, x from
    14 to 8): d_min = 10.3923 at x = 10.2044, d_max = 19.7673 at x = 14.
    """
    function = "polynomial_distance_range"
    c = _coefficients(coefficients, function)
    a, b = sorted(_interval(x_start, x_end, function))
    half_derivative = np.polyadd(np.array([1.0, 0.0]), np.polymul(c, np.polyder(c)))
    x = np.array([a, b, *_real_roots_within(half_derivative, a, b)])
    y = np.polyval(c, x)
    d = np.hypot(x, y)
    lo, hi = int(np.argmin(d)), int(np.argmax(d))
    return DistanceRange(
        float(d[lo]), float(d[hi]), (float(x[lo]), float(y[lo])), (float(x[hi]), float(y[hi]))
    )


def sample_polynomial(
    coefficients: ArrayLike, x_start: float, x_end: float, samples: int
) -> FloatArray:
    """(samples, 2) points (x, polyval(coefficients, x)), x evenly spaced from x_start to
    x_end inclusive."""
    function = "sample_polynomial"
    c = _coefficients(coefficients, function)
    a, b = _interval(x_start, x_end, function)
    if not (isinstance(samples, numbers.Integral) and samples >= 2):
        raise bad_parameter("samples", function, "an integer >= 2", samples)
    x = np.linspace(a, b, int(samples))
    return np.stack([x, np.polyval(c, x)], axis=-1)
