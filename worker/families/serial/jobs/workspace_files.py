"""The workspace map's data files: NPZ (the voxel grid with axes, units and metadata)
and CSV (one row per reached voxel, header first)."""

from __future__ import annotations

from typing import Any

import numpy as np

from worker.common.data_export import DIMENSIONLESS, column, columns_csv, job_metadata, npz_artifact
from worker.contract import Artifact
from worker.families.serial.kinematics.workspace_map import WorkspaceMap

__all__ = ["INDEX_UNIT", "workspace_files"]

#: The unit of manipulability: a product of singular values of mixed units.
INDEX_UNIT = "mixed"
_STATISTICS = tuple(f"{name}_{stat}" for name in ("manipulability", "inverse_condition")
                    for stat in ("min", "mean", "max"))  # fmt: skip


def _unit(name: str) -> str:
    return INDEX_UNIT if name.startswith("manipulability") else DIMENSIONLESS


def workspace_files(
    result: WorkspaceMap, inputs: dict[str, Any], length_unit: str
) -> tuple[Artifact, Artifact]:
    """(workspace_map.csv, workspace_map.npz)."""
    grid = result.grid
    names = ("x", "y", "z")[: len(grid.axes)]
    nodes = np.meshgrid(*grid.axes, indexing="ij")
    reached = result.reached
    columns: dict[str, Any] = {
        column(n, length_unit): node[reached] for n, node in zip(names, nodes, strict=True)
    }
    columns[column("reachability_index", DIMENSIONLESS)] = result.reachability_index[reached]
    columns[column("samples", DIMENSIONLESS)] = result.samples[reached]
    for name in _STATISTICS:
        columns[column(name, _unit(name))] = result.statistics[name][reached]
    csv = columns_csv("workspace_map.csv", columns, "Reached voxels (CSV)")
    arrays: dict[str, Any] = dict(zip(names, grid.axes, strict=True))
    arrays["reached"] = reached
    arrays["reachability_index"] = result.reachability_index
    arrays["samples"] = result.samples
    arrays.update({name: result.statistics[name] for name in _STATISTICS})
    arrays["convergence_samples"] = np.asarray(result.prefixes, dtype=np.int64)
    arrays["convergence_reached_voxels"] = np.asarray(result.reached_voxels, dtype=np.int64)
    arrays["convergence_mean_index"] = np.asarray(result.mean_index)
    units = {n: length_unit for n in names}
    units.update({k: _unit(k) for k in arrays if k not in names})
    axes = {k: names for k in ("reached", "reachability_index", "samples", *_STATISTICS)}
    axes.update({n: (n,) for n in names})
    axes.update({k: ("prefix",) for k in arrays if k.startswith("convergence_")})
    npz = npz_artifact(
        "workspace_map.npz",
        arrays,
        "Workspace map (NumPy arrays)",
        units=units,
        axes=axes,
        metadata={
            **job_metadata("serial-workspace-map", inputs),
            "voxel_size": grid.size,
            "nodes": "voxel centres at multiples of voxel_size; NaN statistics where not reached",
        },
    )
    return csv, npz
