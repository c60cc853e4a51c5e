"""The largest rectangle W_lambda of aspect lambda = b/h, centred on x = 0, inside
W_kappa0 (docs/methods/planar-parallel.md, Fig. 6), solved for a batch of architectures at once.

Method. With W_kappa0 described column-wise by its lowest run [L(x), T(x)]
(:mod:`.columns`), the rectangle |x| <= w,
bottom <= y <= top lies inside iff ``top <= U(w) = min_{|x|<=w} T(x)`` and
``bottom >= D(w) = max_{|x|<=w} L(x)``. For a given h (so w = lambda h / 2) a centre
exists iff ``U(w) - D(w) >= h``; that is the paper's bisection on h with a search over
the centre H', solved exactly: U - D - 2 w / lambda decreases in w, so the largest w is
its one root. At the root the top edge touches the upper bound (P1, P2 of Fig. 6) and
the bottom corners the lower bound (Q1, Q2), and ``H' = -(U + D) / 2``.

Accuracy. T and L are exact (~1e-12) on the columns; each interior minimum of T (the
tangency points) and maximum of L is zoomed into (4 halvings with exact T or L at the
new abscissae) and finished by a parabola (error ~1e-10); the corner abscissa is solved
with T and L recomputed exactly at x = +-w (nested Illinois). So h and H' are good to
~1e-9, independent of the column count once the columns resolve W_kappa0's shape.
Every rectangle is then checked on its boundary (``boundary_samples`` points
per edge); if a feature narrower than a column spacing makes the check fail, the
rectangle is shrunk about its centre until it passes, and its message says so.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from worker.families.planar_parallel.kinematics.columns import (
    ArchitectureBatch,
    bottom_runs,
    crossing_near,
    illinois,
    subset,
)
from worker.families.planar_parallel.kinematics.model import FloatArray, is_mirror_symmetric

__all__ = ["RectangleArrays", "boundary_minimum", "solve_rectangles"]

CHECK_TOLERANCE = 1e-9  # on 1/kappa, for the boundary check
ZOOM_ROUNDS = 4


@dataclass(frozen=True)
class RectangleArrays:
    """Batched result, each (B,): found, half-width w, height h, centre y, boundary minimum
    of 1/kappa, and status codes: 0 ok, 1 no run on x = 0, 2 reaches the searched span's
    end, 3 shrunk to pass the boundary check."""

    found: np.ndarray
    w: FloatArray
    h: FloatArray
    centre: FloatArray
    boundary_min: FloatArray
    status: np.ndarray


@dataclass(frozen=True)
class _Bound:
    """One run end (T or L) on one side, in "f-space" f = sense * y, where the rectangle
    needs min f over |x| <= w (sense +1 for T, -1 for L). All (B, C): values: f on the
    columns (-inf where no run: nothing fits there); next_position / next_value: a
    refined interior minimum strictly inside (a[k-1], a[k]), filed under k (inf if none).
    """

    sense: float
    heights: FloatArray  # raw run ends in y (NaN where no run)
    values: FloatArray
    next_position: FloatArray
    next_value: FloatArray


def _zoom(
    batch: ArchitectureBatch, sign: float, xs: FloatArray, fs: FloatArray, sense: float
) -> tuple[FloatArray, FloatArray]:
    """Refine K local minima of f, each bracketed by 3 evenly spaced points (K, 3), by
    halving around the best point ZOOM_ROUNDS times, then a parabola: (position, value)."""
    pair = subset(batch, np.repeat(np.arange(batch.size), 2))
    for _ in range(ZOOM_ROUNDS):
        mids = 0.5 * (xs[:, :-1] + xs[:, 1:])
        ends = (sense * fs[:, :-1].ravel(), sense * fs[:, 1:].ravel())
        pad = (np.abs(fs[:, 1:] - fs[:, :-1]) + (xs[:, 1:] - xs[:, :-1])).ravel()
        y = crossing_near(pair, sign * mids.ravel(), ends, np.full(pad.shape, 0.5),
                          sense < 0, pad)  # fmt: skip
        five_x = np.stack([xs[:, 0], mids[:, 0], xs[:, 1], mids[:, 1], xs[:, 2]], axis=1)
        five_f = np.stack([fs[:, 0], sense * y[0::2], fs[:, 1], sense * y[1::2], fs[:, 2]], 1)
        best = np.clip(np.argmin(five_f, axis=1), 1, 3)[:, None] + np.arange(-1, 2)
        xs, fs = np.take_along_axis(five_x, best, 1), np.take_along_axis(five_f, best, 1)
    t0, t1, t2 = fs[:, 0], fs[:, 1], fs[:, 2]
    curvature = t0 - 2.0 * t1 + t2
    good = np.isfinite(curvature) & (curvature > 0.0)
    safe = np.where(good, curvature, 1.0)
    value = np.minimum(np.where(good, t1 - (t2 - t0) ** 2 / (8.0 * safe), t1), fs.min(axis=1))
    step = xs[:, 1] - xs[:, 0]
    return np.where(good, xs[:, 1] + step * (t0 - t2) / (2.0 * safe), xs[:, 1]), value


def _bound(
    batch: ArchitectureBatch, sign: float, a: FloatArray, heights: FloatArray, sense: float
) -> _Bound:
    """Column values of one run end plus its refined interior minima (in f-space)."""
    f = np.where(np.isnan(heights), -np.inf, sense * heights)  # no run: nothing fits
    next_position, next_value = np.full(f.shape, np.inf), np.full(f.shape, np.inf)
    t0, t1, t2 = f[:, :-2], f[:, 1:-1], f[:, 2:]
    with np.errstate(invalid="ignore"):
        local = np.isfinite(t0 + t1 + t2) & (t1 <= t0) & (t1 <= t2) & ((t1 < t0) | (t1 < t2))
    rows, cols = np.nonzero(local)
    values = f.copy()
    if rows.size:
        cols = cols + 1
        neighbours = cols[:, None] + np.arange(-1, 2)
        position, value = _zoom(subset(batch, rows), sign, a[rows[:, None], neighbours],
                                f[rows[:, None], neighbours], sense)  # fmt: skip
        k = np.where(position > a[rows, cols], cols + 1, cols)
        on_column = position == a[rows, k]
        np.minimum.at(values, (rows[on_column], k[on_column]), value[on_column])
        off = ~on_column
        np.minimum.at(next_value, (rows[off], k[off]), value[off])
        np.minimum.at(next_position, (rows[off], k[off]), position[off])
    return _Bound(sense, heights, values, next_position, next_value)


@dataclass(frozen=True)
class _Columns:
    """Column data: abscissae a (B, C) >= 0, per side (x = +a, and x = -a unless the mode
    is mirror-symmetric) the bounds T and L, and the envelopes U (running min of T over
    |x| <= a) and D (running max of L), each (B, C)."""

    a: FloatArray
    sides: tuple[float, ...]
    tops: list[_Bound]
    bottoms: list[_Bound]
    envelope_top: FloatArray
    envelope_bottom: FloatArray


def _column_data(
    batch: ArchitectureBatch,
    box: tuple[FloatArray, FloatArray, FloatArray],
    columns: int,
    rows: int,
) -> _Columns:
    half_span, y_low, y_high = box
    a = half_span[:, None] * np.linspace(0.0, 1.0, columns)
    sides = (1.0,) if is_mirror_symmetric(batch.template, batch.mode) else (1.0, -1.0)
    runs = [bottom_runs(batch, side * a, y_low, y_high, rows) for side in sides]
    tops = [_bound(batch, side, a, up, 1.0) for side, (_, up) in zip(sides, runs, strict=True)]
    bottoms = [_bound(batch, side, a, lo, -1.0)
               for side, (lo, _) in zip(sides, runs, strict=True)]  # fmt: skip

    def envelope(bounds: list[_Bound]) -> FloatArray:
        merged = np.min([np.minimum(b.values, b.next_value) for b in bounds], axis=0)
        return np.asarray(bounds[0].sense * np.minimum.accumulate(merged, axis=1))

    return _Columns(a, sides, tops, bottoms, envelope(tops), envelope(bottoms))


def _corner_solver(
    batch: ArchitectureBatch, cols: _Columns, j: np.ndarray
) -> tuple[FloatArray, FloatArray, Callable[[FloatArray], tuple[FloatArray, FloatArray]]]:
    """(a_lo, a_hi, edges): the column gap [a_j, a_j+1] holding the corner abscissa w, and
    edges(w) -> (top, bottom) = (U(w), D(w)) with T, L recomputed exactly at x = +-w."""
    r = np.arange(batch.size)
    a_lo, a_hi = cols.a[r, j], cols.a[r, j + 1]
    gap = a_hi - a_lo

    def edges(w: FloatArray) -> tuple[FloatArray, FloatArray]:
        fraction = (w - a_lo) / np.where(gap > 0, gap, 1.0)
        found = []
        for envelope, bounds in ((cols.envelope_top, cols.tops), (cols.envelope_bottom,
                                                                   cols.bottoms)):  # fmt: skip
            f = bounds[0].sense * envelope[r, j]
            for side, bound in zip(cols.sides, bounds, strict=True):
                inside_gap = bound.next_position[r, j + 1] <= w
                f = np.minimum(f, np.where(inside_gap, bound.next_value[r, j + 1], np.inf))
                ends = (bound.heights[r, j], bound.heights[r, j + 1])
                pad = 0.5 * np.abs(ends[1] - ends[0]) + gap
                y = crossing_near(batch, side * w, ends, fraction, bound.sense < 0,
                                  np.nan_to_num(pad))  # fmt: skip
                f = np.minimum(f, bound.sense * y)
            found.append(bounds[0].sense * f)
        return found[0], found[1]

    return a_lo, a_hi, edges


def solve_rectangles(
    batch: ArchitectureBatch,
    aspect: float,
    box: tuple[FloatArray, FloatArray, FloatArray],
    columns: int,
    rows: int,
    boundary_samples: int,
) -> RectangleArrays:
    """Largest centred rectangle of aspect b/h = ``aspect`` in each W_kappa0 of the batch.

    box: (X, y_low, y_high), each (B,), the search range (|x| <= X); columns: abscissae
    in [0, X] (both signs are searched unless the working mode is mirror-symmetric);
    rows: scan samples per column; boundary_samples: check points per edge.
    """
    cols = _column_data(batch, box, columns, rows)
    with np.errstate(invalid="ignore"):
        slack = cols.envelope_top - cols.envelope_bottom - 2.0 * cols.a / aspect
    feasible_count = np.sum(slack >= 0.0, axis=1)
    found = (feasible_count > 0) & (box[0] > 0.0)
    status = np.where(found, np.where(feasible_count == columns, 2, 0), 1)
    a_lo, a_hi, edges = _corner_solver(batch, cols, np.clip(feasible_count - 1, 0, columns - 2))

    def excess(w: FloatArray, which: np.ndarray) -> FloatArray:
        full = a_lo.copy()
        full[which] = w
        top, bottom = edges(full)
        with np.errstate(invalid="ignore"):
            value = top - bottom - 2.0 * full / aspect
        return np.asarray(np.nan_to_num(value, nan=-1.0, neginf=-1.0)[which], dtype=np.float64)

    everyone = np.arange(batch.size)
    f_lo, f_hi = excess(a_lo, everyone), excess(a_hi, everyone)
    w = np.where(f_hi >= 0.0, a_hi, a_lo)
    bracketed = np.flatnonzero(found & (f_lo >= 0.0) & (f_hi < 0.0))
    if bracketed.size:
        w[bracketed] = illinois(
            lambda v: excess(v, bracketed), a_lo[bracketed], a_hi[bracketed],
            f_lo[bracketed], f_hi[bracketed], iterations=40, xtol=1e-11,
        )  # fmt: skip
    top, bottom = edges(w)
    with np.errstate(invalid="ignore"):
        h = np.minimum(2.0 * w / aspect, top - bottom)
    found &= np.isfinite(h) & (h > 0.0)
    h = np.where(found, h, np.nan)
    with np.errstate(invalid="ignore"):
        centre = np.where(found, 0.5 * (top + bottom), np.nan)
    return _checked(batch, aspect, found, h, centre, status, boundary_samples)


def boundary_minimum(
    batch: ArchitectureBatch, w: FloatArray, bottom: FloatArray, top: FloatArray, samples: int
) -> FloatArray:
    """Min of 1/kappa (0 where unreachable) over ``samples`` points on each edge, (B,)."""
    t = np.linspace(0.0, 1.0, samples)
    xs = (-w)[:, None] + (2.0 * w)[:, None] * t
    ys = bottom[:, None] + (top - bottom)[:, None] * t
    ones = np.ones_like(t)
    x = np.concatenate([xs, xs, -w[:, None] * ones, w[:, None] * ones], axis=1)
    y = np.concatenate([top[:, None] * ones, bottom[:, None] * ones, ys, ys], axis=1)
    return np.asarray(np.min(batch.margin(x, y), axis=1) + batch.limit, dtype=np.float64)


def _checked(
    batch: ArchitectureBatch,
    aspect: float,
    found: np.ndarray,
    h: FloatArray,
    centre: FloatArray,
    status: np.ndarray,
    samples: int,
) -> RectangleArrays:
    """Check each rectangle on its boundary; shrink failures about the centre until they pass."""
    height = np.where(found, h, 0.0)
    middle = np.where(found, centre, 0.0)

    def minimum(scale: FloatArray) -> FloatArray:
        hh = height * scale
        return boundary_minimum(batch, aspect * hh / 2.0, middle - hh / 2.0, middle + hh / 2.0,
                                samples)  # fmt: skip

    scale = np.ones_like(height)
    full = minimum(scale)
    failed = found & (full < batch.limit - CHECK_TOLERANCE)
    if np.any(failed):
        low, high = np.zeros_like(height), np.ones_like(height)
        for _ in range(50):
            mid = 0.5 * (low + high)
            passes = minimum(mid) >= batch.limit - CHECK_TOLERANCE
            low, high = np.where(passes, mid, low), np.where(passes, high, mid)
        scale = np.where(failed, low, 1.0)
        full = minimum(scale)
    new_h = np.where(found, height * scale, np.nan)
    ok = found & (new_h > 0.0)
    return RectangleArrays(
        ok,
        np.where(ok, aspect * new_h / 2.0, np.nan),
        np.where(ok, new_h, np.nan),
        np.where(ok, centre, np.nan),
        np.where(ok, full, np.nan),
        np.where(failed, 3, status),
    )
