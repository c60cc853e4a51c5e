"""Plots and data files of ``spm-conditioning-map``.

Plots: 1/kappa over tilt x azimuth at the chosen torsions (``inverse_condition_map``,
the paper's Fig. 6 style) and along a torsion turn (``torsion_sweeps``, Fig. 7).
Data: one CSV row per workspace sample, and every array in one NPZ.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.common.data_export import DIMENSIONLESS, columns_csv, job_metadata, npz_artifact
from worker.common.figures import figure_artifacts
from worker.common.progress import ProgressReporter
from worker.contract import Artifact
from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.jobs.pose_grids import InverseConditionMaps, TorsionSweeps
from worker.families.spherical_parallel.jobs.workspace_sampling import FloatArray
from worker.families.spherical_parallel.plots import conditioning as plots
from worker.families.spherical_parallel.specs import ConditioningMapSpec

__all__ = ["CSV_COLUMNS", "CSV_NAME", "NPZ_NAME", "conditioning_data", "conditioning_plots",
           "design_label"]  # fmt: skip

CSV_NAME = "conditioning_samples.csv"
NPZ_NAME = "conditioning_map.npz"
#: One row per workspace sample: the orientation, whether every leg closes, the input
#: angles, 1/kappa, kappa and det A (each name with its unit).
CSV_COLUMNS = (
    "psi1 [deg]", "psi2 [deg]", "psi3 [deg]", "real [-]", "theta1 [deg]", "theta2 [deg]",
    "theta3 [deg]", "inverse_condition [-]", "condition_number [-]", "det_a [-]",
)  # fmt: skip


def design_label(design: sp.SpmDesign) -> str:
    """'(a1, a2, beta, gamma)' in degrees, to 4 significant digits."""
    return "(" + ", ".join(f"{v:.4g}" for v in design.degrees()) + ")"


def _workspace_text(spec: ConditioningMapSpec) -> str:
    ws = spec.workspace
    lo, hi = ws.torsion_deg
    torsion = "full torsion turn" if ws.full_turn else f"torsion [{lo:.10g}, {hi:.10g}]°"
    return f"cone of {2 * ws.tilt_max_deg:.10g}° opening, {torsion}, branch {spec.branch:+d}"


def conditioning_plots(
    spec: ConditioningMapSpec,
    design: sp.SpmDesign,
    samples: FloatArray,
    maps: InverseConditionMaps,
    sweeps: TorsionSweeps,
    progress: ProgressReporter,
) -> tuple[Artifact, ...]:
    """The two figures (PNG + SVG each); none when ``spec.plots`` is false."""
    if not spec.plots:
        return ()
    progress.report(75.0, "plot: 1/kappa maps")
    name = f"SPM {design_label(design)}°"
    limited = None if spec.workspace.full_turn else spec.workspace.torsion_deg
    fig_map = plots.inverse_condition_map_figure(
        maps.azimuth_deg, maps.tilt_deg, maps.values, maps.torsions_deg,
        title=rf"$1/\kappa$ over the pointing cone, {name}", subtitle=_workspace_text(spec),
        samples_deg=np.degrees(samples),
    )  # fmt: skip
    artifacts = figure_artifacts(fig_map, "inverse_condition_map",
                                 "1/kappa over tilt x azimuth at fixed torsions")  # fmt: skip
    progress.report(85.0, "plot: torsion sweeps")
    fig_sweep = plots.torsion_sweep_figure(
        sweeps.psi3_deg, sweeps.azimuth_tilt_deg,
        [plots.SweepSeries(f"{name}, branch {spec.branch:+d}", sweeps.values)],
        title=rf"$1/\kappa$ over a full torsion turn, {name}",
        tilt_max_deg=spec.workspace.tilt_max_deg, torsion_range_deg=limited,
    )  # fmt: skip
    return (*artifacts, *figure_artifacts(fig_sweep, "torsion_sweeps",
                                          "1/kappa along a full torsion turn"))  # fmt: skip


def conditioning_data(
    spec: ConditioningMapSpec,
    samples: FloatArray,
    indices: sp.Indices,
    maps: InverseConditionMaps,
    sweeps: TorsionSweeps,
    orientations: Sequence[dict[str, Any]],
) -> tuple[Artifact, ...]:
    """CSV: one row per workspace sample; NPZ: samples, maps, sweeps and orientations."""
    psi_deg = np.degrees(samples)
    inverse = np.where(indices.real, indices.inverse_condition, np.nan)
    with np.errstate(divide="ignore"):
        kappa = np.where(inverse > 0.0, 1.0 / np.where(inverse > 0.0, inverse, 1.0), np.inf)
    kappa = np.where(indices.real, kappa, np.nan)
    theta_deg = np.degrees(indices.theta)
    columns: dict[str, NDArray[np.generic]] = dict(zip(CSV_COLUMNS, (
        psi_deg[:, 0], psi_deg[:, 1], psi_deg[:, 2], indices.real.astype(np.int8),
        theta_deg[:, 0], theta_deg[:, 1], theta_deg[:, 2], inverse, kappa, indices.det_a,
    ), strict=True))  # fmt: skip
    csv = columns_csv(CSV_NAME, columns, "Inverse kinematics and 1/kappa at the samples (CSV)")
    given = np.asarray([o["psi_deg"] for o in orientations], dtype=float).reshape(-1, 3)
    given_inverse = np.array([np.nan if o["inverse_condition"] is None else o["inverse_condition"]
                              for o in orientations], dtype=float)  # fmt: skip
    arrays: dict[str, NDArray[np.generic]] = {
        "design_deg": np.array([spec.alpha1_deg, spec.alpha2_deg, spec.beta_deg, spec.gamma_deg]),
        "branch": np.array(spec.branch),
        "samples_deg": psi_deg,
        "real": indices.real,
        "theta_deg": theta_deg,
        "inverse_condition": inverse,
        "condition_number": kappa,
        "det_a": indices.det_a,
        "map_azimuth_deg": maps.azimuth_deg,
        "map_tilt_deg": maps.tilt_deg,
        "map_torsions_deg": maps.torsions_deg,
        "map_inverse_condition": maps.values,
        "sweep_psi3_deg": sweeps.psi3_deg,
        "sweep_azimuth_tilt_deg": sweeps.azimuth_tilt_deg,
        "sweep_inverse_condition": sweeps.values,
        "orientations_deg": given,
        "orientations_inverse_condition": given_inverse,
    }
    angles = {n for n in arrays if n.endswith("_deg")}
    per_sample = ("sample",)
    npz = npz_artifact(
        NPZ_NAME,
        arrays,
        "Conditioning map (NumPy arrays)",
        units={n: "deg" if n in angles else DIMENSIONLESS for n in arrays},
        axes={
            "design_deg": ("alpha1_alpha2_beta_gamma",),
            "samples_deg": (*per_sample, "psi1_psi2_psi3"),
            "real": per_sample,
            "theta_deg": (*per_sample, "leg"),
            "inverse_condition": per_sample,
            "condition_number": per_sample,
            "det_a": per_sample,
            "map_inverse_condition": ("map_torsions_deg", "map_tilt_deg", "map_azimuth_deg"),
            "sweep_azimuth_tilt_deg": ("sweep", "psi1_psi2"),
            "sweep_inverse_condition": ("sweep", "sweep_psi3_deg"),
            "orientations_deg": ("orientation", "psi1_psi2_psi3"),
            "orientations_inverse_condition": ("orientation",),
        },
        metadata=job_metadata("spm-conditioning-map", spec.model_dump(mode="json")),
    )
    return csv, npz
