"""W_kappa0 = {reachable points of the working mode with 1/kappa >= limit}, its area and
outline (Huang et al. 2004 §III-C; docs/methods/planar-parallel.md, "The
well-conditioned workspace"). Re-exported by
:mod:`worker.families.planar_parallel.kinematics`; conventions as there.

W_kappa0 is found column by column (the paper's "1-D root search" along vertical lines,
:mod:`.column_runs`): every run of every column, thin ones included. The largest 1/kappa
is climbed from the scan's maxima and the reach's corners (:mod:`.maxima`), and a column
goes through each maximum above the limit, so a set narrower than the column spacing
is met. Columns are then added where the trapezoid rule over them is not yet good to
1e-3 of the area (or of 1e-6 of the reachable area, if that is larger): halfway between
two columns whose run counts differ (where a piece of the set ends, splits or starts)
and where the run lengths bend sharply (near the ends of a piece).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from worker.common.parameter_errors import bad_parameter
from worker.families.planar_parallel.kinematics.column_runs import (
    ColumnRuns,
    padded_rows,
    scan_columns,
)
from worker.families.planar_parallel.kinematics.columns import (
    ArchitectureBatch,
    search_box,
    single,
)
from worker.families.planar_parallel.kinematics.maxima import local_maxima
from worker.families.planar_parallel.kinematics.model import (
    Architecture,
    FloatArray,
    Robot,
    checked_limit,
    checked_mode,
)

__all__ = ["KappaRegion", "kappa_region_boundary", "robot_kappa_region"]

#: The area is refined to this fraction of itself, or of FLOOR_FRACTION x the reachable
#: area in the search box if that is larger.
RELATIVE_TOLERANCE = 1e-3
FLOOR_FRACTION = 1e-6
#: Refinement rounds, columns added at most (the larger of MIN_ADDED and MAX_ADDED times
#: the columns asked for), and the most pieces a gap is cut into in one round.
MAX_ROUNDS = 40
MAX_ADDED = 2.0
MIN_ADDED = 1000
MAX_PIECES = 8
#: Columns are never closer than this fraction of the searched width.
MIN_GAP = 2.0**-40
#: Extra heights per run of a neighbouring column, over the run and its length again on
#: each side (at least RUN_PAD_ROWS row spacings).
RUN_SAMPLES = 9
RUN_PAD_ROWS = 0.125


@dataclass(frozen=True)
class KappaRegion:
    """W_kappa0 described column by column.

    found: W_kappa0 has a run on some column (a column goes through every local maximum
    of 1/kappa above the limit, so it is found whenever the largest 1/kappa exceeds the
    limit). x (C,): column abscissae, increasing (``base_columns`` evenly spaced over
    |x| <= X, the rest added where W_kappa0 is thin or ends); lower, upper (C,): the ends
    of each column's lowest run (NaN where the column has none), exact to ~1e-12.
    boundary: one closed polyline (k, 2) per piece of the lowest runs (consecutive
    columns whose lowest runs overlap): the lower ends left to right, then the upper
    ends right to left, first point repeated. whole_area: all of W_kappa0 (every run of
    every column); rectangle_region_area: the lowest runs only (the part the paper's
    rectangle lives in, outlined by ``boundary``); both by the trapezoid rule over the
    columns, to about 1e-3 of the area. largest_inverse_condition and largest_point:
    the largest 1/kappa found (NaN if nothing is searched); at a corner of the reach it
    is the limit as the point approaches the corner.
    """

    found: bool
    limit: float
    x: FloatArray
    lower: FloatArray
    upper: FloatArray
    boundary: tuple[FloatArray, ...]
    whole_area: float
    rectangle_region_area: float
    largest_inverse_condition: float
    largest_point: tuple[float, float]
    base_columns: int
    message: str

    @property
    def added_columns(self) -> int:
        """Columns added to the evenly spaced ones."""
        return int(self.x.size - self.base_columns)


def _positive_int(value: object, name: str, function: str, minimum: int) -> int:
    if not (isinstance(value, numbers.Integral) and not isinstance(value, bool)
            and int(value) >= minimum):  # fmt: skip
        raise bad_parameter(name, function, f"an integer >= {minimum}", value)
    return int(value)


def _groups(lower: FloatArray, upper: FloatArray) -> list[tuple[int, int]]:
    """(start, stop) index ranges of consecutive columns whose lowest runs overlap (a
    piece of the lowest runs: it ends where a column has none, or where the lowest run
    jumps to another piece)."""
    with np.errstate(invalid="ignore"):
        joined = (lower[1:] <= upper[:-1]) & (lower[:-1] <= upper[1:])  # False with NaN
    found = np.isfinite(lower)
    starts = np.flatnonzero(found & ~np.concatenate([[False], joined]))
    stops = np.flatnonzero(found & ~np.concatenate([joined, [False]])) + 1
    return [(int(a), int(b)) for a, b in zip(starts, stops, strict=True)]


def _trapezoid(x: FloatArray, values: FloatArray) -> float:
    return float(np.sum(0.5 * (values[1:] + values[:-1]) * np.diff(x)))


def _neighbour_heights(runs: ColumnRuns, sides: tuple[np.ndarray, ...], row: float
                       ) -> FloatArray:  # fmt: skip
    """(m, E) extra heights for m columns whose neighbours are ``sides`` (each (m,),
    indices into ``runs``, out of range for none): RUN_SAMPLES over each of their runs,
    widened by its length (at least RUN_PAD_ROWS row spacings) on each side."""
    owners, heights = [], []
    t = np.linspace(0.0, 1.0, RUN_SAMPLES)
    for side in sides:
        valid = (side >= 0) & (side < runs.x.size)
        owner, lower, upper = runs.runs_of(side[valid])
        pad = np.maximum(upper - lower, RUN_PAD_ROWS * row)
        samples = (lower - pad)[:, None] + (upper - lower + 2.0 * pad)[:, None] * t
        owners.append(np.repeat(np.flatnonzero(valid)[owner], RUN_SAMPLES))
        heights.append(samples.ravel())
    return padded_rows(np.concatenate(owners), np.concatenate(heights), sides[0].size)


def _pieces(runs: ColumnRuns, tolerance: float) -> np.ndarray:
    """(C - 1,) into how many equal pieces to cut each gap between consecutive columns
    (1: keep). Where the run count changes, the trapezoid rule may miss half the jump in
    length times the gap, allowed a share of ``tolerance``; elsewhere its error is
    estimated from the second divided differences of the lengths at its two ends (the
    smaller: a kink on a column bends one of them; a bend inside the gap both), on the
    same side of any change of count, allowed a share by width (of the gaps next to a
    run). Both shrink with the pieces (linearly, cubically)."""
    x, counts = runs.x, runs.counts
    lower, upper = runs.lowest()
    widths = np.diff(x)
    if not tolerance > 0.0:  # nothing reachable, or only runs of no length
        return np.ones(widths.size, dtype=np.intp)
    structural = counts[1:] != counts[:-1]
    struct_share = tolerance / (4.0 * max(int(structural.sum()), 1))
    total = runs.lengths
    occupied = (total[1:] > 0.0) | (total[:-1] > 0.0)
    share = 0.5 * tolerance * widths / max(float(np.sum(widths[occupied])), 1e-300)
    ratio = np.zeros(widths.size)
    usable = np.zeros(x.size, dtype=bool)
    usable[1:-1] = ~structural[1:] & ~structural[:-1]
    for lengths in (total, np.nan_to_num(upper - lower)):
        jump = np.abs(np.diff(lengths))
        ratio = np.maximum(ratio, np.where(structural, 0.5 * widths * jump / struct_share, 0.0))
        slope = np.diff(lengths) / widths
        bend = np.zeros(x.size)
        bend[1:-1] = 2.0 * np.abs(np.diff(slope)) / (widths[1:] + widths[:-1])
        left = np.where(usable[:-1], bend[:-1], np.inf)
        right = np.where(usable[1:], bend[1:], np.inf)
        curvature = np.minimum(left, right)  # a kink on a column bends only one side
        curvature = np.where(np.isinf(curvature), 0.0, curvature)
        error = widths**3 / 12.0 * curvature
        ratio = np.maximum(ratio, np.where(structural, 0.0, np.sqrt(error / share)))
    pieces = np.where(ratio > 1.0, np.clip(np.ceil(ratio), 2, MAX_PIECES), 1)
    return np.where(widths > MIN_GAP * (x[-1] - x[0]), pieces, 1).astype(np.intp)


def _refine(
    batch: ArchitectureBatch, runs: ColumnRuns, heights: FloatArray, floor: float
) -> tuple[ColumnRuns, bool]:
    """Add columns until the trapezoid rule is good to RELATIVE_TOLERANCE (see the module
    docstring): (the columns, whether it is). New columns take their neighbours' runs as
    extra heights, and a column with fewer runs than a neighbour is scanned again with
    its neighbours' runs (once)."""
    row = float(heights[1] - heights[0])
    budget = max(int(MAX_ADDED * runs.x.size), MIN_ADDED)
    checked = np.zeros(0)
    for _ in range(MAX_ROUNDS):
        counts = runs.counts
        fewer = np.zeros(runs.x.size, dtype=bool)
        fewer[:-1] |= counts[:-1] < counts[1:]
        fewer[1:] |= counts[1:] < counts[:-1]
        again = np.flatnonzero(fewer & ~np.isin(runs.x, checked))
        lower, upper = runs.lowest()
        area = _trapezoid(runs.x, np.nan_to_num(upper - lower))
        pieces = _pieces(runs, RELATIVE_TOLERANCE * max(area, floor))
        cut = np.flatnonzero(pieces > 1)
        if again.size == 0 and cut.size == 0:
            return runs, True
        cut = cut[np.cumsum(pieces[cut] - 1) <= budget]
        if again.size == 0 and cut.size == 0:
            break
        gap = np.repeat(cut, pieces[cut] - 1)
        part = np.arange(gap.size) - np.repeat(np.cumsum(pieces[cut] - 1) - (pieces[cut] - 1),
                                               pieces[cut] - 1) + 1  # fmt: skip
        fraction = part / pieces[gap]
        new_x = runs.x[gap] + fraction * (runs.x[gap + 1] - runs.x[gap])
        x = np.concatenate([runs.x[again], new_x])
        extra = _neighbour_heights(
            runs, (np.concatenate([again - 1, gap]), np.concatenate([again + 1, gap + 1])), row
        )
        runs = runs.merged(scan_columns(batch, x, heights, extra)[0])
        checked = np.concatenate([checked, x])
        budget -= new_x.size
    return runs, False


def kappa_region_boundary(
    arch: Architecture,
    limit: float,
    working_mode: tuple[int, int] = (1, -1),
    *,
    columns: int = 801,
    rows: int = 321,
    x_half_span: float | None = None,
) -> KappaRegion:
    """W_kappa0 = {reachable, 1/kappa >= limit} by vertical 1-D root searches.

    ``columns`` abscissae evenly over |x| <= X (X: the reach for the proximal arm, the
    bounding circles for the telescopic leg, 2 l2 for the linear drive, whose W_kappa0 is
    an unbounded band; ``x_half_span`` overrides it), each scanned at ``rows`` heights;
    more columns where W_kappa0 is thin or ends. See :class:`KappaRegion`.
    """
    function = "kappa_region_boundary"
    value = checked_limit(limit, function)
    mode = checked_mode(working_mode, function)
    count = _positive_int(columns, "columns", function, 2)
    scans = _positive_int(rows, "rows", function, 3)
    if x_half_span is not None and not (
        isinstance(x_half_span, numbers.Real) and not isinstance(x_half_span, bool)
        and math.isfinite(float(x_half_span)) and float(x_half_span) > 0
    ):  # fmt: skip
        raise bad_parameter("x_half_span", function, "a positive length", x_half_span)
    half_span = None if x_half_span is None else float(x_half_span)
    return robot_kappa_region(Robot(arch, mode), value, (count, scans), half_span)


def robot_kappa_region(
    robot: Robot, limit: float, search: tuple[int, int], x_half_span: float | None = None
) -> KappaRegion:
    """:func:`kappa_region_boundary` of a checked :class:`~.model.Robot` at a limit in
    (0, 1], ``search`` = (columns >= 2, rows >= 3) (no checks)."""
    arch, mode, value = robot.arch, robot.mode, limit
    count, scans = search
    span, y_low, y_high = search_box(arch, value, x_half_span)
    if not span > 0:
        empty = np.full(count, np.nan)
        message = f"W_kappa0 at 1/kappa >= {value:g} is empty: there is nothing to search"
        return KappaRegion(False, value, np.zeros(count), empty, empty.copy(), (), 0.0, 0.0,
                           math.nan, (math.nan, math.nan), count, message)  # fmt: skip
    batch = single(arch, mode, value)
    heights = np.linspace(y_low, y_high, scans)
    runs, margins = scan_columns(batch, np.linspace(-span, span, count), heights)
    points, values = local_maxima(batch.extended_inverse_condition, arch,
                                  (runs.x, heights, margins), value)  # fmt: skip
    inside = (np.abs(points[:, 0]) <= span) & (points[:, 1] >= y_low) & (points[:, 1] <= y_high)
    forced = points[(values >= value) & inside]
    forced_x, first = np.unique(forced[:, 0], return_index=True)
    if forced_x.size:  # a column through each maximum above the limit
        runs = runs.merged(scan_columns(batch, forced_x, heights, forced[first, 1:])[0])
    reach = float(np.mean(margins > -value)) * 2.0 * span * (y_high - y_low)
    runs, converged = _refine(batch, runs, heights, FLOOR_FRACTION * reach)
    largest = (float(values[0]), (float(points[0, 0]), float(points[0, 1])))
    column_best = int(np.argmax(runs.best))
    if runs.best[column_best] + value > largest[0]:
        largest = (float(runs.best[column_best] + value),
                   (float(runs.x[column_best]), float(runs.best_y[column_best])))  # fmt: skip
    return _region(runs, value, largest, count, (span, scans, converged))


def _region(
    runs: ColumnRuns,
    limit: float,
    largest: tuple[float, tuple[float, float]],
    base: int,
    search: tuple[float, int, bool],
) -> KappaRegion:
    lower, upper = runs.lowest()
    xs = runs.x
    polygons = []
    for start, stop in _groups(lower, upper):
        x, lo, up = xs[start:stop], lower[start:stop], upper[start:stop]
        ring = np.concatenate([np.stack([x, lo], -1), np.stack([x[::-1], up[::-1]], -1)])
        polygons.append(np.concatenate([ring, ring[:1]]))
    whole = _trapezoid(xs, runs.lengths)
    lowest = _trapezoid(xs, np.nan_to_num(upper - lower))
    span, scans, converged = search
    value, (px, py) = largest
    where = f"largest 1/kappa {value:.6g} at ({px:.6g}, {py:.6g})"
    searched = (f"{base} columns over |x| <= {span:.6g} and {xs.size - base} added where "
                f"it is thin or ends, {scans} rows")  # fmt: skip
    if not converged:
        searched += "; the columns ran out before the areas were good to 1e-3"
    message = (
        f"W_kappa0 at 1/kappa >= {limit:g}: area {whole:.6g}, rectangle_region_area "
        f"{lowest:.6g} (the lowest run of each column), {len(polygons)} polygon(s); "
        f"{where} ({searched})"
        if polygons else f"W_kappa0 at 1/kappa >= {limit:g} is empty: the {where} ({searched})"
    )  # fmt: skip
    return KappaRegion(bool(polygons), limit, xs, lower, upper, tuple(polygons), whole, lowest,
                       value, (px, py), base, message)  # fmt: skip
