"""The ``planar3r-dexterity-map`` job: d_z and D = d_z/3 over a grid (Patel & Sobh §2, §5).

Exact closed form with fully revolute joints; under joint limits exact events (the
default) or orientation sampling, both elbow branches (docs/methods/planar-serial.md).
Reports the paper's regions next to the exact full-dexterity bands, areas (of the
limited arm under joint limits), the task points and a trajectory, with CSV/NPZ data and
three plots (heat map, 3-D surface, radial section).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.common.figures import figure_artifacts
from worker.common.progress import ProgressReporter
from worker.contract import Artifact, JobContext, JobOutcome
from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.errata import dexterity_map_errata_notes
from worker.families.planar_serial.jobs.data_export import dexterity_map_files
from worker.families.planar_serial.jobs.dexterity_evaluation import (
    RADIAL_ANGLE_DEG,
    RADIAL_SAMPLES,
    LimitedJoints,
    Links,
    WorkspaceGrid,
    grid_dexterity,
    limited_joints,
    map_method,
    orientations,
    point_dexterity,
    point_method,
    radial_reach,
    workspace_grid,
)
from worker.families.planar_serial.jobs.map_notes import (
    map_notes,
    map_warnings,
    unreachable_labels,
)
from worker.families.planar_serial.jobs.map_statistics import map_areas, map_summary
from worker.families.planar_serial.jobs.regions import (
    Bands,
    LimitedRay,
    limited_ray_profile,
    region_table,
)
from worker.families.planar_serial.jobs.task_points import task_point_entries
from worker.families.planar_serial.jobs.trajectories import (
    trajectory_path,
    trajectory_samples,
    trajectory_summary,
)
from worker.families.planar_serial.plots import figures as plots
from worker.families.planar_serial.specs import DexterityMapSpec

__all__ = ["RADIAL_SAMPLES", "run_dexterity_map"]

FloatArray = NDArray[np.float64]


def run_dexterity_map(spec: DexterityMapSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + artifacts + notes out."""
    progress = ProgressReporter(ctx)
    progress.report(0.0, "starting")
    links: Links = spec.links
    grid = workspace_grid(spec.grid, links)
    sampling = limited_joints(spec.joint_limits_deg, spec.orientation_step_deg, spec.method)
    d_z = grid_dexterity(links, grid, sampling, progress.span(2.0, 80.0, "dexterity map"))
    distance = np.hypot(*np.meshgrid(grid.x, grid.y))
    region = planar_serial.paper_regions(links, distance)

    progress.report(80.0, "task points and trajectory")
    task_xy = np.asarray(spec.task_points or (), dtype=float).reshape(-1, 2)
    task_entries = task_point_entries(
        spec.labels,
        task_xy,
        point_dexterity(links, task_xy, sampling),
        planar_serial.paper_regions(links, np.hypot(task_xy[:, 0], task_xy[:, 1])),
    )
    trajectory = None
    if spec.trajectory is not None:
        samples = trajectory_samples(spec.trajectory)
        trajectory = trajectory_summary(point_dexterity(links, samples, sampling))

    progress.report(85.0, "radial section")
    radial_d = np.linspace(0.0, radial_reach(links), RADIAL_SAMPLES)
    radial_dz = _radial_section(links, radial_d, sampling)

    progress.report(87.0, "regions along the ray")
    ray = None
    if sampling is not None:
        ray = limited_ray_profile(links, sampling.joint_limits_rad, RADIAL_ANGLE_DEG)
    warnings = map_warnings(spec, grid, int(np.count_nonzero(d_z > 0.0)), task_entries)
    bands = planar_serial.full_dexterity_bands(links)  # the unlimited arm's, computed once
    result = _result(spec, grid, sampling, ray, bands, d_z, task_entries, trajectory, warnings)
    notes = warnings + map_notes(
        spec, sampling, ray, task_entries, trajectory, result["regions"], bands
    )
    errata = dexterity_map_errata_notes(spec, result)

    artifacts: tuple[Artifact, ...] = ()
    if spec.plots:
        progress.report(90.0, "plots")
        path = None if spec.trajectory is None else trajectory_path(spec.trajectory)
        artifacts = _plots(spec, sampling, grid, bands, d_z, task_xy, path, (radial_d, radial_dz))
    progress.report(97.0, "data files")
    artifacts += dexterity_map_files(spec, grid, d_z, region)
    progress.report(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(notes), errata=tuple(errata))


def _radial_section(
    links: Links, distances: FloatArray, sampling: LimitedJoints | None
) -> FloatArray:
    angle = math.radians(RADIAL_ANGLE_DEG)
    points = np.stack([distances * math.cos(angle), distances * math.sin(angle)], axis=-1)
    if sampling is not None and sampling.sampled:
        return planar_serial.limited_orientation_dexterity(
            links, points, sampling.joint_limits_rad, sampling.requested_step_rad
        )
    return point_dexterity(links, points, sampling)


def _result(
    spec: DexterityMapSpec,
    grid: WorkspaceGrid,
    sampling: LimitedJoints | None,
    ray: LimitedRay | None,
    unlimited_bands: Bands,
    d_z: FloatArray,
    task_entries: list[dict[str, Any]],
    trajectory: dict[str, float | int] | None,
    warnings: list[str],
) -> dict[str, Any]:
    links = spec.links
    bands = unlimited_bands if ray is None else ray.bands
    areas = map_areas(links, grid, sampling, d_z, bands=unlimited_bands)
    if "unlimited_reference" in areas:
        areas["unlimited_reference"]["regions"] = region_table(links, bands=unlimited_bands)
    return {
        "links": list(links),
        "joint_limits_deg": _limits_list(spec),
        "length_unit": spec.length_unit,
        "method": map_method(sampling),
        "discretisation": {
            "grid": grid.describe(),
            **orientations(sampling),
            "task_points": point_method(sampling),
            "radial_section": {
                "angle_deg": RADIAL_ANGLE_DEG,
                "samples": RADIAL_SAMPLES,
                "d_to": radial_reach(links),
                "method": map_method(sampling),
            },
        },
        "regions": region_table(links, ray, bands=unlimited_bands),
        "full_dexterity_bands": [list(band) for band in bands],
        "areas": areas,
        "summary": {
            **map_summary(d_z),
            "unreachable_task_points": unreachable_labels(task_entries),
            "warnings": warnings,
        },
        "task_points": task_entries,
        "trajectory": trajectory,
        "data": {"csv": "dexterity_map.csv", "npz": "dexterity_map.npz"},
    }


def _limits_list(spec: DexterityMapSpec) -> list[list[float]] | None:
    if spec.joint_limits_deg is None:
        return None
    return [list(pair) for pair in spec.joint_limits_deg]


def _plots(
    spec: DexterityMapSpec,
    sampling: LimitedJoints | None,
    grid: WorkspaceGrid,
    bands: Bands,
    d_z: FloatArray,
    task_xy: FloatArray,
    path: FloatArray | None,
    radial: tuple[FloatArray, FloatArray],
) -> tuple[Artifact, ...]:
    links = spec.links
    limited = sampling is not None
    l1, l2, l3 = links
    title = f"3R arm ({l1:g}, {l2:g}, {l3:g}){', joint-limited' if limited else ''}"
    radii = planar_serial.region_radii(links)
    shown = np.where(d_z > 0.0, d_z, np.nan)  # NaN: drawn as unreachable
    labels = spec.labels if task_xy.size else None
    points = task_xy if task_xy.size else None
    heatmap = plots.dexterity_heatmap_figure(
        grid.x, grid.y, shown, links=links, region_radii=radii, bands=bands,
        task_points=points, task_labels=labels, trajectory=path,
        title=f"Dexterity map, {title}", length_unit=spec.length_unit,
        joint_limited=limited,
        limited_method="exact-events" if sampling is None else sampling.method,
    )  # fmt: skip
    surface = plots.dexterity_surface_figure(
        grid.x, grid.y, shown, title=f"Dexterity surface, {title}", length_unit=spec.length_unit
    )
    # Under joint limits the section holds only on its ray: task points off it are not marked.
    marked = not limited and task_xy.size > 0
    section = plots.radial_section_figure(
        *radial, region_radii=radii, bands=bands,
        task_distances=np.hypot(task_xy[:, 0], task_xy[:, 1]).tolist() if marked else None,
        task_labels=labels if marked else None, title=f"Radial section, {title}",
        length_unit=spec.length_unit, angle_deg=RADIAL_ANGLE_DEG,
        note=_sampling_note(sampling),
    )  # fmt: skip
    return (
        *figure_artifacts(heatmap, "heatmap", "Dexterity d_z over the workspace"),
        *figure_artifacts(surface, "surface", "Dexterity d_z, 3-D surface"),
        *figure_artifacts(section, "radial_section", "Dexterity d_z along a ray from the base"),
    )


def _sampling_note(sampling: LimitedJoints | None) -> str:
    """Under sampled joint limits, the staircase of the curve is the sampling."""
    if sampling is None:
        return ""
    if not sampling.sampled:
        return r"joint-limited $d_z$, exact (feasible orientation arcs between events)"
    return (
        rf"joint-limited $d_z$ sampled every {sampling.effective_step_deg:.4g}° of "
        rf"orientation: it comes in steps of $1/{sampling.samples:d}$ (the staircase)"
    )
