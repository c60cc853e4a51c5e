"""The ``planar2dof-conditioning-map`` job: 1/kappa and pressure angles over a grid
(Huang et al. 2004, eqs 2, 7, 15; Figs 4-5; docs/methods/planar-parallel.md).

For one robot of Fig. 1 in one working mode: reachability, 1/kappa, both pressure angles
and beta_min at every grid node; W_kappa0's boundary and area when a limit is given; the
isotropic point; exact values at the given points; CSV/NPZ data and two contour plots.
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.common.figures import figure_artifacts
from worker.common.grids import WorkspaceGrid
from worker.common.progress import ProgressReporter
from worker.contract import Artifact, JobContext, JobOutcome
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.errata import conditioning_map_errata_notes
from worker.families.planar_parallel.jobs.architecture import (
    describe_architecture,
    map_grid,
    robot_from_spec,
)
from worker.families.planar_parallel.jobs.kappa_region import (
    KappaRegionSection,
    kappa_region_section,
)
from worker.families.planar_parallel.jobs.map_files import CSV_NAME, NPZ_NAME, map_files
from worker.families.planar_parallel.jobs.point_values import point_entries, unreachable_note
from worker.families.planar_parallel.plots import conditioning as plots
from worker.families.planar_parallel.specs import ConditioningMapSpec

__all__ = ["MAP_ROW_BLOCKS", "run_conditioning_map"]

FloatArray = NDArray[np.float64]
#: Row blocks of the map (so that progress moves on large grids).
MAP_ROW_BLOCKS = 10
ISOTROPIC_POINT_METHOD = (
    "closed form where one exists (eq 12 in mode [1, -1]; telescopic legs: (0, -e); linear "
    "drives with m2 = -m1: (0, -l2/√2)), else the largest 1/kappa on x = 0 below the base "
    "(4001 samples, then bounded Brent)"
)
#: Below this pressure angle (deg) the direct Jacobian A counts as singular.
DEGENERATE_PRESSURE_ANGLE_DEG = 1.0
FIGURE_4_TITLE = "Conditioning index 1/kappa over the workspace (Fig. 4)"
FIGURE_5_TITLE = "Minimum pressure angle beta_min over the workspace (Fig. 5)"


def run_conditioning_map(spec: ConditioningMapSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + artifacts + notes out."""
    progress = ProgressReporter(ctx)
    progress.report(0.0, "starting")
    robot = robot_from_spec(spec)  # the job's one checked robot, passed on
    arch = robot.arch
    grid = map_grid(spec.grid, arch)
    cmap = _grid_map(robot, grid, progress)

    region = None
    if spec.inverse_condition_limit is not None:
        progress.report(42.0, "W_kappa0 boundary")
        region = kappa_region_section(robot, spec.inverse_condition_limit, grid,
                                      cmap.inverse_condition, spec.length_unit)  # fmt: skip
    progress.report(45.0, "isotropic point and given points")
    points = np.asarray(spec.points or (), dtype=float).reshape(-1, 2)
    entries = point_entries(robot, points)
    isotropic = _isotropic_entry(robot)

    result = _result(spec, arch, grid, cmap, region, isotropic, entries)
    notes = _notes(spec, arch, cmap, region, isotropic, entries)
    errata = conditioning_map_errata_notes(spec)

    artifacts: tuple[Artifact, ...] = ()
    if spec.plots:
        artifacts = _plots(spec, arch, grid, cmap, points, isotropic, progress)
    progress.report(70.0, "data files")
    artifacts += map_files(spec, arch, grid, cmap, region, progress)
    progress.report(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(notes), errata=tuple(errata))


def _grid_map(robot: pp.Robot, grid: WorkspaceGrid, progress: ProgressReporter
              ) -> pp.ConditioningMap:  # fmt: skip
    """The map in row blocks (progress 2-40 %), joined into one ConditioningMap."""
    x, y = grid.x, grid.y
    edges = np.linspace(0, y.size, min(MAP_ROW_BLOCKS, y.size) + 1).astype(int).tolist()
    blocks = []
    on_block = progress.span(2.0, 40.0, "conditioning map")
    for start, stop in itertools.pairwise(edges):
        blocks.append(pp.robot_map(robot, x, y[start:stop]))
        on_block(stop, y.size)
    return pp.ConditioningMap(
        x,
        y,
        reachable=np.concatenate([b.reachable for b in blocks]),
        inverse_condition=np.concatenate([b.inverse_condition for b in blocks]),
        pressure_angles=np.concatenate([b.pressure_angles for b in blocks]),
        min_pressure_angle=np.concatenate([b.min_pressure_angle for b in blocks]),
        joints=np.concatenate([b.joints for b in blocks]),
    )


def _isotropic_entry(robot: pp.Robot) -> dict[str, Any] | None:
    """The isotropic (or best-conditioned) point on x = 0 below the base, or None.

    ``degenerate``: a pressure angle there is below :data:`DEGENERATE_PRESSURE_ANGLE_DEG`,
    so A is (nearly) singular and 1/kappa -> 1 only because sigma_1 = sigma_2 -> infinity
    (the paper's right-triangle configuration, Fig. 3, eq 9): not a usable optimum.
    """
    x, y = pp.robot_isotropic_point(robot)
    if not (math.isfinite(x) and math.isfinite(y)):
        return None
    point = np.array([x, y])
    value = float(pp.robot_inverse_condition(robot, point))
    beta = float(np.degrees(np.min(pp.robot_pressure_angles(robot, point))))
    if not (math.isfinite(value) and math.isfinite(beta)):  # out of reach by a rounding hair
        return None
    degenerate = not beta >= DEGENERATE_PRESSURE_ANGLE_DEG
    return {
        "x": x,
        "y": y,
        "inverse_condition": value,
        "min_pressure_angle_deg": beta,
        "isotropic": value >= 1.0 - 1e-9 and not degenerate,
        "degenerate": degenerate,
    }


def _stats(values: FloatArray) -> dict[str, float | None]:
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return {"min": None, "max": None, "mean": None}
    return {"min": float(finite.min()), "max": float(finite.max()), "mean": float(finite.mean())}


def _result(
    spec: ConditioningMapSpec,
    arch: pp.Architecture,
    grid: WorkspaceGrid,
    cmap: pp.ConditioningMap,
    region: KappaRegionSection | None,
    isotropic: dict[str, Any] | None,
    entries: list[dict[str, Any]],
) -> dict[str, Any]:
    reachable = int(cmap.reachable.sum())
    return {
        "actuation": spec.actuation,
        "l1": spec.l1,
        "l2": spec.l2,
        "e": arch.e if spec.actuation != "linear-drive" else spec.e,
        "delta": arch.l2 / arch.l1 if spec.actuation == "proximal-arm" else None,
        "architecture": spec.architecture or "given",
        "working_mode": list(spec.working_mode),
        "length_unit": spec.length_unit,
        "isotropic_point": isotropic,
        "summary": {
            "reachable_points": reachable,
            "reachable_area_grid": reachable * grid.cell_area,
            "inverse_condition": _stats(cmap.inverse_condition),
            "min_pressure_angle_deg": _stats(np.degrees(cmap.min_pressure_angle)),
        },
        "w_kappa0": None if region is None else region.entry,
        "points": entries,
        "discretisation": {
            "grid": grid.describe(),
            "w_kappa0": None if region is None else region.search,
            "points": "exact (closed forms, eqs 2, 7, 15)",
            "isotropic_point": ISOTROPIC_POINT_METHOD,
        },
        "data": {"csv": CSV_NAME, "npz": NPZ_NAME},
    }


def _notes(
    spec: ConditioningMapSpec,
    arch: pp.Architecture,
    cmap: pp.ConditioningMap,
    region: KappaRegionSection | None,
    isotropic: dict[str, Any] | None,
    entries: list[dict[str, Any]],
) -> list[str]:
    notes: list[str] = []
    m1, m2 = spec.working_mode
    if not cmap.reachable.any():
        notes.append(f"No grid node is reachable in working mode [{m1:+d}, {m2:+d}]: "
                     "enlarge the grid or check the dimensions.")  # fmt: skip
    if spec.actuation == "telescopic-leg":
        notes.append("Telescopic legs: A = E2, so both pressure angles are 90° everywhere; "
                     "l1 and l2 are not used and the working mode does not matter.")  # fmt: skip
    elif spec.actuation == "linear-drive":
        notes.append("Linear drives: the sliders share the x axis, so e and l1 are not used, "
                     "and 1/kappa does not depend on x.")  # fmt: skip
    if isotropic is None:
        notes.append("No point on x = 0 below the base has 1/kappa > 0: no isotropic point.")
    elif isotropic["degenerate"]:
        notes.append(
            f"No isotropic point in working mode [{m1:+d}, {m2:+d}]: the largest 1/kappa on "
            f"x = 0 below the base, {isotropic['inverse_condition']:.6f} at "
            f"({isotropic['x']:.6g}, {isotropic['y']:.6g}), is where the links fold "
            f"(pressure angle {isotropic['min_pressure_angle_deg']:.3g}°): A is singular and "
            "sigma_1 = sigma_2 -> infinity (the paper's right-triangle case, eq 9), not an "
            "optimum. It is not drawn."
        )
    elif not isotropic["isotropic"]:
        notes.append(
            f"No isotropic point (1/kappa = 1) in working mode [{m1:+d}, {m2:+d}]: the best "
            f"on x = 0 below the base is ({isotropic['x']:.6g}, {isotropic['y']:.6g}) with "
            f"1/kappa = {isotropic['inverse_condition']:.6f}."
        )
    if region is not None:
        notes += region.notes
    notes += unreachable_note(entries, spec.working_mode)
    return notes


def _plots(
    spec: ConditioningMapSpec,
    arch: pp.Architecture,
    grid: WorkspaceGrid,
    cmap: pp.ConditioningMap,
    points: FloatArray,
    isotropic: dict[str, Any] | None,
    progress: ProgressReporter,
) -> tuple[Artifact, ...]:
    """The two contour maps (progress 48-70 %)."""
    joints = None if spec.actuation == "linear-drive" else [[arch.e, 0.0], [-arch.e, 0.0]]
    common: dict[str, Any] = {
        "inverse_condition_limit": spec.inverse_condition_limit,
        "points": points if points.size else None,
        "joints": joints,
        "isotropic_point": (
            (isotropic["x"], isotropic["y"])
            if isotropic is not None and not isotropic["degenerate"]
            else None
        ),
        "subtitle": describe_architecture(spec, arch),
        # A linear drive's 1/kappa does not depend on x: isotropic along a whole line.
        "isotropic_line": spec.actuation == "linear-drive",
        "length_unit": spec.length_unit,
    }
    progress.report(48.0, "plot of 1/kappa")
    conditioning = plots.inverse_condition_map_figure(
        grid.x, grid.y, cmap.inverse_condition,
        title=rf"Conditioning index $1/\kappa$, {spec.actuation} robot", **common,
    )  # fmt: skip
    first = figure_artifacts(conditioning, "inverse_condition_map", FIGURE_4_TITLE)
    progress.report(59.0, "plot of beta_min")
    pressure = plots.pressure_angle_map_figure(
        grid.x, grid.y, np.degrees(cmap.min_pressure_angle),
        inverse_condition=cmap.inverse_condition,
        title=rf"Minimum pressure angle $\beta_{{\min}}$, {spec.actuation} robot",
        constant_reason=(
            "both pressure angles are 90° everywhere: a telescopic leg pushes along itself"
            if spec.actuation == "telescopic-leg"
            else None
        ),
        **common,
    )  # fmt: skip
    second = figure_artifacts(pressure, "pressure_angle_map", FIGURE_5_TITLE)
    return (*first, *second)
