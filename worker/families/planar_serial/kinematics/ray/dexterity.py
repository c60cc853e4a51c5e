"""Exact joint-limited d_z along a ray from the base: its range and its d_z = 1 radii.

Under joint limits d_z(r) along the ray p = r u(theta) is piecewise analytic; its pieces
end at the breakpoints of :mod:`.events`, and on a piece the feasibility of each
sub-arc between the event roots is fixed (docs/methods/planar-serial.md, "Joint limits
along a ray").  So a piece has d_z = 1 throughout iff every sub-arc is feasible at its
middle, and d_z(r) on it follows the roots, which bounds it on any interval
(:mod:`.bounds`).  :func:`ray_dexterity` evaluates d_z at every breakpoint and every
piece's middle, then bisects each interval whose bounds leave room for a value more
than :data:`RANGE_TOL` beyond the best found (branch and bound), so the least and
largest d_z are certified to that tolerance.  Every d_z value is
:func:`..limited_exact.exact_limited_orientation_dexterity` at that distance.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from worker.common.parameter_errors import bad_parameter
from worker.families.planar_serial.kinematics.inputs import (
    BoolArray,
    FloatArray,
    Links,
    checked_joint_limits,
    checked_links,
)
from worker.families.planar_serial.kinematics.joint_limits import feasible_orientations
from worker.families.planar_serial.kinematics.limited_exact import (
    exact_limited_orientation_dexterity,
)
from worker.families.planar_serial.kinematics.ray.bounds import dexterity_bounds
from worker.families.planar_serial.kinematics.ray.events import (
    ConditionPolynomials,
    RayConditions,
    condition_polynomials,
    ray_breakpoints,
    ray_conditions,
    root_angles,
)

__all__ = ["RANGE_TOL", "RayDexterity", "RayRange", "ray_dexterity"]

#: The least and largest d_z along a ray are certified to within this, except where
#: d_z moves like the square root of the distance (at a tangency): there a distance
#: rounded to 1e-16 moves d_z by ~1e-8 and the bounds close no further.
RANGE_TOL = 1e-10
#: Most d_z evaluations the search of one interval makes; past it the bounds found so
#: far are reported as they are (``d_z_min_bound``, ``d_z_max_bound``).
MAX_EVALUATIONS = 100_000
#: Intervals narrower than this (a fraction of l1 + l2 + l3) are not bisected further.
_MIN_WIDTH = 1e-13
TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class RayRange:
    """The least and largest d_z over [d_from, d_to] along a ray (distances in the
    links' unit).  ``d_z_min`` is d_z at ``d_z_min_at`` (the nearest such distance
    found), ``d_z_max`` at ``d_z_max_at``; ``d_z_min_bound <= d_z <= d_z_max_bound``
    holds on the whole interval, each bound within :data:`RANGE_TOL` of its value (see
    there for the exception; or the search ran out of :data:`MAX_EVALUATIONS`)."""

    d_z_min: float
    d_z_min_at: float
    d_z_max: float
    d_z_max_at: float
    d_z_min_bound: float
    d_z_max_bound: float


@dataclass(frozen=True)
class RayDexterity:
    """d_z along one ray: its range over each interval, and the closed distance
    intervals ((lo, hi), ...) where d_z = 1."""

    ranges: tuple[RayRange, ...]
    bands: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class _Ray:
    """One ray: the links, their sum and the links over it, limits (rad), direction,
    and the conditions and their polynomials in lengths over the sum."""

    links: Links
    total: float
    unit: Links
    limits: FloatArray
    direction: tuple[float, float]
    conditions: RayConditions
    polynomials: ConditionPolynomials

    def d_z(self, distance: FloatArray) -> FloatArray:
        """Exact d_z at distances (n,) in the links' unit."""
        points = np.stack([distance * self.direction[0], distance * self.direction[1]], -1)
        return exact_limited_orientation_dexterity(self.links, points, self.limits)


@dataclass(frozen=True)
class _Pieces:
    """Breakpoints (P + 1,) scaled and in the links' unit (the ends exactly d_from and
    d_to), each root's c on each piece (P, C, 2), every sub-arc feasible (P,)."""

    edges: FloatArray
    distances: FloatArray
    coefficient: FloatArray
    full: BoolArray


def _ray(links: ArrayLike, joint_limits: ArrayLike, angle: float, edges: Sequence[float]) -> _Ray:
    function = "ray_dexterity"
    lengths = checked_links(links, function)
    limits = checked_joint_limits(joint_limits, function)
    if not math.isfinite(angle):
        raise bad_parameter("angle", function, "a finite angle in radians", angle)
    ends = np.asarray(edges, dtype=float)
    if not (ends.ndim == 1 and ends.size >= 2 and np.all(np.isfinite(ends))
            and ends[0] >= 0.0 and np.all(np.diff(ends) >= 0.0)):  # fmt: skip
        raise bad_parameter("edges", function, "at least two distances 0 <= e0 <= e1 <= ...", edges)
    total = math.fsum(lengths)
    scaled = (lengths[0] / total, lengths[1] / total, lengths[2] / total)
    conditions = ray_conditions(scaled, limits, angle)
    direction = (math.cos(angle), math.sin(angle))
    polynomials = condition_polynomials(conditions)
    return _Ray(lengths, total, scaled, limits, direction, conditions, polynomials)


def _pieces(ray: _Ray, edges: FloatArray) -> _Pieces:
    """The pieces from edges[0] to edges[-1] (every edge a breakpoint) and the
    arrangement of the roots on each: c of a root is the feasibility of the sub-arc
    before it minus that of the one after it (phi increasing), so that 2 pi d_z moves
    by sum c dphi."""
    scaled = ray_breakpoints(ray.conditions, ray.polynomials, edges / ray.total)
    distances = scaled * ray.total
    distances[np.searchsorted(scaled, np.unique(edges) / ray.total)] = np.unique(edges)
    middle = 0.5 * (scaled[:-1] + scaled[1:])
    count, columns = middle.size, 2 * ray.conditions.count
    centre, half, exists = root_angles(ray.conditions, middle)
    roots = np.stack([centre - half, centre + half], axis=-1).reshape(count, columns)
    roots = np.where(np.repeat(exists, 2, axis=1), np.mod(roots, TWO_PI), np.nan)
    order = np.argsort(roots, axis=1)  # NaN (no root) last
    ordered = np.take_along_axis(roots, order, axis=1)
    valid = ~np.isnan(ordered)
    n = valid.sum(axis=1, keepdims=True)
    j = np.arange(max(columns, 1))[None, :]
    following = np.where(j + 1 < n, j + 1, 0)
    after = np.take_along_axis(ordered, following, axis=1) + np.where(j + 1 < n, 0.0, TWO_PI)
    # one test per sub-arc, at its middle; a piece without roots is tested at phi = 0
    test = np.where(n > 0, valid, j == 0)
    phi = np.where(n > 0, 0.5 * (ordered + after), 0.0)
    rows, cols = np.nonzero(test)
    feasible = np.zeros(test.shape, dtype=bool)
    feasible[rows, cols] = feasible_orientations(
        ray.unit, ray.limits, middle[rows] * ray.direction[0], middle[rows] * ray.direction[1],
        phi[rows, cols],
    )  # fmt: skip
    preceding = np.where(j >= 1, j - 1, np.maximum(n - 1, 0))
    change = np.take_along_axis(feasible, preceding, axis=1).astype(float) - feasible
    coefficient = np.zeros((count, max(columns, 1)))
    np.put_along_axis(coefficient, order, np.where(valid, change, 0.0), axis=1)
    full = np.all(feasible | ~test, axis=1)
    shaped = coefficient[:, :columns].reshape(count, columns // 2, 2)
    return _Pieces(scaled, distances, shaped, full)


def _range(ray: _Ray, pieces: _Pieces, first: int, last: int, found: FloatArray) -> RayRange:
    """Branch and bound over pieces first..last - 1, given d_z at their edges and
    middles (``found``: (2 P + 1,), edges then middles)."""
    edge_count = pieces.edges.size
    index = np.arange(first, last)
    middle = 0.5 * (pieces.edges[index] + pieces.edges[index + 1])
    at = np.concatenate([pieces.distances[first : last + 1], middle * ray.total])
    values = np.concatenate([found[first : last + 1], found[edge_count + index]])
    middle_dz = found[edge_count + index]
    # each piece as two halves anchored at its middle (d_z at a breakpoint need not
    # continue the piece's formula; it counts as a value found, not as an anchor)
    x = np.concatenate([pieces.edges[index], middle])
    y = np.concatenate([middle, pieces.edges[index + 1]])
    piece, anchor = np.concatenate([index, index]), np.concatenate([middle_dz, middle_dz])
    left = np.arange(2 * index.size) >= index.size
    floor, ceiling = np.inf, -np.inf
    while x.size:
        lower, upper = dexterity_bounds(
            ray.conditions, ray.polynomials, pieces.coefficient[piece], x, y, anchor, left
        )
        best_min, best_max = values.min(), values.max()
        split = (lower < best_min - RANGE_TOL) | (upper > best_max + RANGE_TOL)
        split &= y - x > _MIN_WIDTH
        floor = min(floor, lower[~split].min(initial=np.inf))
        ceiling = max(ceiling, upper[~split].max(initial=-np.inf))
        if values.size + split.sum() > MAX_EVALUATIONS:  # out of budget: bounds as they are
            floor = min(floor, lower[split].min(initial=np.inf))
            ceiling = max(ceiling, upper[split].max(initial=-np.inf))
            break
        x, y, piece, anchor, left = x[split], y[split], piece[split], anchor[split], left[split]
        if not x.size:
            break
        middle = 0.5 * (x + y)
        middle_dz = ray.d_z(middle * ray.total)
        at = np.concatenate([at, middle * ray.total])
        values = np.concatenate([values, middle_dz])
        # [x, middle] keeps its anchor if that was x; [middle, y] is anchored at middle
        first_anchor = np.where(left, anchor, middle_dz)
        x, y = np.concatenate([x, middle]), np.concatenate([middle, y])
        piece, anchor = np.concatenate([piece, piece]), np.concatenate([first_anchor, middle_dz])
        left = np.concatenate([left, np.ones(middle.size, dtype=bool)])
    least, most = float(values.min()), float(values.max())
    return RayRange(
        d_z_min=least,
        d_z_min_at=float(at[values == least].min()),
        d_z_max=most,
        d_z_max_at=float(at[values == most].min()),
        d_z_min_bound=min(floor, least),
        d_z_max_bound=max(ceiling, most),
    )


def _bands(pieces: _Pieces) -> tuple[tuple[float, float], ...]:
    """Closed intervals of full dexterity: the full pieces, touching ones merged."""
    bands: list[tuple[float, float]] = []
    starts, stops = pieces.distances[:-1].tolist(), pieces.distances[1:].tolist()
    ends = zip(starts, stops, pieces.full.tolist(), strict=True)
    for lo, hi, full in ends:
        if not full:
            continue
        if bands and bands[-1][1] == lo:
            bands[-1] = (bands[-1][0], hi)
        else:
            bands.append((lo, hi))
    return tuple(bands)


def ray_dexterity(
    links: ArrayLike, joint_limits: ArrayLike, angle: float, edges: Sequence[float]
) -> RayDexterity:
    """Exact joint-limited d_z along the ray at ``angle`` over consecutive intervals.

    links: (3,); joint_limits: (3, 2) rad as in
    :func:`..limited_exact.exact_limited_orientation_dexterity`; angle: rad; edges:
    distances 0 <= e0 <= e1 <= ... in the links' unit.  Returns the range of d_z over
    each [e_i, e_i+1] (module docstring) and the closed intervals of [e0, e_last] where
    d_z = 1: a piece has d_z = 1 throughout iff every sub-arc is feasible at its middle;
    touching pieces are merged.  A single distance where d_z only touches 1 (a band of
    zero width) is left out: whether rounding puts d_z there at 1 or a hair below is
    chance.
    """
    ray = _ray(links, joint_limits, angle, edges)
    ends = np.asarray(edges, dtype=float)
    pieces = _pieces(ray, ends)
    middle = 0.5 * (pieces.edges[:-1] + pieces.edges[1:])
    found = ray.d_z(np.concatenate([pieces.distances, middle * ray.total]))
    bounds = np.searchsorted(pieces.distances, ends)
    ranges = tuple(
        _range(ray, pieces, int(first), int(last), found)
        for first, last in itertools.pairwise(bounds.tolist())
    )
    return RayDexterity(ranges, _bands(pieces))
