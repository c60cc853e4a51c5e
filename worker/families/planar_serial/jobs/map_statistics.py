"""The numbers ``planar3r-dexterity-map`` reports about its map: the ``summary``
statistics over the grid and the ``areas``.  The job and its study kernel
(:mod:`worker.families.planar_serial.study_plan`) both call these, one design at a
time, so a study reads the job's numbers to the bit."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.common.grids import WorkspaceGrid
from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.jobs.dexterity_evaluation import (
    FULL_DEXTERITY_TOL,
    LimitedJoints,
    Links,
)

__all__ = ["map_areas", "map_summary"]


def map_summary(d_z: NDArray[np.float64]) -> dict[str, float | int]:
    """d_z_max, the mean d_z (and D) over the reachable nodes (d_z > 0; 0 if none), the
    reachable and fully dexterous node counts of a map (ny, nx)."""
    reachable = d_z > 0.0
    reachable_dz = d_z[reachable]
    mean_reachable = float(reachable_dz.mean()) if reachable_dz.size else 0.0
    return {
        "d_z_max": float(d_z.max()),
        "d_z_mean_reachable": mean_reachable,
        "D_mean_reachable": mean_reachable / 3.0,
        "reachable_points": int(reachable.sum()),
        "fully_dexterous_points": int((d_z >= 1.0 - FULL_DEXTERITY_TOL).sum()),
    }


def map_areas(
    links: Links,
    grid: WorkspaceGrid,
    sampling: LimitedJoints | None,
    d_z: NDArray[np.float64],
    *,
    bands: tuple[tuple[float, float], ...] | None = None,
) -> dict[str, Any]:
    """Reachable and fully dexterous areas: exact for revolute joints; under joint limits
    those of the limited arm, counted on the map d_z (ny, nx), with the revolute ones as
    ``unlimited_reference`` (its ``regions`` are the job's to add).  ``bands``: the
    unlimited arm's full-dexterity bands, if the caller has them already."""
    if bands is None:
        bands = planar_serial.full_dexterity_bands(links)
    inner, outer = planar_serial.reach_radii(links)
    unlimited = {
        "reachable": math.pi * (outer**2 - inner**2),
        "fully_dexterous": planar_serial.band_area(bands),
    }
    on_grid = {
        "reachable_grid": int((d_z > 0.0).sum()) * grid.cell_area,
        "fully_dexterous_grid": int((d_z >= 1.0 - FULL_DEXTERITY_TOL).sum()) * grid.cell_area,
        "cell_area": grid.cell_area,
    }
    if sampling is None:
        return {**unlimited, **on_grid, "method": "exact-closed-form"}
    return {
        "reachable": on_grid["reachable_grid"],
        "fully_dexterous": on_grid["fully_dexterous_grid"],
        **on_grid,
        "method": f"grid count of {sampling.method} d_z (joint-limited arm)",
        "unlimited_reference": {**unlimited, "full_dexterity_bands": [list(b) for b in bands]},
    }
