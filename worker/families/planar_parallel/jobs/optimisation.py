"""The ``planar2dof-optimisation`` job: the paper's global design of the proximal-arm robot
(Huang et al. 2004 §III-C, Figs 6-9, Table I; docs/methods/planar-parallel.md).

The conditioning limit 1/kappa0 from an allowable pressure angle (eq 17 + eq 7, maximised
over delta) or as given; then, for each delta of a sweep (or one delta), the isotropic
architecture of eq (12), the largest rectangle W_lambda of aspect lambda inside W_kappa0,
the mean 1/kappa over it (eq 14) and eta = (S/S_max) mean (eq 13); the optimum and the
flat window around it; CSV/NPZ data and the paper's Figs 6-9.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from worker.common.progress import ProgressReporter
from worker.contract import JobContext, JobOutcome
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.discretisation import (
    FIG9_MESH,
    MAP_POINTS_PER_AXIS,
    MAX_CHUNK_MESH_POINTS,
    RECTANGLE_BOUNDARY_SAMPLES,
    RECTANGLE_COLUMNS,
    RECTANGLE_ROWS,
    S_MAX_MESH,
)
from worker.families.planar_parallel.errata import optimisation_errata_notes
from worker.families.planar_parallel.jobs.design_rows import (
    Design,
    design_entry,
    rescaled_row,
    sweep_entry,
    sweep_notes,
)
from worker.families.planar_parallel.jobs.optimisation_artifacts import (
    CSV_NAME,
    NPZ_NAME,
    optimisation_artifacts,
)
from worker.families.planar_parallel.specs import (
    DEFAULT_DELTA_RANGE,
    DEFAULT_DELTA_STEP,
    OptimisationSpec,
    sweep_deltas,
)

__all__ = ["ConditioningLimit", "SweepOutcome", "run_optimisation"]


@dataclass(frozen=True)
class ConditioningLimit:
    """1/kappa0 and where it comes from: eq (17) maximised at ``delta`` over
    ``delta_range``, or given (``delta`` None)."""

    value: float
    delta: float | None
    delta_range: tuple[float, float] | None


@dataclass(frozen=True)
class SweepOutcome:
    """The rows reported, S_max, the chosen design (None: no rectangle) and the window."""

    rows: tuple[pp.SweepRow, ...]
    S_max: float
    design: Design | None
    window: tuple[float, float] | None
    message: str
    notes: tuple[str, ...] = ()


def run_optimisation(spec: OptimisationSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + artifacts + notes out."""
    progress = ProgressReporter(ctx)
    progress.report(0.0, "conditioning limit")
    limit = conditioning_limit(spec)
    progress.report(3.0, "delta sweep")
    outcome = _sweep(spec, limit.value, progress) if spec.delta is None else _single(
        spec, limit.value, progress
    )  # fmt: skip
    progress.report(82.0, "result")
    result = _result(spec, limit, outcome)
    notes = _notes(spec, outcome)
    errata = optimisation_errata_notes(spec, result, outcome.rows)
    artifacts = optimisation_artifacts(spec, limit.value, limit.delta, outcome, progress)
    progress.report(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(notes), errata=tuple(errata))


def conditioning_limit(spec: OptimisationSpec) -> ConditioningLimit:
    """1/kappa0: eq (17) + eq (7) maximised over the sweep's range (the paper's [1, 2.5]
    for a single delta), or the given limit."""
    if spec.inverse_condition_limit is not None:
        return ConditioningLimit(spec.inverse_condition_limit, None, None)
    angle = spec.allowable_pressure_angle_deg
    assert angle is not None  # the spec holds exactly one of the two
    span = spec.sweep_range if spec.delta is None else DEFAULT_DELTA_RANGE
    value, delta = pp.max_condition_limit(angle, span)
    return ConditioningLimit(value, delta, span)


def _run_sweep(
    spec: OptimisationSpec, limit: float, deltas: list[float], mesh: int,
    progress: ProgressReporter, span: tuple[float, float, str],
) -> pp.DesignSweep:  # fmt: skip
    return pp.design_sweep(
        limit, deltas, spec.aspect_ratio, mesh, on_row=progress.span(*span),
        columns=RECTANGLE_COLUMNS, rows=RECTANGLE_ROWS,
        boundary_samples=RECTANGLE_BOUNDARY_SAMPLES,
        chunk=max(1, min(16, MAX_CHUNK_MESH_POINTS // mesh**2)),
    )  # fmt: skip


def _sweep(spec: OptimisationSpec, limit: float, progress: ProgressReporter) -> SweepOutcome:
    deltas = sweep_deltas(*spec.sweep_range, spec.sweep_step)
    sweep = _run_sweep(spec, limit, deltas, spec.mean_mesh, progress, (5.0, 80.0, "delta sweep"))
    if not sweep.found:
        return SweepOutcome(sweep.rows, math.nan, None, None, sweep.message)
    design = Design(sweep.rows[sweep.optimum], sweep.S_max)
    return SweepOutcome(sweep.rows, sweep.S_max, design, sweep.window, sweep.message)


def _single(spec: OptimisationSpec, limit: float, progress: ProgressReporter) -> SweepOutcome:
    """One delta; S_max over the paper's range at its step (and this delta)."""
    assert spec.delta is not None
    reference = _run_sweep(
        spec,
        limit,
        sweep_deltas(*DEFAULT_DELTA_RANGE, DEFAULT_DELTA_STEP),
        S_MAX_MESH,
        progress,
        (5.0, 72.0, "S_max over delta in [1, 2.5]"),
    )
    progress.report(74.0, f"design at delta = {spec.delta:g}")
    single = _run_sweep(spec, limit, [spec.delta], spec.mean_mesh, progress,
                        (74.0, 80.0, f"design at delta = {spec.delta:g}"))  # fmt: skip
    row = single.rows[0]
    areas = [s for s in (reference.S_max, row.rectangle.S) if math.isfinite(s)]
    s_max = max(areas, default=math.nan)
    if not row.rectangle.found:  # no design at this delta, whatever S_max is
        return SweepOutcome((row,), s_max, None, None, row.rectangle.message)
    row = rescaled_row(row, s_max)
    notes: tuple[str, ...] = ()
    if not reference.S_max >= row.rectangle.S:  # also when [1, 2.5] has no rectangle
        lo, hi = DEFAULT_DELTA_RANGE
        notes = (
            f"The rectangle at delta = {row.delta:g} (S = {row.rectangle.S:.6g}) is larger "
            f"than any for delta in [{lo:g}, {hi:g}]: S_max is its S, S/S_max = 1.",
        )
    return SweepOutcome((row,), s_max, Design(row, s_max), None, row.rectangle.message, notes)


def _result(
    spec: OptimisationSpec, limit: ConditioningLimit, outcome: SweepOutcome
) -> dict[str, Any]:
    single = spec.delta is not None
    return {
        "allowable_pressure_angle_deg": spec.allowable_pressure_angle_deg,
        "inverse_condition_limit": limit.value,
        "inverse_condition_limit_source": "given" if limit.delta is None
        else "eq (17) + eq (7), maximised over delta",
        "inverse_condition_limit_delta": limit.delta,
        "aspect_ratio": spec.aspect_ratio,
        "mean_mesh": spec.mean_mesh,
        "evaluation": "single-delta" if single else "sweep",
        "S_max": outcome.S_max if math.isfinite(outcome.S_max) else None,
        "sweep": [sweep_entry(row) for row in outcome.rows],
        "optimum": None if outcome.design is None else design_entry(outcome.design),
        "window": None if outcome.window is None else list(outcome.window),
        "discretisation": _discretisation(spec, limit),
        "data": {"csv": CSV_NAME, "npz": NPZ_NAME},
    }  # fmt: skip


def _discretisation(spec: OptimisationSpec, limit: ConditioningLimit) -> dict[str, Any]:
    if spec.delta is None:
        lo, hi = spec.sweep_range
        deltas = {"range": [lo, hi], "step": spec.sweep_step, "count": spec.sweep_size}
        s_max = "over the swept deltas"
    else:
        deltas = {"delta": spec.delta}
        lo, hi = DEFAULT_DELTA_RANGE
        s_max = (f"over delta in [{lo:g}, {hi:g}] at step {DEFAULT_DELTA_STEP:g} "
                 f"(and delta = {spec.delta:g})")  # fmt: skip
    return {
        "deltas": deltas,
        "mean_mesh": [spec.mean_mesh, spec.mean_mesh],
        "S_max": s_max,
        "inverse_condition_limit": None if limit.delta_range is None else {
            "delta_range": list(limit.delta_range),
            "method": "1501 samples then bounded Brent (xatol 1e-12)",
        },
        "rectangle": {
            "method": "exact envelope of W_kappa0's column runs (bisection on h and a "
            "search over the centre, solved by root finding), checked on its boundary",
            "columns": RECTANGLE_COLUMNS,
            "rows": RECTANGLE_ROWS,
            "boundary_samples_per_edge": RECTANGLE_BOUNDARY_SAMPLES,
        },
        "window_tolerance": 0.001 if spec.delta is None else None,
        "figure_9_mesh": [FIG9_MESH, FIG9_MESH],
        "workspace_map_points_per_axis": MAP_POINTS_PER_AXIS,
    }  # fmt: skip


def _notes(spec: OptimisationSpec, outcome: SweepOutcome) -> list[str]:
    notes = sweep_notes(outcome.rows) + list(outcome.notes)
    design = outcome.design
    if design is None:
        notes.append(f"No design: {outcome.message}.")
        return notes
    row = design.row
    if spec.delta is None:
        lo, hi = spec.sweep_range
        if len(outcome.rows) > 1 and row.delta in (outcome.rows[0].delta, outcome.rows[-1].delta):
            notes.append(f"The optimum delta = {row.delta:.6g} lies at an end of the swept "
                         f"range [{lo:g}, {hi:g}]; eta may rise beyond it.")  # fmt: skip
    angle = spec.allowable_pressure_angle_deg
    if angle is not None and row.min_pressure_angle_deg < angle - 1e-6:
        notes.append(
            f"The rectangle's least pressure angle {row.min_pressure_angle_deg:.4f}° is below "
            f"[beta] = {angle:g}°: eq (17) bounds beta on the top edge at the delta where "
            "1/kappa0 peaks, not at every delta."
        )
    if row.eta > row.mean_inverse_condition + 1e-12:
        notes.append("eta exceeds the mean 1/kappa, which S <= S_max rules out.")
    return notes
