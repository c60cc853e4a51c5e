"""The ``planar2dof-conditioning-map`` preview: the job's 1/kappa and beta_min maps and a
summary counted on the grid (no exact W_kappa0 boundary, given points or files); the
live explorer's evaluation (:mod:`worker.previews`)."""

from __future__ import annotations

from typing import Any

import numpy as np

from worker.common.preview_arrays import map_entry
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.jobs.architecture import map_grid, robot_from_spec
from worker.families.planar_parallel.specs import ConditioningMapSpec

__all__ = ["conditioning_preview"]


def conditioning_preview(spec: ConditioningMapSpec) -> dict[str, Any]:
    """1/kappa (eq 7) and beta_min (eq 15, deg) over the job's grid (ny, nx), None where
    unreachable, with the reachable nodes, the largest and mean 1/kappa and the area of
    W_kappa0 = {1/kappa >= 1/kappa0} counted on the grid (nodes x cell area)."""
    robot = robot_from_spec(spec)
    grid = map_grid(spec.grid, robot.arch)
    cmap = pp.robot_map(robot, grid.x, grid.y)
    inverse = np.where(cmap.reachable, cmap.inverse_condition, np.nan)
    beta_min = np.where(cmap.reachable, np.degrees(cmap.min_pressure_angle), np.nan)
    reached = inverse[np.isfinite(inverse)]
    unit = spec.length_unit
    dx, dy = grid.step
    indices: list[dict[str, Any]] = [
        {"name": "reachable_points", "label": "reachable nodes", "value": int(reached.size),
         "unit": "nodes"},
        {"name": "max_inverse_condition", "label": "max 1/κ on the grid",
         "value": float(reached.max()) if reached.size else None, "unit": ""},
        {"name": "mean_inverse_condition", "label": "mean 1/κ over the reachable nodes",
         "value": float(reached.mean()) if reached.size else None, "unit": ""},
    ]  # fmt: skip
    if spec.inverse_condition_limit is not None:
        inside = int(np.count_nonzero(reached >= spec.inverse_condition_limit))
        indices.append({
            "name": "kappa_region_area",
            "label": f"area of W_κ0 (1/κ ≥ {spec.inverse_condition_limit:g}), on the grid",
            "value": inside * dx * dy, "unit": f"{unit}²",
        })  # fmt: skip
    arch = robot.arch
    title = f"l1 = {arch.l1:.4g}, l2 = {arch.l2:.4g}, e = {arch.e:.4g} {unit}"
    notes = [] if reached.size else ["No node of the grid is reachable."]
    x_axis, y_axis = (grid.x, "x", unit), (grid.y, "y", unit)
    return {
        "maps": [
            map_entry(f"1/κ, {title}", x_axis, y_axis, (inverse, "1/κ", "")),
            map_entry(f"β_min, {title}", x_axis, y_axis, (beta_min, "β_min", "deg")),
        ],
        "indices": indices,
        "notes": notes,
    }
