"""Every run of W_kappa0 = {reachable, 1/kappa >= limit} on vertical lines ("columns").

See docs/methods/planar-parallel.md, "The well-conditioned workspace". A column is
sampled at the scan heights plus any extra heights given for it (where a neighbouring
column has a run, so that a thin run is followed from column to column). Between
samples the margin ``1/kappa - limit`` (1/kappa extended by 0 where unreachable) can
rise above 0 and fall back, or dip below it, without a sample showing it: every sampled
local maximum below 0 and every sampled local minimum above it is refined by a
golden-section search between its neighbours, and kept as a sample if it changes sign.
Every change of sign between consecutive samples is then refined to ~1e-12 (Illinois),
so that runs thinner than the scan's row spacing are found and measured exactly. A run
is missed only if two extrema of the margin lie between the same two samples.

Internal to :mod:`.kappa_region`; no input checks here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from worker.families.planar_parallel.kinematics.columns import ArchitectureBatch, illinois
from worker.families.planar_parallel.kinematics.maxima import golden_maximum
from worker.families.planar_parallel.kinematics.model import FloatArray

__all__ = ["ColumnRuns", "padded_rows", "scan_columns"]

IntArray = NDArray[np.intp]
#: Golden-section steps for a hidden extremum: a bracket of two row spacings shrinks
#: by 0.618 per step, to below 1e-8 of it.
GOLDEN_STEPS = 40


@dataclass(frozen=True)
class ColumnRuns:
    """The runs of W_kappa0 on C columns.

    x: (C,) abscissae, increasing. column, lower, upper: (K,) one entry per run: its
    column's index and its ends, sorted by column, then upwards; the runs of one column
    are disjoint. best, best_y: (C,) the largest margin ``1/kappa - limit`` met on each
    column (samples and refined extrema) and its height.
    """

    x: FloatArray
    column: IntArray
    lower: FloatArray
    upper: FloatArray
    best: FloatArray
    best_y: FloatArray

    @property
    def counts(self) -> IntArray:
        """(C,) the number of runs on each column."""
        return np.bincount(self.column, minlength=self.x.size)

    @property
    def lengths(self) -> FloatArray:
        """(C,) the total length of the runs on each column."""
        lengths = np.bincount(self.column, self.upper - self.lower, minlength=self.x.size)
        return np.asarray(lengths, dtype=np.float64)

    def lowest(self) -> tuple[FloatArray, FloatArray]:
        """(lower, upper), each (C,): the lowest run of each column, NaN where none."""
        lower, upper = np.full(self.x.size, np.nan), np.full(self.x.size, np.nan)
        columns, first = np.unique(self.column, return_index=True)
        lower[columns], upper[columns] = self.lower[first], self.upper[first]
        return lower, upper

    def runs_of(self, columns: IntArray) -> tuple[IntArray, FloatArray, FloatArray]:
        """(owner, lower, upper): the runs of the given columns, ``owner`` indexing
        ``columns``."""
        starts = np.searchsorted(self.column, columns, side="left")
        stops = np.searchsorted(self.column, columns, side="right")
        owner = np.repeat(np.arange(columns.size), stops - starts)
        index = np.concatenate([np.arange(a, b) for a, b in zip(starts, stops, strict=True)]
                               or [np.zeros(0, dtype=np.intp)])  # fmt: skip
        return owner, self.lower[index], self.upper[index]

    def merged(self, other: ColumnRuns) -> ColumnRuns:
        """These columns and ``other``'s, sorted by x; a column of ``other`` replaces one
        of these at the same abscissa."""
        keep = ~np.isin(self.x, other.x)
        x = np.concatenate([self.x[keep], other.x])
        order = np.argsort(x, kind="stable")
        rank = np.empty_like(order)
        rank[order] = np.arange(order.size)
        kept_runs = keep[self.column]
        old_index = np.cumsum(keep) - 1
        column = np.concatenate([rank[old_index[self.column[kept_runs]]],
                                 rank[keep.sum() + other.column]])  # fmt: skip
        lower = np.concatenate([self.lower[kept_runs], other.lower])
        upper = np.concatenate([self.upper[kept_runs], other.upper])
        runs = np.lexsort((lower, column))
        best = np.concatenate([self.best[keep], other.best])[order]
        best_y = np.concatenate([self.best_y[keep], other.best_y])[order]
        return ColumnRuns(x[order], column[runs], lower[runs], upper[runs], best, best_y)


def _brackets_of_hidden(
    batch: ArchitectureBatch, xs: FloatArray, heights: FloatArray, values: FloatArray
) -> tuple[IntArray, FloatArray, FloatArray, FloatArray, FloatArray, np.ndarray]:
    """Changes of sign between samples that no sample shows: a local maximum of the
    samples below 0 (or minimum above it), refined by golden-section search between its
    neighbours, that crosses 0 makes two crossings, one on each side of it. Only
    extrema within twice their larger step to a neighbouring sample of 0 are refined (a
    cone or a smooth peak between samples rises by less than one step). Returns
    (column, inside, outside, f_inside, f_outside, entering), each (2k,): the brackets
    of the crossings, and whether each enters W_kappa0 going up."""
    left, mid, right = values[:, :-2], values[:, 1:-1], values[:, 2:]
    unreachable = -batch.limit[0]
    step = np.maximum(np.abs(mid - left), np.abs(mid - right))
    rises = (mid >= left) & (mid >= right) & ((mid > left) | (mid > right))
    falls = (mid <= left) & (mid <= right) & ((mid < left) | (mid < right))
    peak = rises & (mid < 0.0) & (mid > unreachable) & (mid + 2.0 * step >= 0.0)
    dip = falls & (mid >= 0.0) & (mid - 2.0 * step < 0.0)
    rows, k = np.nonzero(peak | dip)
    empty = np.zeros(0)
    if rows.size == 0:
        return rows, empty, empty, empty, empty, np.zeros(0, dtype=bool)
    sense = np.where(peak[rows, k], 1.0, -1.0)
    column_x = xs[rows]
    enough = np.where(sense > 0.0, 0.0, np.nextafter(0.0, 1.0))  # a change of sign
    where, found = golden_maximum(lambda y: sense * batch.margin(column_x, y),
                                  heights[rows, k], heights[rows, k + 2], GOLDEN_STEPS,
                                  enough)  # fmt: skip
    value = sense * found
    flips = np.flatnonzero(np.where(sense > 0.0, value >= 0.0, value < 0.0))
    rows, k, where, value, up = rows[flips], k[flips], where[flips], value[flips], sense[flips]
    below = np.where(where < heights[rows, k + 1], k, k + 1)
    sides = (below, below + 1)
    column = np.concatenate([rows, rows])
    other_y = np.concatenate([heights[rows, side] for side in sides])
    other_v = np.concatenate([values[rows, side] for side in sides])
    at_y, at_v = np.concatenate([where, where]), np.concatenate([value, value])
    peak_side = np.concatenate([up > 0.0, up > 0.0])
    entering = np.concatenate([up > 0.0, up < 0.0])  # a peak enters below, a dip above
    inside = np.where(peak_side, at_y, other_y)
    outside = np.where(peak_side, other_y, at_y)
    f_inside = np.where(peak_side, at_v, other_v)
    f_outside = np.where(peak_side, other_v, at_v)
    return column, inside, outside, f_inside, f_outside, entering


def padded_rows(rows: IntArray, values: FloatArray, count: int) -> FloatArray:
    """(count, W) array holding ``values`` (k,) in the rows ``rows`` (k,), left to right in
    the order given, NaN elsewhere; W is the most values in one row."""
    per_row = np.bincount(rows, minlength=count)
    table = np.full((count, int(per_row.max()) if rows.size else 0), np.nan)
    order = np.argsort(rows, kind="stable")
    slot = np.empty_like(order)
    slot[order] = np.arange(rows.size) - np.searchsorted(rows[order], rows[order], side="left")
    table[rows, slot] = values
    return table


def scan_columns(
    batch: ArchitectureBatch,
    xs: FloatArray,
    heights: FloatArray,
    extra_heights: FloatArray | None = None,
) -> tuple[ColumnRuns, FloatArray]:
    """The runs of W_kappa0 on the columns ``xs`` (n,), for a batch of one architecture.

    heights: (R,) increasing scan heights shared by every column; extra_heights: (n, E)
    more heights per column (NaN for none). Returns the runs and the margins (n, R + E)
    at the sorted samples (for an ``extra_heights`` of None, the margins at
    ``heights``, (n, R)). A run open at the scan's end counts from there.
    """
    n = xs.size
    samples = np.broadcast_to(heights, (n, heights.size))
    if extra_heights is not None and extra_heights.shape[1]:
        extra = np.where(np.isnan(extra_heights), heights[-1], extra_heights)
        extra = np.clip(extra, heights[0], heights[-1])
        samples = np.sort(np.concatenate([samples, extra], axis=1), axis=1)
    values = batch.margin(xs[:, None], samples)
    best_index = np.argmax(values, axis=1)
    best = np.take_along_axis(values, best_index[:, None], 1)[:, 0]
    best_y = np.take_along_axis(samples, best_index[:, None], 1)[:, 0]

    feasible = values >= 0.0
    b, k = np.nonzero(feasible[:, 1:] != feasible[:, :-1])
    entering = feasible[b, k + 1]
    inside, outside = np.where(entering, k + 1, k), np.where(entering, k, k + 1)
    hidden = _brackets_of_hidden(batch, xs, samples, values)
    in_y = np.concatenate([samples[b, inside], hidden[1]])
    out_y = np.concatenate([samples[b, outside], hidden[2]])
    in_v = np.concatenate([values[b, inside], hidden[3]])
    out_v = np.concatenate([values[b, outside], hidden[4]])
    b = np.concatenate([b, hidden[0]])
    entering = np.concatenate([entering, hidden[5]])
    crossing = in_y
    if b.size:
        column_x = xs[b]
        crossing = illinois(lambda y: batch.margin(column_x, y), in_y, out_y, in_v, out_v)
    # the best point of each column: its best sample, or a refined hidden peak
    column = np.concatenate([np.arange(n), b])
    value = np.concatenate([best, in_v])
    ranked = np.lexsort((-value, column))
    order = ranked[np.unique(column[ranked], return_index=True)[1]]
    best, best_y = value[order], np.concatenate([best_y, in_y])[order]
    open_low, open_high = np.flatnonzero(feasible[:, 0]), np.flatnonzero(feasible[:, -1])
    start_column = np.concatenate([b[entering], open_low])
    start_y = np.concatenate([crossing[entering], samples[open_low, 0]])
    end_column = np.concatenate([b[~entering], open_high])
    end_y = np.concatenate([crossing[~entering], samples[open_high, -1]])
    starts, ends = np.lexsort((start_y, start_column)), np.lexsort((end_y, end_column))
    runs = ColumnRuns(xs.copy(), start_column[starts], start_y[starts], end_y[ends], best, best_y)
    return runs, values
