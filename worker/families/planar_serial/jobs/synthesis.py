"""The ``planar3r-synthesis`` job: link lengths by the paper's eqs (10)-(11), then checked.

From the task points or a trajectory: the exact distance range [d_min, d_max] from the
base, the design l1 = (d_max + l3)/2 + 1, l2 = (d_max + l3)/2, Grashof's criterion at
both ends of the range, and the design's d_z in the paper's three cases (Patel & Sobh
§5): 1 ideal, 2 with l2 and l3 swapped, 3 under joint limits.
docs/methods/planar-serial.md holds the corrections this job reports in ``notes`` (those
on the paper's examples also in ``paper_errata``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.common.data_export import DIMENSIONLESS, job_metadata, npz_artifact
from worker.common.figures import figure_artifacts
from worker.common.progress import ProgressReporter
from worker.contract import Artifact, JobContext, JobOutcome
from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.errata import synthesis_errata_notes
from worker.families.planar_serial.jobs.design_checks import (
    design_notes,
    full_dexterity_condition,
    grashof_checks,
    paper_conditions,
)
from worker.families.planar_serial.jobs.dexterity_evaluation import (
    FULL_DEXTERITY_TOL,
    LimitedJoints,
    Links,
    WorkspaceGrid,
    grid_dexterity,
    limited_joints,
    map_method,
    orientations,
    point_dexterity,
    point_method,
    workspace_grid,
)
from worker.families.planar_serial.jobs.task_points import shortfall_notes, task_point_entries
from worker.families.planar_serial.jobs.trajectories import (
    task_distance_range,
    trajectory_path,
    trajectory_samples,
    trajectory_summary,
)
from worker.families.planar_serial.kinematics.inputs import Arm
from worker.families.planar_serial.kinematics.trajectory import DistanceRange
from worker.families.planar_serial.plots import figures as plots
from worker.families.planar_serial.specs import SynthesisSpec

__all__ = ["CaseResult", "run_synthesis"]

FloatArray = NDArray[np.float64]
CASE_NAMES = {1: "ideal", 2: "l2-l3-swapped", 3: "joint-limited"}
CASE_LABELS = {1: "Case 1: ideal", 2: "Case 2: l2 and l3 swapped", 3: "Case 3: joint limits"}
#: The same, as the figure writes them (mathtext).
FIGURE_CASE_LABELS = {
    1: "Case 1: ideal",
    2: "Case 2: $l_2$ and $l_3$ swapped",
    3: "Case 3: joint limits",
}


@dataclass(frozen=True)
class CaseResult:
    """One of the paper's cases: its design, its map on the plot grid, its evaluations."""

    case: int
    links: Links
    sampling: LimitedJoints | None
    limited: bool
    d_z: FloatArray  # (ny, nx) on the plot grid
    task_points: list[dict[str, Any]]
    trajectory: dict[str, float | int] | None


def run_synthesis(spec: SynthesisSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + artifacts + notes out."""
    progress = ProgressReporter(ctx)
    progress.report(0.0, "distance range and design")
    source = "trajectory" if spec.trajectory is not None else "task_points"
    distances = task_distance_range(spec.trajectory, spec.task_points)
    d_min_used, d_max_used = distances.d_min, distances.d_max
    if spec.round_distances:
        d_min_used, d_max_used = float(math.floor(d_min_used)), float(math.ceil(d_max_used))
    links = planar_serial.synthesise_links(d_min_used, d_max_used, spec.l3)
    l1, l2, l3 = links
    grid = workspace_grid(spec.grid, links)
    sampling = limited_joints(spec.joint_limits_deg, spec.orientation_step_deg, spec.method)

    designs: list[tuple[int, Links, LimitedJoints | None, bool]] = [
        (1, links, None, False),
        (2, Arm(l1, l3, l2), None, False),
    ]
    if spec.joint_limits_deg is not None:
        designs.append((3, links, sampling, True))
    weights = [1.0 if s is None else float(s.evaluations_per_point) for _, _, s, _ in designs]
    edges = np.concatenate([[0.0], np.cumsum(weights)]) / sum(weights) * 83.0 + 5.0
    cases = [
        _evaluate_case(spec, grid, *design, progress.span(lo, hi, CASE_LABELS[design[0]]))
        for design, lo, hi in zip(designs, edges[:-1], edges[1:], strict=True)
    ]

    result = {
        "distance_source": source,
        "d_min": distances.d_min,
        "d_max": distances.d_max,
        "d_min_at": [float(v) for v in distances.at_min],
        "d_max_at": [float(v) for v in distances.at_max],
        "round_distances": spec.round_distances,
        "d_min_used": d_min_used,
        "d_max_used": d_max_used,
        "l3": spec.l3,
        "links": list(links),
        "grashof": grashof_checks(links, distances.d_min, distances.d_max),
        "paper_conditions": paper_conditions(links, distances.d_min, distances.d_max),
        "full_dexterity_bands": [list(b) for b in planar_serial.full_dexterity_bands(links)],
        "full_dexterity_condition": full_dexterity_condition(
            links, distances.d_min, distances.d_max
        ),
        "task_points": cases[0].task_points,
        "cases": [_case_entry(spec, grid, case) for case in cases],
        "discretisation": {
            "grid": grid.describe(),
            **orientations(sampling),
            "task_points": point_method(sampling),
            "trajectory_samples": None if spec.trajectory is None else spec.trajectory.samples,
        },
        "length_unit": spec.length_unit,
    }
    notes = design_notes(spec, links, distances, d_min_used, d_max_used)
    notes += _case_notes(spec, distances, cases)
    errata = synthesis_errata_notes(spec, result)

    progress.report(90.0, "plots")
    artifacts = _artifacts(spec, grid, cases)
    progress.report(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(notes), errata=tuple(errata))


def _task_xy(spec: SynthesisSpec) -> FloatArray:
    return np.asarray(spec.task_points or (), dtype=float).reshape(-1, 2)


def _evaluate_case(
    spec: SynthesisSpec,
    grid: WorkspaceGrid,
    case: int,
    links: Links,
    sampling: LimitedJoints | None,
    limited: bool,
    on_progress: Callable[[int, int], None],
) -> CaseResult:
    d_z = grid_dexterity(links, grid, sampling, on_progress)
    task_xy = _task_xy(spec)
    entries = task_point_entries(
        spec.labels,
        task_xy,
        point_dexterity(links, task_xy, sampling),
        planar_serial.paper_regions(links, np.hypot(task_xy[:, 0], task_xy[:, 1])),
    )
    trajectory = None
    if spec.trajectory is not None:
        path = trajectory_samples(spec.trajectory)
        trajectory = trajectory_summary(point_dexterity(links, path, sampling))
    return CaseResult(case, links, sampling, limited, d_z, entries, trajectory)


def _case_entry(spec: SynthesisSpec, grid: WorkspaceGrid, case: CaseResult) -> dict[str, Any]:
    exact = case.sampling is None
    bands = planar_serial.full_dexterity_bands(case.links)
    inner, outer = planar_serial.reach_radii(case.links)
    reachable_area = math.pi * (outer**2 - inner**2)
    full_area = planar_serial.band_area(bands)
    full_grid = int(np.count_nonzero(case.d_z >= 1.0 - FULL_DEXTERITY_TOL)) * grid.cell_area
    reachable_grid = int(np.count_nonzero(case.d_z > 0.0)) * grid.cell_area
    if not exact:  # the joint-limited arm's own areas, counted on its map
        full_area, reachable_area = full_grid, reachable_grid
    short = [e for e in case.task_points if e["d_z"] < 1.0 - FULL_DEXTERITY_TOL]
    return {
        "case": case.case,
        "name": CASE_NAMES[case.case],
        "links": list(case.links),
        "joint_limits_deg": (
            [list(p) for p in spec.joint_limits_deg]
            if case.limited and spec.joint_limits_deg is not None
            else None
        ),
        "method": map_method(case.sampling),
        "full_dexterity_bands": [list(b) for b in bands] if exact else None,
        "fully_dexterous_area": full_area,
        "reachable_area": reachable_area,
        "fully_dexterous_fraction": full_area / reachable_area if reachable_area > 0 else 0.0,
        "areas_method": "exact-closed-form"
        if exact
        else f"grid count of {map_method(case.sampling)} d_z (joint-limited arm)",
        "fully_dexterous_area_grid": full_grid,
        "reachable_area_grid": reachable_grid,
        "task_points": case.task_points,
        "trajectory": case.trajectory,
        "all_task_points_fully_dexterous": not short if case.task_points else None,
    }


def _case_notes(
    spec: SynthesisSpec, distances: DistanceRange, cases: list[CaseResult]
) -> list[str]:
    notes: list[str] = []
    if spec.trajectory is not None:
        outside = [
            e for e in cases[0].task_points
            if not distances.d_min <= e["distance"] <= distances.d_max
        ]  # fmt: skip
        notes += [
            f"Task point {e['label']} ({e['x']:g}, {e['y']:g}) at d = {e['distance']:.4f} lies "
            f"outside the trajectory's range [{distances.d_min:.4f}, {distances.d_max:.4f}], "
            "which alone set the design."
            for e in outside
        ]
    for case in cases:
        prefix = f"Case {case.case} ({CASE_NAMES[case.case]}): "
        notes += shortfall_notes(case.task_points, prefix)
        if case.trajectory is not None and case.trajectory["fully_dexterous_fraction"] < 1.0:
            notes.append(
                f"{prefix}the trajectory is fully dexterous at "
                f"{100 * case.trajectory['fully_dexterous_fraction']:.1f}% of its "
                f"{case.trajectory['samples']} samples (min d_z = "
                f"{case.trajectory['d_z_min']:.4f}, mean {case.trajectory['d_z_mean']:.4f})."
            )
    return notes


def _artifacts(
    spec: SynthesisSpec, grid: WorkspaceGrid, cases: list[CaseResult]
) -> tuple[Artifact, ...]:
    task_xy = _task_xy(spec)
    arrays = _case_arrays(spec, grid, cases, task_xy)
    data = npz_artifact(
        "synthesis_cases.npz",
        arrays,
        "d_z maps of the cases (NumPy arrays)",
        units={n: DIMENSIONLESS if n.startswith("d_z") else spec.length_unit for n in arrays},
        axes={
            "task_points": ("task_point", "xy"),
            **({"trajectory_samples": ("sample", "xy")} if "trajectory_samples" in arrays else {}),
            **{n: ("y", "x") for n in arrays if n.startswith("d_z_case")},
            **{n: ("link",) for n in arrays if n.startswith("links_case")},
        },
        metadata=job_metadata("planar3r-synthesis", spec.model_dump(mode="json")),
    )
    if not spec.plots:
        return (data,)
    path = None if spec.trajectory is None else trajectory_path(spec.trajectory)
    panels = [
        plots.CasePanel(
            label=FIGURE_CASE_LABELS[case.case],
            links=case.links,
            x=grid.x,
            y=grid.y,
            d_z=np.where(case.d_z > 0.0, case.d_z, np.nan),
            bands=planar_serial.full_dexterity_bands(case.links),
            region_radii=planar_serial.region_radii(case.links),
            joint_limited=case.limited,
        )
        for case in cases
    ]
    l1, l2, l3 = cases[0].links
    figure = plots.synthesis_cases_figure(
        panels,
        task_points=task_xy if task_xy.size else None,
        task_labels=spec.labels if task_xy.size else None,
        trajectory=path,
        title=f"Synthesised design ({l1:.6g}, {l2:.6g}, {l3:.6g}): the paper's cases",
        length_unit=spec.length_unit,
    )
    return (
        *figure_artifacts(figure, "synthesis_cases", "d_z of the design in the paper's cases"),
        data,
    )


def _case_arrays(
    spec: SynthesisSpec, grid: WorkspaceGrid, cases: list[CaseResult], task_xy: NDArray[Any]
) -> dict[str, NDArray[np.generic]]:
    arrays: dict[str, NDArray[np.generic]] = {"x": grid.x, "y": grid.y, "task_points": task_xy}
    if spec.trajectory is not None:
        arrays["trajectory_samples"] = trajectory_samples(spec.trajectory)
    for case in cases:
        arrays[f"d_z_case{case.case}"] = case.d_z
        arrays[f"links_case{case.case}"] = np.asarray(case.links)
    return arrays
