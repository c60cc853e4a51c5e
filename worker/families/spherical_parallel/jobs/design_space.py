"""The ``spm-design-space`` job: the feasible link angles per beta (Bai 2010 §4, eqs 14-19,
Figs 5-6; docs/methods/spherical-parallel.md).

For each beta (and gamma, or gamma = beta), f_min and f_max of f_i = n_i . v_i over the
continuous workspace and the rectangle |a1 - a2| <= acos(-f_min),
|a1 + a2 - 180| <= acos(f_max) in the alpha1-alpha2 plane, or that it is degenerate (a
line) or empty; optionally the conditioning index across one rectangle (Fig. 6).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from worker.common.data_export import (
    angle_or_pure,
    columns_csv,
    job_metadata,
    named_column,
    npz_artifact,
)
from worker.common.figures import figure_artifacts
from worker.common.progress import ProgressReporter
from worker.contract import Artifact, JobContext, JobOutcome
from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.errata import design_space_paper_notes
from worker.families.spherical_parallel.jobs.index_distribution import (
    IndexDistribution,
    best_designs,
    index_distribution,
    index_distribution_entry,
)
from worker.families.spherical_parallel.jobs.workspace_sampling import (
    kinematic_workspace,
    sampling_entry,
    workspace_entry,
    workspace_samples,
)
from worker.families.spherical_parallel.kinematics.axis_reach import search_grid_counts
from worker.families.spherical_parallel.plots import design_space as plots
from worker.families.spherical_parallel.specs import DesignSpaceSpec

__all__ = ["CSV_NAME", "NPZ_NAME", "design_space_rows", "run_design_space"]

CSV_NAME = "design_space.csv"
NPZ_NAME = "design_space.npz"
_CHUNK = 16  # betas per call to the kinematics (progress between calls)


def design_space_rows(
    spec: DesignSpaceSpec, ws: sp.Workspace, on_progress: Any = None
) -> list[dict[str, Any]]:
    """One entry per beta, in order (eqs 16-19)."""
    betas = spec.betas
    rows: list[dict[str, Any]] = []
    for start in range(0, len(betas), _CHUNK):
        chunk = betas[start : start + _CHUNK]
        if spec.identical_platforms:
            parts = [sp.design_space(ws, math.radians(b), [math.radians(b)]) for b in chunk]
        else:
            parts = [sp.design_space(ws, math.radians(spec.gamma_for(0.0)),
                                     np.radians(chunk))]  # fmt: skip
        for part in parts:
            for k in range(len(part.betas)):
                rows.append(_row(part, k))
        if on_progress is not None:
            on_progress(min(start + _CHUNK, len(betas)), len(betas))
    return rows


def _row(space: sp.DesignSpace, k: int) -> dict[str, Any]:
    d1, d2 = math.degrees(float(space.d1[k])), math.degrees(float(space.d2[k]))
    status = "empty" if space.empty[k] else "degenerate" if space.degenerate[k] else "rectangle"
    half = 0.5 * (d1 + d2)
    return {
        "beta_deg": round(math.degrees(float(space.betas[k])), 10),
        "gamma_deg": round(math.degrees(space.gamma), 10),
        "f_min": float(space.f_min[k]),
        "f_max": float(space.f_max[k]),
        "D1_deg": d1,
        "D2_deg": d2,
        "status": status,
        "degenerate": bool(space.degenerate[k]),
        "empty": bool(space.empty[k]),
        "rectangle": {
            "abs_alpha_difference_max_deg": d1,
            "abs_alpha_sum_minus_180_max_deg": d2,
            "corners_deg": plots.rectangle_corners(d1, d2).round(10).tolist(),
            "alpha1_range_deg": [90.0 - half, 90.0 + half],
            "alpha2_range_deg": [90.0 - half, 90.0 + half],
            "area_deg2": 2.0 * d1 * d2,
        },
    }


def run_design_space(spec: DesignSpaceSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + artifacts + notes out."""
    progress = ProgressReporter(ctx)
    progress.report(0.0, "design space")
    ws = kinematic_workspace(spec.workspace)
    rows = design_space_rows(spec, ws, progress.span(2.0, 50.0, "design space per beta"))
    dist = None
    result: dict[str, Any] = {
        "workspace": workspace_entry(spec.workspace),
        "identical_platforms": spec.identical_platforms,
        "gamma_deg": None if spec.identical_platforms else spec.gamma_for(0.0),
        "method": _method(spec),
        "designs": rows,
        "summary": _summary(rows),
        "index_map": None,
        "sampling": None,
        "data": {"csv": CSV_NAME, "npz": NPZ_NAME},
    }
    if spec.index_map is not None:
        progress.report(50.0, f"index over the rectangle of beta = {spec.index_map.beta_deg:g}")
        samples, layout = workspace_samples(spec.workspace)
        beta = spec.index_map.beta_deg
        dist = index_distribution(
            ws,
            samples,
            beta,
            spec.gamma_for(beta),
            spec.index_map.points_per_side,
            spec.index_map.branch,
        )
        result["index_map"] = index_distribution_entry(dist, samples)
        result["sampling"] = sampling_entry(layout)
    # The paper's Fig. 5 and §6.1 are reproduced: plain notes, not errata.
    notes = _notes(result) + design_space_paper_notes(spec, result)
    artifacts: tuple[Artifact, ...] = ()
    if spec.plots:
        progress.report(80.0, "plots")
        artifacts = _plots(spec, rows, dist)
    progress.report(95.0, "data files")
    artifacts += _data(spec, rows, dist)
    progress.report(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(notes))


def _method(spec: DesignSpaceSpec) -> str:
    if spec.workspace.full_turn:
        return ("closed form on the continuous workspace: with a full torsion turn v_i sweeps "
                "the band of polar angles [beta - T, beta + T] completely")  # fmt: skip
    n1, n2, n3 = search_grid_counts(kinematic_workspace(spec.workspace))
    return (f"least angle between v_1 and -/+ n_1 over the continuous workspace: the local "
            f"minima of a {n1} x {n2} x {n3} grid over (psi1, psi2, psi3) (psi1 every 10°, "
            "psi2 every T/8, psi3 at most every 15°, ends included), polished by projected "
            "Newton and Gauss-Newton steps")  # fmt: skip


def _summary(rows: list[dict[str, Any]]) -> dict[str, Any]:
    open_rows = [r for r in rows if r["status"] == "rectangle"]
    widest = max(open_rows, key=lambda r: r["rectangle"]["area_deg2"], default=None)
    return {
        "betas": len(rows),
        "rectangles": len(open_rows),
        "degenerate_betas_deg": [r["beta_deg"] for r in rows if r["status"] == "degenerate"],
        "empty_betas_deg": [r["beta_deg"] for r in rows if r["status"] == "empty"],
        "widest_beta_deg": None if widest is None else widest["beta_deg"],
    }


def _notes(result: dict[str, Any]) -> list[str]:
    summary = result["summary"]
    notes = []
    if summary["degenerate_betas_deg"]:
        notes.append(
            f"Degenerate (a line in the alpha1-alpha2 plane, no interior) at beta = "
            f"{', '.join(f'{b:g}' for b in summary['degenerate_betas_deg'])}°: only link "
            "angles on that line reach the whole workspace, every one of them on its edge."
        )
    if summary["empty_betas_deg"]:
        notes.append(
            f"Empty at beta = {', '.join(f'{b:g}' for b in summary['empty_betas_deg'])}°: only "
            "(90, 90) closes every leg, and there every leg is stretched or folded somewhere."
        )
    index_map = result["index_map"]
    if index_map is not None and index_map["degenerate"]:
        notes.append(f"The rectangle of beta = {index_map['beta_deg']:g}° has no interior: the "
                     "index map runs along its line and is not drawn.")  # fmt: skip
    return notes


def _plots(
    spec: DesignSpaceSpec, rows: list[dict[str, Any]], dist: IndexDistribution | None
) -> tuple[Artifact, ...]:
    ws = spec.workspace
    lo, hi = ws.torsion_deg
    torsion = "full torsion turn" if ws.full_turn else f"torsion [{lo:.10g}, {hi:.10g}]°"
    gamma = (
        r"$\gamma = \beta$" if spec.identical_platforms else rf"$\gamma$ = {spec.gamma_for(0.0):g}°"
    )
    subtitle = f"cone of {2 * ws.tilt_max_deg:.10g}° opening, {torsion}, {gamma}"
    spaces = [plots.SubDesignSpace(r["beta_deg"], r["gamma_deg"], r["D1_deg"], r["D2_deg"])
              for r in rows]  # fmt: skip
    fig = plots.design_space_figure(spaces, title="Design space: feasible link angles per "
                                    r"$\beta$ (eqs 16-19)", subtitle=subtitle)  # fmt: skip
    artifacts = figure_artifacts(fig, "design_space", "Sub-design spaces in the a1-a2 plane")
    if dist is None or dist.degenerate:
        return artifacts
    markers = [plots.DesignMarker(a1, a2, "best grid designs (tie)", "grid best")
               for a1, a2 in best_designs(dist)]  # fmt: skip
    fig = plots.index_distribution_figure(
        dist.alpha1_deg, dist.alpha2_deg, dist.values,
        title=rf"Conditioning index over the design space, $\beta$ = {dist.beta_deg:g}°",
        subtitle=f"{subtitle}; branch {dist.branch:+d}", markers=markers,
    )  # fmt: skip
    return (*artifacts, *figure_artifacts(fig, "index_map",
                                          "mean(1/kappa^2) over one sub-design space"))  # fmt: skip


def _data(
    spec: DesignSpaceSpec, rows: list[dict[str, Any]], dist: IndexDistribution | None
) -> tuple[Artifact, ...]:
    names = ("beta_deg", "gamma_deg", "f_min", "f_max", "D1_deg", "D2_deg", "degenerate", "empty")
    columns = {n: np.array([r[n] for r in rows]) for n in names}
    named = {named_column(n): values for n, values in columns.items()}
    csv = columns_csv(CSV_NAME, named, "Design space per beta (CSV)")
    arrays = dict(columns)
    arrays["corners_deg"] = np.array([r["rectangle"]["corners_deg"] for r in rows])
    axes: dict[str, tuple[str, ...]] = {n: ("beta_deg",) for n in names if n != "beta_deg"}
    axes["corners_deg"] = ("beta_deg", "corner", "alpha1_alpha2")
    if dist is not None:
        arrays |= {
            "index_map_alpha1_deg": dist.alpha1_deg,
            "index_map_alpha2_deg": dist.alpha2_deg,
            "index_map_mean_square": dist.values,
        }
        axes |= {
            n: ("row", "column")
            for n in ("index_map_alpha1_deg", "index_map_alpha2_deg", "index_map_mean_square")
        }
    npz = npz_artifact(
        NPZ_NAME,
        arrays,
        "Design space (NumPy arrays)",
        units={n: angle_or_pure(n) for n in arrays},
        axes=axes,
        metadata=job_metadata("spm-design-space", spec.model_dump(mode="json")),
    )
    return csv, npz
