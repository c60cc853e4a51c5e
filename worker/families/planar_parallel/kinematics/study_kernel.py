"""The arithmetic of the ``planar2dof-conditioning-map`` study kernel: many robots of one
type and working mode at once (Huang et al. 2004, eqs 2, 7; docs/methods/planar-parallel.md).

One row per design: ``lengths`` (m, 3) are (l1, l2, e) as the job's
:class:`~.model.Architecture` holds them (unused lengths filled as the job fills them).
:func:`default_bounds` is the job's default grid, :func:`grid_axes` its nodes,
:func:`map_summary` 1/kappa over every design's grid (reachable nodes, least, largest
and mean 1/kappa, nodes of W_kappa0), evaluated in tiles of designs x grid rows so that
temporaries stay bounded, with the very formulas of
:func:`~worker.families.planar_parallel.kinematics.conditioning_map` (so every node's
value is the job's to the bit). :func:`kappa_region_areas` measures W_kappa0 design by
design with the job's own column search
(:func:`~.kappa_region.robot_kappa_region`): its adaptive refinement is per robot.

Internal to the study kernel and the job's grid; no input checks here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from worker.families.planar_parallel.kinematics.kappa_region import robot_kappa_region
from worker.families.planar_parallel.kinematics.model import (
    Architecture,
    FloatArray,
    Robot,
    WorkingMode,
    chain_components,
    inverse_condition_of_components,
)

__all__ = [
    "DEFAULT_GRID_MARGIN",
    "TILE_NODES",
    "MapSummary",
    "RegionNumbers",
    "default_bounds",
    "grid_axes",
    "kappa_region_areas",
    "map_summary",
]

#: The default grid reaches this fraction beyond the workspace on every side.
DEFAULT_GRID_MARGIN = 0.03
#: Telescopic legs reach everywhere: the default grid spans this many times e.
TELESCOPIC_SPAN = 3.0
#: Linear drives reach a band |y| <= l2 unbounded in x: the default grid spans |x| <= 2 l2.
LINEAR_DRIVE_X_SPAN = 2.0
#: Grid nodes evaluated at once (designs x rows x columns of one tile).
TILE_NODES = 1 << 17


def default_bounds(actuation: str, lengths: FloatArray) -> FloatArray:
    """[x_min, x_max, y_min, y_max] (m, 4) around each design's reachable workspace with
    a 3 % margin, for ``lengths`` (m, 3) = (l1, l2, e).

    Proximal arm: |x| <= l1 + l2 - e (at least 5 % of l1 + l2), |y| <= l1 + l2;
    telescopic leg: the square |x|, |y| <= 3e (l1 if e = 0); linear drive: |x| <= 2 l2,
    |y| <= l2.
    """
    l1, l2, e = lengths[:, 0], lengths[:, 1], lengths[:, 2]
    if actuation == "proximal-arm":
        reach = l1 + l2
        half_x, half_y = np.maximum(reach - e, 0.05 * reach), reach
    elif actuation == "telescopic-leg":
        half_x = half_y = np.where(e > 0, TELESCOPIC_SPAN * e, l1)
    else:
        half_x, half_y = LINEAR_DRIVE_X_SPAN * l2, l2
    grow = 1.0 + DEFAULT_GRID_MARGIN
    return np.stack([-grow * half_x, grow * half_x, -grow * half_y, grow * half_y], axis=-1)


def grid_axes(bounds: FloatArray, points_per_axis: int) -> tuple[FloatArray, FloatArray]:
    """The nodes of each design's grid: x (m, n) and y (m, n) from ``bounds`` (m, 4),
    ends included (as :class:`worker.common.grids.WorkspaceGrid` places them)."""
    x = np.linspace(bounds[:, 0], bounds[:, 1], points_per_axis, axis=-1)
    y = np.linspace(bounds[:, 2], bounds[:, 3], points_per_axis, axis=-1)
    return np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)


@dataclass(frozen=True)
class MapSummary:
    """1/kappa over each design's grid, (m,) each: ``reachable`` nodes; ``minimum``,
    ``maximum``, ``mean`` of 1/kappa over the reachable nodes (NaN where none);
    ``inside``: nodes with 1/kappa >= the design's limit (0 without limits)."""

    reachable: FloatArray
    minimum: FloatArray
    maximum: FloatArray
    mean: FloatArray
    inside: FloatArray


def map_summary(
    actuation: str,
    mode: WorkingMode,
    lengths: FloatArray,
    axes: tuple[FloatArray, FloatArray],
    limit: FloatArray | None = None,
) -> MapSummary:
    """1/kappa (eq 7) on the grids ``axes`` = (x (m, n), y (m, n)) of the designs
    ``lengths`` (m, 3), summarised per design (see :class:`MapSummary`); ``limit`` (m,)
    counts the nodes of W_kappa0. Tiles of at most :data:`TILE_NODES` nodes."""
    x, y = axes
    m, nx = x.shape
    ny = y.shape[1]
    reachable, count = np.zeros(m), np.zeros(m)
    low, high = np.full(m, np.inf), np.full(m, -np.inf)
    total, inside = np.zeros(m), np.zeros(m)
    designs = max(1, TILE_NODES // (nx * ny))
    rows = ny if designs > 1 else max(1, TILE_NODES // nx)
    for first in range(0, m, designs):
        last = min(first + designs, m)
        part = lengths[first:last, :, None, None]
        for top in range(0, ny, rows):
            reach, values = _tile(actuation, mode, part, x[first:last, None, :],
                                  y[first:last, top : top + rows, None])  # fmt: skip
            finite = np.isfinite(values)
            block = slice(first, last)
            reachable[block] += reach.sum(axis=(1, 2))
            count[block] += finite.sum(axis=(1, 2))
            low[block] = np.fmin(low[block], np.where(finite, values, np.inf).min(axis=(1, 2)))
            high[block] = np.fmax(high[block], np.where(finite, values, -np.inf).max(axis=(1, 2)))
            total[block] += np.where(finite, values, 0.0).sum(axis=(1, 2))
            if limit is not None:
                level = limit[block, None, None]
                inside[block] += (np.nan_to_num(values, nan=-1.0) >= level).sum(axis=(1, 2))
    none = count == 0
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = total / count
    return MapSummary(reachable, np.where(none, np.nan, low), np.where(none, np.nan, high),
                      np.where(none, np.nan, mean), inside)  # fmt: skip


def _tile(actuation: str, mode: WorkingMode, lengths: FloatArray, x: FloatArray, y: FloatArray
          ) -> tuple[NDArray[np.bool_], FloatArray]:  # fmt: skip
    """(reachable, 1/kappa), each (t, r, nx), at the nodes x (t, 1, nx) by y (t, r, 1) of
    t designs ``lengths`` (t, 3, 1, 1); 1/kappa NaN where unreachable."""
    l1, l2, e = lengths[:, 0], lengths[:, 1], lengths[:, 2]
    chains = chain_components(actuation, (l1, l2, e), mode, x, y)
    shape = (x.shape[0], y.shape[1], x.shape[2])
    reachable = np.broadcast_to(chains[0][0] & chains[1][0], shape)
    values = np.where(reachable, inverse_condition_of_components(*chains), np.nan)
    return reachable, np.asarray(np.broadcast_to(values, shape), dtype=np.float64)


@dataclass(frozen=True)
class RegionNumbers:
    """W_kappa0 of each design, (m,) each: ``area`` and ``rectangle_region_area`` (0
    where it is empty), the largest 1/kappa found (``largest``, NaN if nothing was
    searched) and where (``largest_x``, ``largest_y``)."""

    area: FloatArray
    rectangle_region_area: FloatArray
    largest: FloatArray
    largest_x: FloatArray
    largest_y: FloatArray


def kappa_region_areas(
    actuation: str,
    mode: WorkingMode,
    lengths: FloatArray,
    limit: FloatArray,
    search: tuple[int, int],
) -> RegionNumbers:
    """W_kappa0's numbers (:class:`RegionNumbers`) for the designs ``lengths`` (m, 3) at
    the limits ``limit`` (m,), by the job's column search with ``search`` = (columns,
    rows), one design at a time; NaN for a design whose search raises (its job would
    fail: a study kernel never raises for a design)."""
    numbers = np.full((5, len(lengths)), np.nan)
    for k, (l1, l2, e) in enumerate(lengths.tolist()):
        robot = Robot(Architecture(actuation, l1, l2, e), mode)  # type: ignore[arg-type]
        try:
            region = robot_kappa_region(robot, float(limit[k]), search)
        except (ArithmeticError, ValueError):
            continue
        found = region.found
        numbers[:, k] = (region.whole_area if found else 0.0,
                         region.rectangle_region_area if found else 0.0,
                         region.largest_inverse_condition, *region.largest_point)  # fmt: skip
    return RegionNumbers(*numbers)
