"""W_kappa0 = {points of the working mode with 1/kappa >= 1/kappa0} as a result section.

The exact boundary comes from
:func:`worker.families.planar_parallel.kinematics.kappa_region_boundary`
(vertical 1-D root searches, every run of every column, thin sets included);
``area`` is the whole set, ``rectangle_region_area`` the lowest run of each column
only (the part the paper's rectangle search uses, outlined by ``boundary``). Both are
good to 1 % for a set of at least RESOLUTION_FRACTION of the reachable area on the
grid; a smaller set is flagged ``below_resolution`` and noted. The map's grid then
checks the boundary: nodes of W_kappa0 above a gap in their column (overhangs, e.g. the
hooks of the arms of W_kappa0 at small delta) are not part of that description, and
are reported.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.common.grids import WorkspaceGrid
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.discretisation import BOUNDARY_COLUMNS, BOUNDARY_ROWS

__all__ = ["KappaRegionSection", "kappa_region_section"]

#: Grid area of W_kappa0 outside the column-wise description that is worth a note, as a
#: fraction of the grid area of W_kappa0 (below it: boundary cells and rounding).
UNDESCRIBED_NOTE_FRACTION = 0.005
#: W_kappa0's areas are good to 1 % when it covers at least this fraction of the
#: reachable area on the grid (``summary.reachable_area_grid``); below it, a note.
RESOLUTION_FRACTION = 1e-4


@dataclass(frozen=True)
class KappaRegionSection:
    """The result entry, its notes and the region (for the data files)."""

    entry: dict[str, Any]
    notes: list[str]
    region: pp.KappaRegion

    @property
    def search(self) -> dict[str, Any]:
        """How W_kappa0 was searched, for the result's ``discretisation``."""
        return {
            "method": "vertical 1-D root searches (Illinois), every run of every column "
            "(extrema between scan rows refined by golden-section search); the largest "
            "1/kappa climbed (Nelder-Mead) from the scan's maxima and the reach's corners, "
            "a column through each maximum above the limit; columns added where the set "
            "is thin or ends until the trapezoid rule is good to 1e-3",
            "columns": BOUNDARY_COLUMNS,
            "columns_added": self.region.added_columns,
            "rows": BOUNDARY_ROWS,
            "x_half_span": float(self.region.x[-1]),
        }


def kappa_region_section(
    robot: pp.Robot,
    limit: float,
    grid: WorkspaceGrid,
    inverse_condition: NDArray[np.float64],
    length_unit: str,
) -> KappaRegionSection:
    """W_kappa0's boundary and area for the job's robot and its (validated) limit,
    checked against the map (``inverse_condition``
    (ny, nx) on ``grid``); areas in ``length_unit`` squared."""
    region = pp.robot_kappa_region(robot, limit, (BOUNDARY_COLUMNS, BOUNDARY_ROWS))
    inside = np.nan_to_num(inverse_condition, nan=-1.0) >= limit
    area_grid = int(inside.sum()) * grid.cell_area
    reachable_grid = int(np.isfinite(inverse_condition).sum()) * grid.cell_area
    undescribed = int((inside & ~_described(region, grid)).sum()) * grid.cell_area
    below_resolution = region.found and region.whole_area < RESOLUTION_FRACTION * reachable_grid
    largest = region.largest_inverse_condition
    entry = {
        "inverse_condition_limit": limit,
        "found": region.found,
        "area": region.whole_area if region.found else 0.0,
        "rectangle_region_area": region.rectangle_region_area if region.found else 0.0,
        "area_grid": area_grid,
        "undescribed_area_grid": undescribed,
        "largest_inverse_condition": None if math.isnan(largest) else {
            "value": largest, "x": region.largest_point[0], "y": region.largest_point[1]},
        "below_resolution": below_resolution,
        "boundary": [polygon.tolist() for polygon in region.boundary],
        "message": region.message,
    }  # fmt: skip
    notes = _notes(region, limit, length_unit, below_resolution, reachable_grid)
    if area_grid > 0 and undescribed > UNDESCRIBED_NOTE_FRACTION * area_grid:
        notes.append(
            f"W_kappa0 reaches above a gap in some columns (about {undescribed:.4g} "
            f"{length_unit}² of its {area_grid:.4g} on the grid): the "
            "column-wise 'boundary' and 'rectangle_region_area' describe the lowest part of "
            "each column only (the part the paper's rectangle lives in); 'area' and the "
            "figures cover all of it."
        )
    return KappaRegionSection(entry, notes, region)


def _notes(
    region: pp.KappaRegion, limit: float, unit: str, below_resolution: bool, reachable: float
) -> list[str]:
    """Notes on W_kappa0 that do not need the grid's check."""
    notes = []
    if region.found and region.whole_area > (1.0 + 1e-6) * region.rectangle_region_area:
        notes.append(
            f"W_kappa0 is more than the lowest run of each column: its area is "
            f"{region.whole_area:.6g} {unit}², of which {region.rectangle_region_area:.6g} in "
            "the lowest runs ('rectangle_region_area', the part the paper's rectangle lives "
            "in; 'boundary' outlines that part)."
        )
    largest, (x, y) = region.largest_inverse_condition, region.largest_point
    if not region.found:
        why = (
            "there is nothing to search" if math.isnan(largest)
            else f"the largest 1/kappa is {largest:.7g}, at ({x:.6g}, {y:.6g})"
        )  # fmt: skip
        notes.append(f"W_kappa0 is empty: no point of the working mode has 1/kappa >= "
                     f"{limit:g} ({why}).")  # fmt: skip
    if below_resolution:
        notes.append(
            f"W_kappa0 is below the resolution: its area, {region.whole_area:.4g} {unit}², is "
            f"less than {RESOLUTION_FRACTION:g} of the reachable area on the grid "
            f"({reachable:.4g} {unit}²), below which 'area' and 'rectangle_region_area' "
            f"are not guaranteed to 1 % (the largest 1/kappa is {largest:.6g}, at "
            f"({x:.6g}, {y:.6g})); the grid may not show it."
        )
    return notes


def _described(region: pp.KappaRegion, grid: WorkspaceGrid) -> NDArray[np.bool_]:
    """Grid nodes within the column-wise description, (ny, nx): lower <= y <= upper of
    either neighbouring column, with a grid step of slack."""
    x, y = grid.x, grid.y
    dx, dy = grid.step
    if not region.found:
        return np.zeros((y.size, x.size), dtype=bool)
    right = np.clip(np.searchsorted(region.x, x), 0, region.x.size - 1)
    left = np.clip(right - 1, 0, region.x.size - 1)
    with np.errstate(invalid="ignore"):
        lower = np.fmin(region.lower[left], region.lower[right])
        upper = np.fmax(region.upper[left], region.upper[right])
        spanned = (x >= region.x[0] - dx) & (x <= region.x[-1] + dx)
        column = (y[:, None] >= lower[None, :] - dy) & (y[:, None] <= upper[None, :] + dy)
    return np.asarray(column & spanned[None, :], dtype=bool)
