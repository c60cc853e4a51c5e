"""The ``planar3r-dexterity-map`` preview: the job's d_z map and its summary, nothing
else (no task points, trajectory, regions or files); the live explorer's evaluation
(:mod:`worker.previews`)."""

from __future__ import annotations

from typing import Any

from worker.common.preview_arrays import map_entry
from worker.families.planar_serial.jobs.dexterity_evaluation import (
    grid_dexterity,
    limited_joints,
    map_method,
    workspace_grid,
)
from worker.families.planar_serial.jobs.map_statistics import map_summary
from worker.families.planar_serial.specs import DexterityMapSpec

__all__ = ["dexterity_preview"]

_SUMMARY = (
    ("d_z_max", "max d_z", ""),
    ("d_z_mean_reachable", "mean d_z over the reachable nodes", ""),
    ("D_mean_reachable", "mean D = d_z/3 over the reachable nodes", ""),
    ("reachable_points", "reachable nodes", "nodes"),
    ("fully_dexterous_points", "fully dexterous nodes (d_z = 1)", "nodes"),
)


def dexterity_preview(spec: DexterityMapSpec) -> dict[str, Any]:
    """d_z (ny, nx) over the job's grid (the same method: exact closed form, or under
    joint limits exact events or orientation sampling) and its summary, as plain JSON
    values; an unreachable node (d_z = 0) is None."""
    links = spec.links
    grid = workspace_grid(spec.grid, links)
    sampling = limited_joints(spec.joint_limits_deg, spec.orientation_step_deg, spec.method)
    d_z = grid_dexterity(links, grid, sampling, lambda done, total: None)
    summary = map_summary(d_z)
    shown = d_z.copy()
    shown[shown <= 0.0] = float("nan")
    unit = spec.length_unit
    l1, l2, l3 = links
    title = f"d_z of the 3R arm ({l1:g}, {l2:g}, {l3:g}), {map_method(sampling)}"
    indices = [
        {"name": name, "label": label, "value": summary[name], "unit": unit_}
        for name, label, unit_ in _SUMMARY
    ]
    notes = [] if summary["reachable_points"] else ["No node of the grid is reachable."]
    return {
        "maps": [map_entry(title, (grid.x, "x", unit), (grid.y, "y", unit), (shown, "d_z", ""))],
        "indices": indices,
        "notes": notes,
    }
