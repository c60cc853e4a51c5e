"""The ``serial-workspace-map`` job: reachable workspace and dexterity on a voxel grid.

Joint samples within the limits through the batched forward kinematics and indices
(:mod:`..kinematics.workspace_map`); the result gives the summary, the convergence
report and the grid; the files are the NPZ grid, the CSV of reached voxels and three
figures (docs/methods/serial.md, "Workspace map").
"""

from __future__ import annotations

from typing import Any

from worker.common.figures import figure_artifacts
from worker.common.progress import ProgressReporter
from worker.contract import Artifact, JobContext, JobOutcome
from worker.families.serial.jobs.indices import arm_description
from worker.families.serial.jobs.workspace_files import workspace_files
from worker.families.serial.kinematics.voxel_grid import sphere_bin_layout
from worker.families.serial.kinematics.workspace_map import (
    MapSettings,
    WorkspaceMap,
    relative_changes,
    workspace_map,
)
from worker.families.serial.plots.workspace import (
    histogram_figure,
    scatter_figure,
    slices_figure,
)
from worker.families.serial.workspace_spec import SerialWorkspaceMapSpec

__all__ = ["convergence_report", "run_serial_workspace_map"]


def _size_key(result: WorkspaceMap) -> str:
    """``reached_area`` for a planar arm's pixel map (length^2), else ``reached_volume``."""
    return "reached_area" if len(result.grid.shape) == 2 else "reached_volume"


def convergence_report(result: WorkspaceMap, tolerance: float) -> dict[str, Any]:
    """Reached volume (area: a planar arm) and mean index at N/8, N/4, N/2, N, their
    relative changes over each doubling and whether the last doubling changed both by at
    most ``tolerance``."""
    cell = result.grid.cell_measure
    volume = tuple(v * cell for v in result.reached_voxels)
    volume_change = relative_changes(volume)
    index_change = relative_changes(result.mean_index)
    return {
        "samples": list(result.prefixes),
        _size_key(result): list(volume),
        "mean_reachability_index": list(result.mean_index),
        "relative_change_volume": volume_change,
        "relative_change_index": index_change,
        "tolerance": tolerance,
        "met": bool(volume_change[-1] <= tolerance and index_change[-1] <= tolerance),
    }


def _summary(result: WorkspaceMap) -> dict[str, Any]:
    reached = result.reached
    n = int(reached.sum())
    stats = result.statistics

    def over_reached(name: str, how: str) -> float | None:
        if not n:
            return None
        values = stats[name][reached]
        return float(values.min() if how == "min" else values.max() if how == "max"
                     else values.mean())  # fmt: skip

    return {
        "samples": result.samples_used,
        "samples_in_grid": int(result.samples.sum()),
        "voxels": int(reached.size),
        "reached_voxels": n,
        _size_key(result): n * result.grid.cell_measure,
        "mean_reachability_index": float(result.reachability_index[reached].mean()) if n else 0.0,
        "full_orientation_voxels": int((result.reachability_index[reached] >= 1.0).sum()),
        "manipulability_min": over_reached("manipulability_min", "min"),
        "manipulability_max": over_reached("manipulability_max", "max"),
        "inverse_condition_mean": over_reached("inverse_condition_mean", "mean"),
        "inverse_condition_max": over_reached("inverse_condition_max", "max"),
    }


def run_serial_workspace_map(spec: SerialWorkspaceMapSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + data files + figures out."""
    progress = ProgressReporter(ctx)
    progress.report(0.0, "sampling")
    arm = spec.arm()
    grid = spec.grid(arm)
    settings = MapSettings(spec.samples, spec.sampler, spec.seed, spec.orientation_bins,
                           spec.characteristic_length)  # fmt: skip
    result = workspace_map(arm, grid, settings,
                           on_chunk=lambda done, total: progress.report(
                               80.0 * done / total, f"{done:,} of {total:,} samples"))  # fmt: skip
    planar = arm.planar
    bands, cells = (
        (1, spec.orientation_bins) if planar else sphere_bin_layout(spec.orientation_bins)
    )
    document = {
        "arm": arm_description(spec.robot, arm),
        "length_unit": spec.length_unit,
        "characteristic_length": spec.characteristic_length,
        "sampler": spec.sampler,
        "seed": spec.seed,
        "voxel_size": spec.voxel_size,
        "orientation_bins": {
            "count": spec.orientation_bins,
            "of": "tool angle phi" if planar else "tool axis (z of the tool frame)",
            "bands": bands,
            "cells_per_band": cells,
        },
        "grid": {
            "axes": ["x", "y"] if planar else ["x", "y", "z"],
            "shape": list(grid.shape),
            "first": [float(a[0]) for a in grid.axes],
            "last": [float(a[-1]) for a in grid.axes],
            "cell": "pixel" if planar else "voxel",
        },
        "summary": _summary(result),
        "convergence": convergence_report(result, spec.convergence_tolerance),
    }
    progress.report(80.0, "files")
    artifacts: tuple[Artifact, ...] = workspace_files(result, spec.model_dump(mode="json"),
                                                      spec.length_unit)  # fmt: skip
    if spec.plots:
        progress.report(85.0, "plots")
        artifacts += figure_artifacts(slices_figure(result, spec.length_unit), "workspace_slices",
                                      "Reachability index: slices through the grid")  # fmt: skip
        artifacts += figure_artifacts(scatter_figure(result, spec.length_unit), "workspace_3d",
                                      "Reached voxels in 3-D")  # fmt: skip
        histograms = "Histograms of the indices over the reached voxels"
        artifacts += figure_artifacts(histogram_figure(result), "workspace_histograms", histograms)
    progress.report(100.0, "done")
    return JobOutcome(result=document, artifacts=artifacts, notes=tuple(_notes(spec, document)))


def _notes(spec: SerialWorkspaceMapSpec, document: dict[str, Any]) -> list[str]:
    planar = document["arm"]["planar"]
    cell = "pixel" if planar else "voxel"
    notes = [
        f"Node-centred {cell}s of {spec.voxel_size:g} {spec.length_unit} at multiples of "
        f"the {cell} size; a sample counts in the {cell} of its nearest node.",
        "The reachability index is the fraction of "
        + ("tool-angle phi bins over [-180, 180) deg" if planar
           else "equal-area tool-axis cells on the sphere")
        + f" ({spec.orientation_bins}) reached by a sample in the {cell}.",
    ]  # fmt: skip
    summary = document["summary"]
    if summary["samples_in_grid"] < summary["samples"]:
        notes.append(f"{summary['samples'] - summary['samples_in_grid']:,} samples fell "
                     "outside the bounds.")  # fmt: skip
    if not document["convergence"]["met"]:
        notes.append("Not converged: the last doubling of the samples changed the reached "
                     "volume or the mean index by more than the tolerance; use more samples "
                     "or larger voxels.")  # fmt: skip
    if spec.characteristic_length is not None:
        notes.append(f"The inverse condition number divides the linear rows by the "
                     f"characteristic length {spec.characteristic_length:g} "
                     f"{spec.length_unit}.")  # fmt: skip
    return notes
