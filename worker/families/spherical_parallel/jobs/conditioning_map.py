"""The ``spm-conditioning-map`` job: one design's conditioning over a prescribed workspace
(Bai 2010 §3, §5.1, Figs 6-7; docs/methods/spherical-parallel.md).

Inverse kinematics on one branch (eqs 11-12, 29) at every sample, 1/kappa with the
weighted norm of eqs 21-22, C_n (eq 25), mean(1/kappa^2) (eq 28), GCI (eq 24), the
extremes, the least 1/kappa on the closed workspace, det(A) (eq 30), exact values at
given orientations, 1/kappa maps over tilt x azimuth and torsion sweeps, CSV/NPZ data.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from worker.common.progress import ProgressReporter
from worker.contract import JobContext, JobOutcome
from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.errata import conditioning_map_errata_notes
from worker.families.spherical_parallel.jobs.conditioning_artifacts import (
    CSV_NAME,
    NPZ_NAME,
    conditioning_data,
    conditioning_plots,
)
from worker.families.spherical_parallel.jobs.design_entries import (
    design_entry,
    design_space_check,
    finite,
    indices_entry,
    minimum_entry,
)
from worker.families.spherical_parallel.jobs.orientation_entries import (
    orientation_entries,
    sample_entries,
)
from worker.families.spherical_parallel.jobs.pose_grids import (
    InverseConditionMaps,
    TorsionSweeps,
    inverse_condition_maps,
    sweep_start,
    torsion_sweeps,
)
from worker.families.spherical_parallel.jobs.workspace_sampling import (
    design_of,
    kinematic_workspace,
    sampling_entry,
    workspace_entry,
    workspace_samples,
)
from worker.families.spherical_parallel.specs import ConditioningMapSpec

__all__ = ["DEFINITIONS", "run_conditioning_map"]

DEFINITIONS = {
    "condition_number": "kappa = ||J|| ||J^-1||, ||M|| = sqrt(tr(M^T W M)), W = I/3 "
    "(eqs 21-22), J = B^-1 A (eq 9); kappa >= 1",
    "rms_inverse_condition": "C_n = sqrt(mean(1/kappa^2)) over the samples (eq 25)",
    "mean_square_inverse_condition": "mean(1/kappa^2) (eq 28): what the paper prints as C_n",
    "gci": "mean(1/kappa) over the equal-weight samples (eq 24)",
    "det_a": "det(A), rows (w_i x v_i)^T; 0 at a type-II singularity (eq 30: det(A)^2 >= lambda)",
    "branch": "the sign of (u_i x w_i) . v_i kept on every leg (eq 29: -1)",
}


def run_conditioning_map(spec: ConditioningMapSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + artifacts + notes out."""
    progress = ProgressReporter(ctx)
    progress.report(0.0, "workspace samples")
    design = design_of(spec.alpha1_deg, spec.alpha2_deg, spec.beta_deg, spec.gamma_deg)
    ws = kinematic_workspace(spec.workspace)
    samples, layout = workspace_samples(spec.workspace)
    progress.report(5.0, "inverse kinematics and 1/kappa at the samples")
    indices = sp.workspace_indices(design, samples, spec.branch)
    progress.report(25.0, "least 1/kappa on the closed workspace")
    minimum = sp.workspace_minimum(design, ws, spec.branch)
    progress.report(35.0, "given orientations")
    orientations = orientation_entries(design, spec.orientations or (), spec.branch)
    progress.report(45.0, "1/kappa maps over tilt x azimuth")
    maps = inverse_condition_maps(design, spec.branch, spec.map_torsions,
                                  spec.workspace.tilt_max_deg,
                                  (spec.map_grid.azimuth, spec.map_grid.tilt))  # fmt: skip
    progress.report(60.0, "torsion sweeps")
    lo, hi = spec.workspace.torsion_deg
    sweeps = torsion_sweeps(design, spec.branch, spec.sweeps,
                            sweep_start(lo, hi, spec.workspace.full_turn))  # fmt: skip

    progress.report(70.0, "result")
    result: dict[str, Any] = {
        "design": design_entry(design),
        "branch": spec.branch,
        "workspace": workspace_entry(spec.workspace),
        "sampling": sampling_entry(layout),
        "indices": indices_entry(indices),
        "workspace_minimum": minimum_entry(minimum),
        "design_space": design_space_check(design, ws),
        "type_ii_singularity": _type_ii(indices, samples),
        "inverse_kinematics": sample_entries(indices, samples),
        "orientations": orientations,
        "maps": _maps_entry(maps),
        "torsion_sweeps": _sweeps_entry(sweeps, spec.workspace.tilt_max_deg),
        "definitions": DEFINITIONS,
        "data": {"csv": CSV_NAME, "npz": NPZ_NAME},
    }
    notes = _notes(result)
    errata = conditioning_map_errata_notes(spec, result, sweeps)
    artifacts = conditioning_plots(spec, design, samples, maps, sweeps, progress)
    progress.report(95.0, "data files")
    artifacts += conditioning_data(spec, samples, indices, maps, sweeps, orientations)
    progress.report(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(notes), errata=tuple(errata))


def _type_ii(indices: sp.Indices, samples: np.ndarray[Any, Any]) -> dict[str, Any]:
    det_a = np.where(indices.real, indices.det_a, np.nan)
    if not np.any(indices.real):
        return {"min_abs_det_a": None, "min_det_a_squared": None, "at_psi_deg": None,
                "det_a_range": None, "criterion": DEFINITIONS["det_a"]}  # fmt: skip
    at = int(np.nanargmin(np.abs(det_a)))
    smallest = float(abs(det_a[at]))
    return {
        "min_abs_det_a": smallest,
        "min_det_a_squared": smallest**2,
        "at_psi_deg": [round(math.degrees(float(v)), 10) for v in samples[at]],
        "det_a_range": [float(np.nanmin(det_a)), float(np.nanmax(det_a))],
        "criterion": DEFINITIONS["det_a"],
    }


def _maps_entry(maps: InverseConditionMaps) -> dict[str, Any]:
    panels = []
    for torsion, values in zip(maps.torsions_deg, maps.values, strict=True):
        real = np.isfinite(values)
        panels.append({
            "torsion_deg": float(torsion),
            "min_inverse_condition": finite(np.min(values[real])) if real.any() else None,
            "max_inverse_condition": finite(np.max(values[real])) if real.any() else None,
            "unreachable_points": int(values.size - real.sum()),
        })  # fmt: skip
    return {
        "azimuth_deg": {"from": 0.0, "to": 360.0, "points": len(maps.azimuth_deg)},
        "tilt_deg": {"from": 0.0, "to": float(maps.tilt_deg[-1]), "points": len(maps.tilt_deg)},
        "panels": panels,
        "grid": "plain grid, ends included (for looking, not for means)",
    }


def _sweeps_entry(sweeps: TorsionSweeps, tilt_max_deg: float) -> list[dict[str, Any]]:
    entries = []
    for (psi1, psi2), values in zip(sweeps.azimuth_tilt_deg, sweeps.values, strict=True):
        real = np.isfinite(values)
        low = int(np.nanargmin(values)) if real.any() else None
        entries.append({
            "psi1_deg": float(psi1),
            "psi2_deg": float(psi2),
            "inside_cone": bool(psi2 <= tilt_max_deg + 1e-9),
            "psi3_deg": {"from": float(sweeps.psi3_deg[0]), "to": float(sweeps.psi3_deg[-1]),
                         "step": 1.0},
            "min_inverse_condition": None if low is None else float(values[low]),
            "min_at_psi3_deg": None if low is None else float(sweeps.psi3_deg[low]),
            "max_inverse_condition": finite(np.max(values[real])) if real.any() else None,
            "unreachable_points": int(values.size - real.sum()),
        })  # fmt: skip
    return entries


def _notes(result: dict[str, Any]) -> list[str]:
    notes = []
    indices, check = result["indices"], result["design_space"]
    if not indices["all_real"]:
        missing = indices["samples"] - indices["real_samples"]
        notes.append(
            f"{missing} of {indices['samples']} samples have no real inverse kinematics "
            "(eq 12 fails on some leg): the design does not reach the whole workspace, so "
            "its indices are null (an infeasible design is never scored)."
        )
    elif not check["feasible"]:
        notes.append(
            "Every sample is reachable, but the design lies outside the design space of "
            f"eq 19 (margins {check['margins_deg'][0]:.4g}°, {check['margins_deg'][1]:.4g}°): "
            "some orientations of the continuous workspace between the samples are not."
        )
    least = result["workspace_minimum"]["inverse_condition"]
    if least is not None and least < 1e-3:
        notes.append(
            f"1/kappa falls to {least:.3g} on the closed workspace (at psi = "
            f"{result['workspace_minimum']['psi_deg']}°): the design touches a singularity "
            "there, even though the samples' least value is "
            f"{indices['min_inverse_condition'] or 0:.4f}."
        )
    return notes
