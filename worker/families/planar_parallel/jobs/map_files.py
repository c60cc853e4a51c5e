"""The conditioning map's data files: the CSV (one row per grid node, every column with
its unit) and the NPZ (the maps with their axes, units and the job's inputs)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from worker.common.data_export import (
    DIMENSIONLESS,
    column,
    columns_csv,
    job_metadata,
    npz_artifact,
)
from worker.common.grids import WorkspaceGrid
from worker.common.progress import ProgressReporter
from worker.contract import Artifact
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.jobs.kappa_region import KappaRegionSection
from worker.families.planar_parallel.specs import ConditioningMapSpec

__all__ = ["CSV_NAME", "NPZ_NAME", "map_files"]

CSV_NAME, NPZ_NAME = "conditioning_map.csv", "conditioning_map.npz"


def map_files(
    spec: ConditioningMapSpec,
    arch: pp.Architecture,
    grid: WorkspaceGrid,
    cmap: pp.ConditioningMap,
    region: KappaRegionSection | None,
    progress: ProgressReporter,
) -> tuple[Artifact, ...]:
    """The map as CSV (progress 70-95 %, by blocks of rows) and NPZ (95-99 %)."""
    xx, yy = np.meshgrid(grid.x, grid.y)
    angles = np.degrees(cmap.pressure_angles)
    length, none = spec.length_unit, DIMENSIONLESS
    proximal = spec.actuation == "proximal-arm"
    joints = np.degrees(cmap.joints) if proximal else cmap.joints
    suffix = "_deg" if proximal else ""
    # The actuated joint's quantity: an arm's angle, a leg's length, a slider's position.
    joint, joint_unit = {
        "proximal-arm": ("joint_{}_angle", "deg"),
        "telescopic-leg": ("leg_{}_length", length),
        "linear-drive": ("slider_{}_position", length),
    }[spec.actuation]
    columns: dict[str, NDArray[np.generic]] = {
        column("x", length): xx,
        column("y", length): yy,
        column("reachable", none): cmap.reachable,
        column("inverse_condition", none): cmap.inverse_condition,
        column("pressure_angle_1", "deg"): angles[..., 0],
        column("pressure_angle_2", "deg"): angles[..., 1],
        column("min_pressure_angle", "deg"): np.degrees(cmap.min_pressure_angle),
        column(joint.format(1), joint_unit): joints[..., 0],
        column(joint.format(2), joint_unit): joints[..., 1],
    }
    csv = columns_csv(
        CSV_NAME,
        columns,
        "Conditioning map, one row per grid node (CSV)",
        progress.span(70.0, 95.0, "data files"),
    )
    arrays: dict[str, NDArray[np.generic]] = {
        "x": grid.x, "y": grid.y, "reachable": cmap.reachable,
        "inverse_condition": cmap.inverse_condition, "pressure_angles_deg": angles,
        "min_pressure_angle_deg": np.degrees(cmap.min_pressure_angle),
        f"joints{suffix}": joints,
        "architecture_l1_l2_e": np.array([arch.l1, arch.l2, arch.e]),
        "working_mode": np.array(spec.working_mode),
    }  # fmt: skip
    units = {
        "x": length, "y": length, "reachable": none, "inverse_condition": none,
        "pressure_angles_deg": "deg", "min_pressure_angle_deg": "deg",
        f"joints{suffix}": joint_unit, "architecture_l1_l2_e": length, "working_mode": none,
    }  # fmt: skip
    on_grid = ("y", "x")
    axes = {
        "reachable": on_grid, "inverse_condition": on_grid,
        "pressure_angles_deg": (*on_grid, "chain"), "min_pressure_angle_deg": on_grid,
        f"joints{suffix}": (*on_grid, "chain"), "architecture_l1_l2_e": ("length",),
        "working_mode": ("chain",),
    }  # fmt: skip
    if region is not None:
        arrays["inverse_condition_limit"] = np.array(region.entry["inverse_condition_limit"])
        arrays["w_kappa0_columns_x"] = region.region.x
        arrays["w_kappa0_columns_lower"] = region.region.lower
        arrays["w_kappa0_columns_upper"] = region.region.upper
        units |= {"inverse_condition_limit": none, "w_kappa0_columns_x": length,
                  "w_kappa0_columns_lower": length, "w_kappa0_columns_upper": length}  # fmt: skip
        axes |= {"w_kappa0_columns_lower": ("w_kappa0_columns_x",),
                 "w_kappa0_columns_upper": ("w_kappa0_columns_x",)}  # fmt: skip
        for k, polygon in enumerate(region.region.boundary):
            arrays[f"w_kappa0_boundary_{k}"] = polygon
            units[f"w_kappa0_boundary_{k}"] = length
            axes[f"w_kappa0_boundary_{k}"] = ("vertex", "xy")
    progress.report(95.0, "data files")
    npz = npz_artifact(
        NPZ_NAME, arrays, "Conditioning map (NumPy arrays)", units=units, axes=axes,
        metadata=job_metadata("planar2dof-conditioning-map", spec.model_dump(mode="json")),
    )  # fmt: skip
    return csv, npz
