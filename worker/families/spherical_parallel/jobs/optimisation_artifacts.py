"""Plots and data files of ``spm-optimisation``.

Plots: the conditioning index over the optimum's sub-design space with the optimum, its
twins and the paper's design marked (``index_map``, the paper's Fig. 6); every start's
final value (``starts``); 1/kappa of the optimum (and the paper's designs) along torsion
turns (``torsion_sweeps``, Fig. 7). Data: one CSV row per start, arrays in an NPZ.
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
from worker.contract import Artifact
from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.jobs.index_distribution import (
    IndexDistribution,
    index_distribution,
)
from worker.families.spherical_parallel.jobs.optimum import Presented
from worker.families.spherical_parallel.jobs.pose_grids import sweep_start, torsion_sweeps
from worker.families.spherical_parallel.jobs.workspace_sampling import FloatArray, design_of
from worker.families.spherical_parallel.optimisation_spec import INDEX_MAP_POINTS, OptimisationSpec
from worker.families.spherical_parallel.plots import conditioning as workspace_plots
from worker.families.spherical_parallel.plots import design_space as design_plots
from worker.families.spherical_parallel.plots import starts as start_plots
from worker.families.spherical_parallel.specs import FIG_7_AZIMUTH_DEG

__all__ = ["CSV_NAME", "NPZ_NAME", "optimisation_artifacts"]

CSV_NAME = "optimisation_starts.csv"
NPZ_NAME = "optimisation.npz"
_CSV_COLUMNS = ("start", "alpha1_start_deg", "alpha2_start_deg", "beta_start_deg",
                "gamma_start_deg", "alpha1_deg", "alpha2_deg", "beta_deg", "gamma_deg",
                "converged", "status", "nfev", "evaluations", "feasible",
                "mean_square_inverse_condition")  # fmt: skip


def _angles(design: sp.SpmDesign | None) -> tuple[float, ...]:
    return (math.nan,) * 4 if design is None else design.degrees()


def _label(design: sp.SpmDesign) -> str:
    return "(" + ", ".join(f"{v:.4g}" for v in design.degrees()[:3]) + ")"


def optimisation_artifacts(
    spec: OptimisationSpec,
    ws: sp.Workspace,
    samples: FloatArray,
    outcome: sp.OptimisationResult,
    shown: Presented | None,
    paper: dict[str, Any] | None,
    progress: ProgressReporter,
) -> tuple[Artifact, ...]:
    """The plots (when asked for and an optimum exists) and the data files."""
    artifacts: tuple[Artifact, ...] = ()
    dist = None
    if spec.plots:
        progress.report(78.0, "plot: index over the optimum's design space")
        if shown is not None:
            _, _, beta, gamma = shown.design.degrees()
            dist = index_distribution(ws, samples, beta, gamma, INDEX_MAP_POINTS, spec.branch)
            artifacts += _index_map(spec, shown, dist, paper)
        progress.report(88.0, "plot: starts")
        artifacts += _starts(outcome, paper, shown)
        if shown is not None:
            progress.report(92.0, "plot: torsion sweeps")
            artifacts += _sweeps(spec, shown.design, paper)
    progress.report(96.0, "data files")
    return artifacts + _data(spec, samples, outcome, shown, dist)


def _paper_rows(paper: dict[str, Any] | None) -> list[dict[str, Any]]:
    if paper is None:
        return []
    return [r for r in paper["designs"] if r["label"] != "Table 3, printed twin"]


def _index_map(spec: OptimisationSpec, shown: Presented, dist: IndexDistribution,
               paper: dict[str, Any] | None) -> tuple[Artifact, ...]:  # fmt: skip
    if dist.degenerate:
        return ()
    same_slice = [t for t in shown.twins
                  if math.isclose(t.design.beta, shown.design.beta)
                  and math.isclose(t.design.gamma, shown.design.gamma)]  # fmt: skip
    a1, a2, *_ = shown.design.degrees()
    markers = [design_plots.DesignMarker(a1, a2, "optimum", "optimum")]
    markers += [design_plots.DesignMarker(t.design.degrees()[0], t.design.degrees()[1],
                                          f"twin (branch {t.branch:+d})", "twin")
                for t in same_slice]  # fmt: skip
    markers += [design_plots.DesignMarker(r["alpha1_deg"], r["alpha2_deg"], r["label"], "paper")
                for r in _paper_rows(paper)
                if math.isclose(r["beta_deg"], dist.beta_deg, abs_tol=1e-6)
                and math.isclose(r["gamma_deg"], dist.gamma_deg, abs_tol=1e-6)]  # fmt: skip
    fig = design_plots.index_distribution_figure(
        dist.alpha1_deg, dist.alpha2_deg, dist.values,
        title=f"Conditioning index around the optimum {_label(shown.design)}°",
        subtitle=rf"$\beta$ = {dist.beta_deg:.4g}°, $\gamma$ = {dist.gamma_deg:.4g}°, branch "
        f"{spec.branch:+d}, {len(spec.free)} free parameter(s)",
        markers=markers,
    )  # fmt: skip
    return figure_artifacts(fig, "index_map", "mean(1/kappa^2) over the optimum's design space")


def _starts(outcome: sp.OptimisationResult, paper: dict[str, Any] | None,
            shown: Presented | None) -> tuple[Artifact, ...]:  # fmt: skip
    bars = [start_plots.StartBar(s.mean_square_inverse_condition, s.converged,
                                  _label(s.design) if s.design is not None else "")
            for s in outcome.starts]  # fmt: skip
    references = []
    for row in _paper_rows(paper)[:1]:
        references.append((f"{row['label']}: printed {row['printed']:g}", row["printed"]))
        value = row["indices"]["mean_square_inverse_condition"]
        if value is not None:
            references.append((f"{row['label']} design on these samples", value))
    fig = start_plots.optimisation_starts_figure(
        bars, best_index=outcome.best_start,
        title=f"Optimisation starts: {outcome.evaluations:,} evaluations",
        references=references,
        reported=_label(shown.design) if shown is not None else "",
    )  # fmt: skip
    return figure_artifacts(fig, "starts", "Final mean(1/kappa^2) of every start")


def _sweeps(spec: OptimisationSpec, design: sp.SpmDesign, paper: dict[str, Any] | None
            ) -> tuple[Artifact, ...]:  # fmt: skip
    tilt = spec.workspace.tilt_max_deg
    pairs = [(FIG_7_AZIMUTH_DEG, tilt * k / 3.0) for k in (1, 2, 3)]
    lo, hi = spec.workspace.torsion_deg
    start = sweep_start(lo, hi, spec.workspace.full_turn)
    sweep = torsion_sweeps(design, spec.branch, pairs, start)
    optimum_label = f"optimum {_label(design)}"
    series: list[workspace_plots.SweepSeries] = []
    for row in _paper_rows(paper)[:3]:
        other = design_of(row["alpha1_deg"], row["alpha2_deg"], row["beta_deg"], row["gamma_deg"])
        values = torsion_sweeps(other, spec.branch, pairs, start).values
        if np.allclose(values, sweep.values, rtol=0.0, atol=1e-4, equal_nan=True):
            # The same curves (the same design, or a twin): one line, both named.
            optimum_label += f", the same as {row['label']} {_label(other)}"
            continue
        series.append(workspace_plots.SweepSeries(f"{row['label']} {_label(other)}", values))
    series.insert(0, workspace_plots.SweepSeries(optimum_label, sweep.values))
    fig = workspace_plots.torsion_sweep_figure(
        sweep.psi3_deg, sweep.azimuth_tilt_deg, series,
        title=r"$1/\kappa$ over a full torsion turn", tilt_max_deg=tilt,
        torsion_range_deg=None if spec.workspace.full_turn else spec.workspace.torsion_deg,
    )  # fmt: skip
    return figure_artifacts(fig, "torsion_sweeps", "1/kappa of the optimum along torsion turns")


def _data(
    spec: OptimisationSpec,
    samples: FloatArray,
    outcome: sp.OptimisationResult,
    shown: Presented | None,
    dist: IndexDistribution | None,
) -> tuple[Artifact, ...]:
    rows = [
        (
            s.index,
            *_angles(s.start_design),
            *_angles(s.design),
            s.converged,
            s.status,
            s.nfev,
            s.evaluations,
            s.feasible,
            s.mean_square_inverse_condition,
        )
        for s in outcome.starts
    ]
    table = list(zip(*rows, strict=True))
    columns = {name: np.asarray(values) for name, values in zip(_CSV_COLUMNS, table, strict=True)}
    for flag in ("converged", "feasible"):
        columns[flag] = columns[flag].astype(np.int8)
    named = {named_column(name): values for name, values in columns.items()}
    csv = columns_csv(CSV_NAME, named, "Every optimisation start (CSV)")
    arrays: dict[str, Any] = dict(columns)
    arrays["samples_deg"] = np.degrees(samples)
    if shown is not None:
        arrays["optimum_deg"] = np.array(shown.design.degrees())
        arrays["optimum_inverse_condition"] = shown.indices.inverse_condition
        arrays["optimum_theta_deg"] = np.degrees(shown.indices.theta)
        arrays["optimum_det_a"] = shown.indices.det_a
    if dist is not None:
        arrays |= {
            "index_map_alpha1_deg": dist.alpha1_deg,
            "index_map_alpha2_deg": dist.alpha2_deg,
            "index_map_mean_square": dist.values,
        }
    axes: dict[str, tuple[str, ...]] = {n: ("start",) for n in columns}
    axes["samples_deg"] = ("sample", "psi1_psi2_psi3")
    if shown is not None:
        axes |= {
            "optimum_deg": ("alpha1_alpha2_beta_gamma",),
            "optimum_inverse_condition": ("sample",),
            "optimum_theta_deg": ("sample", "leg"),
            "optimum_det_a": ("sample",),
        }
    if dist is not None:
        axes |= {
            n: ("row", "column")
            for n in ("index_map_alpha1_deg", "index_map_alpha2_deg", "index_map_mean_square")
        }
    npz = npz_artifact(
        NPZ_NAME,
        arrays,
        "Optimisation (NumPy arrays)",
        units={n: angle_or_pure(n) for n in arrays},
        axes=axes,
        metadata=job_metadata("spm-optimisation", spec.model_dump(mode="json")),
    )
    return csv, npz
