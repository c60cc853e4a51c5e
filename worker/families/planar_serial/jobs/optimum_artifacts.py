"""Figures and data files of ``planar3r-design``.

* ``design_maps`` (PNG, SVG): d_z maps of the paper's rule and of the optimum side by
  side, in the task's frame (each arm's base where it is), with the task points and the
  trajectory;
* ``convergence`` (PNG, SVG): the best design per generation of every start (the kept
  one in front) against the paper's rule;
* ``design_maps.npz``: both maps, the designs, the task points and trajectory samples;
* ``convergence.csv``: one row per start and generation (smallest d_z, total length,
  score).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.common.data_export import DIMENSIONLESS, column, columns_csv, job_metadata, npz_artifact
from worker.common.figures import figure_artifacts
from worker.common.grids import WorkspaceGrid
from worker.contract import Artifact
from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.design_spec import DesignSpec
from worker.families.planar_serial.jobs.design_objective import dexterity_at
from worker.families.planar_serial.jobs.link_search import SearchOutcome
from worker.families.planar_serial.jobs.trajectories import trajectory_path
from worker.families.planar_serial.plots import figures as plots
from worker.families.planar_serial.plots.convergence import convergence_figure

__all__ = ["design_artifacts", "design_grid"]

FloatArray = NDArray[np.float64]
#: Half-width of the default map, as a multiple of the farthest reach from the origin.
MAP_MARGIN = 1.05


def design_grid(spec: DesignSpec, designs: list[dict[str, Any]]) -> WorkspaceGrid:
    """The requested grid, or a square about the origin holding every design's reach."""
    if spec.grid.bounds is not None:
        return WorkspaceGrid(spec.grid.bounds, spec.grid.points_per_axis)
    reach = max(math.hypot(*d["base"]) + d["total_length"] for d in designs)
    half = MAP_MARGIN * reach
    return WorkspaceGrid((-half, half, -half, half), spec.grid.points_per_axis)


def design_artifacts(
    spec: DesignSpec,
    result: dict[str, Any],
    outcome: SearchOutcome,
    task_xy: FloatArray,
    path_samples: FloatArray | None,
) -> tuple[Artifact, ...]:
    limits = (
        None
        if result["method"] == "exact-closed-form"
        else np.radians(np.asarray(spec.joint_limits_deg, dtype=float))
    )
    designs = [("optimum", result["optimum"])]
    if result["paper_rule"] is not None:
        designs.insert(0, ("paper_rule", result["paper_rule"]))
    grid = design_grid(spec, [d for _, d in designs])
    maps = {
        name: dexterity_at(tuple(d["links"]), tuple(d["base"]), grid.points(), limits)
        for name, d in designs
    }
    artifacts: tuple[Artifact, ...] = ()
    if spec.plots:
        artifacts += _figures(spec, result, outcome, grid, maps, task_xy, limits is not None)
    artifacts += (
        _maps_npz(spec, result, grid, maps, task_xy, path_samples),
        _convergence_csv(spec, outcome),
    )
    return artifacts


def _figures(
    spec: DesignSpec,
    result: dict[str, Any],
    outcome: SearchOutcome,
    grid: WorkspaceGrid,
    maps: dict[str, FloatArray],
    task_xy: FloatArray,
    limited: bool,
) -> tuple[Artifact, ...]:
    labels = {"paper_rule": "The paper's rule (eqs 10–11)", "optimum": "Optimum"}
    panels = []
    for name, d_z in maps.items():
        design = result[name]
        panels.append(plots.CasePanel(
            label=f"{labels[name]}: min $d_z$ = {design['min_dz']:.4f}",
            links=tuple(design["links"]), x=grid.x, y=grid.y,
            d_z=np.where(d_z > 0.0, d_z, np.nan),
            bands=planar_serial.full_dexterity_bands(design["links"]),
            region_radii=planar_serial.region_radii(design["links"]),
            joint_limited=limited, base=tuple(design["base"]),
        ))  # fmt: skip
    path = None if spec.trajectory is None else trajectory_path(spec.trajectory)
    maps_figure = plots.synthesis_cases_figure(
        panels, task_points=task_xy if task_xy.size else None,
        task_labels=spec.labels if task_xy.size else None, trajectory=path,
        title="Link lengths designed for the task under its joint limits"
        if limited else "Link lengths designed for the task",
        length_unit=spec.length_unit,
    )  # fmt: skip
    minimise_length = spec.objective == "min_length"
    key = "total_length" if minimise_length else "min_dz"
    kept = outcome.kept
    history = kept.history
    rule = result["paper_rule"]
    curve = convergence_figure(
        [entry[key] for entry in history],
        other_starts=[[entry[key] for entry in start.history]
                      for start in outcome.starts if start is not kept],
        optimum=result["optimum"][key],
        paper_rule=None if rule is None else rule[key],
        quantity=(f"total length $l_1 + l_2 + l_3$ [{spec.length_unit}]" if minimise_length
                  else r"smallest $d_z$ over the task [-]"),
        title="Convergence of the design search",
        met=[entry["min_dz"] >= spec.dz_target - 1e-12 for entry in history]
        if minimise_length else None,
        paper_rule_note="misses the target" if minimise_length and rule is not None
        and not rule["meets_target"] else "",
    )  # fmt: skip
    return (
        *figure_artifacts(maps_figure, "design_maps", "d_z of the paper's rule and the optimum"),
        *figure_artifacts(curve, "convergence", "Best design per generation of every start"),
    )


def _maps_npz(
    spec: DesignSpec,
    result: dict[str, Any],
    grid: WorkspaceGrid,
    maps: dict[str, FloatArray],
    task_xy: FloatArray,
    path_samples: FloatArray | None,
) -> Artifact:
    length = spec.length_unit
    arrays: dict[str, NDArray[np.generic]] = {"x": grid.x, "y": grid.y, "task_points": task_xy}
    units = {"x": length, "y": length, "task_points": length}
    axes: dict[str, tuple[str, ...]] = {"task_points": ("task_point", "xy")}
    if path_samples is not None:
        arrays["trajectory_samples"] = path_samples
        units["trajectory_samples"] = length
        axes["trajectory_samples"] = ("sample", "xy")
    for name, d_z in maps.items():
        arrays[f"d_z_{name}"] = d_z
        arrays[f"links_{name}"] = np.asarray(result[name]["links"])
        arrays[f"base_{name}"] = np.asarray(result[name]["base"])
        units.update({f"d_z_{name}": DIMENSIONLESS, f"links_{name}": length,
                      f"base_{name}": length})  # fmt: skip
        axes.update({f"d_z_{name}": ("y", "x"), f"links_{name}": ("link",),
                     f"base_{name}": ("xy",)})  # fmt: skip
    return npz_artifact(
        "design_maps.npz", arrays, "d_z maps of the paper's rule and the optimum (NumPy arrays)",
        units=units, axes=axes,
        metadata=job_metadata("planar3r-design", spec.model_dump(mode="json")),
    )  # fmt: skip


def _convergence_csv(spec: DesignSpec, outcome: SearchOutcome) -> Artifact:
    rows = [(start.index, entry) for start in outcome.starts for entry in start.history]
    columns = {
        column("start", DIMENSIONLESS): np.array([index for index, _ in rows], dtype=int),
        column("generation", DIMENSIONLESS): np.array(
            [e["generation"] for _, e in rows], dtype=int
        ),
        column("min_dz", DIMENSIONLESS): np.array([e["min_dz"] for _, e in rows]),
        column("total_length", spec.length_unit): np.array([e["total_length"] for _, e in rows]),
        column("score", DIMENSIONLESS): np.array([e["score"] for _, e in rows]),
    }
    return columns_csv("convergence.csv", columns, "Best design per start and generation (CSV)")
