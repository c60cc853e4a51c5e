"""The local maxima of 1/kappa of one robot, for W_kappa0 (docs/methods/planar-parallel.md,
"The well-conditioned workspace").

1/kappa is continuous where the robot can reach and tends to 0 on a smooth stretch of
the reach boundary (one chain folds or stretches, so one v_i -> 0), so every component
of W_kappa0 holds a local maximum inside the reach, or touches a corner of the reach
where two chains fold or stretch at once: there 1/kappa tends to a value that depends
on the direction of approach (up to 1 at the paper's right-triangle point, eq 9). The
maxima are climbed by a Nelder-Mead search batched over its starts: the local maxima
of a scan (each node at least as high as its eight neighbours and within reach of the
limit by its largest step to them) and, for the proximal arm, the intersections of the
four reach circles (and the pivots for telescopic legs or l1 = l2), entered along the
best of 720 directions. A climb that ends just below the limit is finished by a
search along lines (:func:`profile_maxima`), sure where Nelder-Mead crawls.

Internal to :mod:`.kappa_region`; no input checks here.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from worker.families.planar_parallel.kinematics.model import Architecture, FloatArray

__all__ = ["golden_maximum", "local_maxima", "reach_corners"]

#: Scan maxima climbed at most (the highest by value plus largest step to a neighbour).
SCAN_STARTS = 24
CORNER_DIRECTIONS = 720
#: A corner is entered this far (relative to the search box's size).
CORNER_RADIUS = 1e-7
NELDER_MEAD_STEPS = 150
#: Nelder-Mead stops when every simplex is smaller than this (relative to the box), or
#: its values differ by at most VALUE_TOLERANCE.
SIMPLEX_TOLERANCE = 1e-13
VALUE_TOLERANCE = 1e-10
#: Climbs that end this close below the limit are finished by a profile search.
NEAR_LIMIT = 1e-4
#: The profile search: levels, abscissae per level (each level narrows the range by 4),
#: golden-section steps per abscissa.
PROFILE_LEVELS = 16
PROFILE_POINTS = 17
PROFILE_STEPS = 22
INVERSE_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def golden_maximum(
    fun: Callable[[FloatArray], FloatArray],
    a: FloatArray,
    b: FloatArray,
    steps: int,
    enough: FloatArray | float = np.inf,
) -> tuple[FloatArray, FloatArray]:
    """Elementwise maximum of ``fun`` on [a, b] (any shape) by golden-section search:
    ``steps`` narrowings, fewer once every element's best value reaches ``enough``.
    Returns (position, value) of the best point evaluated (so a maximum next to a jump,
    such as a corner of the reach, is approached from the side where the values are)."""
    c, d = b - INVERSE_GOLDEN * (b - a), a + INVERSE_GOLDEN * (b - a)
    fc, fd = fun(c), fun(d)
    best, best_f = np.where(fc >= fd, c, d), np.maximum(fc, fd)
    for _ in range(steps):
        if np.all(best_f >= enough):
            break
        left = fc >= fd  # the maximum is in [a, d]
        a, b = np.where(left, a, c), np.where(left, d, b)
        new = np.where(left, b - INVERSE_GOLDEN * (b - a), a + INVERSE_GOLDEN * (b - a))
        f_new = fun(new)
        c, fc, d, fd = (np.where(left, new, d), np.where(left, f_new, fd),
                        np.where(left, c, new), np.where(left, fc, f_new))  # fmt: skip
        better = f_new > best_f
        best, best_f = np.where(better, new, best), np.where(better, f_new, best_f)
    return best, best_f


def reach_corners(arch: Architecture) -> FloatArray:
    """(k, 2) points where 1/kappa can keep a value at the reach boundary: for the
    proximal arm the intersections of chain 1's circles |p_1| = |l1 - l2|, l1 + l2 with
    chain 2's, plus the pivots (+-e, 0) when l1 = l2; for telescopic legs the pivots;
    none for linear drives."""
    e = arch.e
    pivots = [(e, 0.0), (-e, 0.0)]
    if arch.actuation == "telescopic-leg":
        return np.array(pivots)
    if arch.actuation != "proximal-arm" or e <= 0.0:
        return np.zeros((0, 2))
    radii = (abs(arch.l1 - arch.l2), arch.l1 + arch.l2)
    points = pivots if arch.l1 == arch.l2 else []
    for first in radii:  # chain 1's circle, centre (e, 0)
        for second in radii:  # chain 2's circle, centre (-e, 0)
            if not abs(first - second) <= 2.0 * e <= first + second:
                continue  # the circles do not meet
            x = (second - first) * (second + first) / (4.0 * e)
            height2 = first * first - (x - e) ** 2
            if height2 >= 0.0:
                height = math.sqrt(height2)
                points += [(x, height), (x, -height)]
    return np.array(points).reshape(-1, 2)


def _scan_starts(
    xs: FloatArray, heights: FloatArray, margins: FloatArray, unreachable: float
) -> tuple[FloatArray, FloatArray]:
    """(starts (k, 2), steps (k, 2)): the best node of the scan margins (C, R) on columns
    xs (C,) by heights (R,), then its local maxima below 0 that may reach 0 between nodes
    (within twice their largest step to a neighbour)."""
    padded = np.pad(margins, 1, constant_values=-np.inf)
    count_x, count_y = margins.shape
    highest = np.full(margins.shape, -np.inf)
    lowest = np.full(margins.shape, np.inf)
    rise = np.zeros(margins.shape)
    for i in range(3):
        for j in range(3):
            if (i, j) != (1, 1):
                around = padded[i : i + count_x, j : j + count_y]
                np.maximum(highest, around, out=highest)
                np.minimum(lowest, around, out=lowest)
                step = np.where(around > unreachable, margins - around, 0.0)
                np.maximum(rise, np.abs(step), out=rise)
    peak = (margins >= highest) & (margins > lowest)
    candidate = peak & (margins > unreachable) & (margins < 0.0) & (margins + 2.0 * rise >= 0.0)
    cols, rows = np.nonzero(candidate)
    order = np.argsort(-(margins + rise)[cols, rows], kind="stable")[:SCAN_STARTS]
    best = np.unravel_index(int(np.argmax(margins)), margins.shape)
    cols = np.concatenate([[best[0]], cols[order]])
    rows = np.concatenate([[best[1]], rows[order]])
    dx = (xs[-1] - xs[0]) / max(xs.size - 1, 1)
    dy = (heights[-1] - heights[0]) / max(heights.size - 1, 1)
    steps = np.broadcast_to([0.5 * dx, 0.5 * dy], (cols.size, 2))
    return np.stack([xs[cols], heights[rows]], axis=-1), np.array(steps)


def _corner_starts(
    fun: Callable[[FloatArray, FloatArray], FloatArray], corners: FloatArray, radius: float
) -> FloatArray:
    """(k, 2): each corner entered along the direction of largest 1/kappa at ``radius``."""
    angles = np.linspace(0.0, 2.0 * math.pi, CORNER_DIRECTIONS, endpoint=False)
    ring_x = corners[:, :1] + radius * np.cos(angles)
    ring_y = corners[:, 1:] + radius * np.sin(angles)
    best = np.argmax(fun(ring_x, ring_y), axis=1)[:, None]
    return np.concatenate([np.take_along_axis(ring_x, best, 1),
                           np.take_along_axis(ring_y, best, 1)], axis=1)  # fmt: skip


def nelder_mead_maxima(
    fun: Callable[[FloatArray, FloatArray], FloatArray],
    starts: FloatArray,
    steps: FloatArray,
    tolerance: float,
    enough: FloatArray,
) -> tuple[FloatArray, FloatArray]:
    """Local maxima of ``fun(x, y)`` (elementwise) from each of k ``starts`` (k, 2), the
    first simplex spanning ``steps`` (k, 2): (points (k, 2), values (k,)). A search
    stops when its simplex is smaller than ``tolerance``, its values agree to
    VALUE_TOLERANCE or its best value reaches ``enough`` (k,). Standard coefficients
    (reflect 1, expand 2, contract and shrink 1/2); all trial points of a step are
    evaluated in one call."""
    offsets = np.stack([np.zeros_like(steps), steps * [1.0, 0.0], steps * [0.0, 1.0]], axis=1)
    simplex = starts[:, None, :] + offsets  # (k, 3, 2)
    values = fun(simplex[..., 0], simplex[..., 1])
    for _ in range(NELDER_MEAD_STEPS):
        order = np.argsort(-values, axis=1)
        simplex = np.take_along_axis(simplex, order[..., None], 1)
        values = np.take_along_axis(values, order, 1)
        size = np.max(np.abs(simplex[:, 1:] - simplex[:, :1]), axis=(1, 2))
        active = (size > tolerance) & (values[:, 0] - values[:, 2] > VALUE_TOLERANCE)
        active &= values[:, 0] < enough
        if not active.any():
            break
        best, worst = simplex[:, 0], simplex[:, 2]
        centroid = 0.5 * (best + simplex[:, 1])
        pull = centroid - worst
        trial = np.stack([centroid + pull, centroid + 2.0 * pull, centroid + 0.5 * pull,
                          centroid - 0.5 * pull, 0.5 * (best + simplex[:, 1]),
                          0.5 * (best + worst)], axis=1)  # fmt: skip
        tried = fun(trial[..., 0], trial[..., 1])
        reflected, expanded, out, inner = (tried[:, i] for i in range(4))
        top, middle, bottom = values[:, 0], values[:, 1], values[:, 2]
        expand = (reflected > top) & (expanded > reflected)
        reflect = ~expand & (reflected > middle)
        contract_out = ~(reflected > middle) & (reflected > bottom) & (out >= reflected)
        contract_in = ~(reflected > bottom) & (inner > bottom)
        choice = np.select([expand, reflect, contract_out, contract_in], [1, 0, 2, 3], -1)
        shrink = active & (choice < 0)
        move = active & (choice >= 0)
        pick = np.clip(choice, 0, 3)[:, None]
        simplex[move, 2] = np.take_along_axis(trial, pick[..., None], 1)[move, 0]
        values[move, 2] = np.take_along_axis(tried, pick, 1)[move, 0]
        simplex[shrink, 1:] = trial[shrink, 4:]
        values[shrink, 1:] = tried[shrink, 4:]
    best_vertex = np.argmax(values, axis=1)
    points = simplex[np.arange(starts.shape[0]), best_vertex]
    return points, values[np.arange(starts.shape[0]), best_vertex]


def profile_maxima(
    fun: Callable[[FloatArray, FloatArray], FloatArray],
    starts: FloatArray,
    half_widths: FloatArray,
) -> tuple[FloatArray, FloatArray]:
    """Local maxima of ``fun(x, y)`` in the boxes ``starts`` (k, 2) +- ``half_widths``
    (k, 2), by the largest value along lines: PROFILE_POINTS abscissae across the box,
    the best height on each by golden-section search, the box narrowed by 4 around the
    best and re-centred, PROFILE_LEVELS times; the same with x and y swapped; the better
    of the two. Slower than Nelder-Mead, but sure on a sharp crease (the nearly
    degenerate cones of 1/kappa at an isotropic point) and at a corner of the reach.
    Returns (points (k, 2), values (k,))."""
    t = np.linspace(-1.0, 1.0, PROFILE_POINTS)
    results = []
    for outer in (0, 1):
        inner = 1 - outer
        centre, half = starts.copy(), half_widths.copy()
        value = np.full(starts.shape[0], -np.inf)
        rows = np.arange(starts.shape[0])
        for _ in range(PROFILE_LEVELS):
            u = centre[:, outer, None] + half[:, outer, None] * t
            low = np.broadcast_to((centre[:, inner] - half[:, inner])[:, None], u.shape)
            high = np.broadcast_to((centre[:, inner] + half[:, inner])[:, None], u.shape)

            def along(v: FloatArray, u: FloatArray = u, outer: int = outer) -> FloatArray:
                return fun(u, v) if outer == 0 else fun(v, u)

            v, f = golden_maximum(along, low, high, PROFILE_STEPS)
            best = np.argmax(f, axis=1)
            around = np.clip(best[:, None] + np.array([-1, 1]), 0, PROFILE_POINTS - 1)
            drift = np.max(np.abs(v[rows[:, None], around] - v[rows, best][:, None]), axis=1)
            centre[:, outer], centre[:, inner] = u[rows, best], v[rows, best]
            value = f[rows, best]
            half[:, outer] *= 4.0 / (PROFILE_POINTS - 1)
            half[:, inner] = np.maximum(2.0 * drift, 0.25 * half[:, inner])
        results.append((centre, value))
    (first, first_value), (second, second_value) = results
    better = second_value > first_value
    return np.where(better[:, None], second, first), np.where(better, second_value, first_value)


def local_maxima(
    fun: Callable[[FloatArray, FloatArray], FloatArray],
    arch: Architecture,
    scan: tuple[FloatArray, FloatArray, FloatArray],
    limit: float,
) -> tuple[FloatArray, FloatArray]:
    """Local maxima of 1/kappa, ``fun(x, y)`` (extended by 0 where unreachable), climbed
    from the scan's best node, its maxima below the limit and the reach's corners:
    (points (k, 2), values (k,)), the largest first. A climb other than the best node's
    stops once it reaches the limit (it has found W_kappa0 there). scan: (xs (C,),
    heights (R,), margins (C, R) = 1/kappa - limit)."""
    xs, heights, margins = scan
    size = math.hypot(xs[-1] - xs[0], heights[-1] - heights[0])
    starts, steps = _scan_starts(xs, heights, margins, -limit)
    corners = reach_corners(arch)
    if corners.size:
        radius = CORNER_RADIUS * size
        corner_starts = _corner_starts(fun, corners, radius)
        starts = np.concatenate([starts, corner_starts])
        steps = np.concatenate([steps, np.full(corner_starts.shape, radius)])
    enough = np.full(starts.shape[0], limit)
    enough[0] = np.inf  # the best node is climbed all the way: the largest 1/kappa
    points, values = nelder_mead_maxima(fun, starts, steps, SIMPLEX_TOLERANCE * size, enough)
    near = np.flatnonzero((values < limit) & (values >= limit - NEAR_LIMIT))
    if near.size:
        widths = np.maximum(np.abs(points[near] - starts[near]), 2.0 * steps[near])
        polished, better = profile_maxima(fun, points[near], widths)
        improved = better > values[near]
        points[near[improved]], values[near[improved]] = polished[improved], better[improved]
    order = np.argsort(-values, kind="stable")
    return points[order], values[order]
