"""The ``spm-optimisation`` job: the most dexterous design for a prescribed workspace
(Bai 2010 §5, eqs 28-30, Tables 1-3; docs/methods/spherical-parallel.md).

Maximises mean(1/kappa^2) over the workspace samples (eq 28) by nonlinear least squares
from several starts drawn in the design space, feasible on the continuous workspace by
construction (the kinematics parametrises the rectangle of eq 19), with the branch kept
(eq 29) and optionally det(A)^2 >= lambda (eq 30). Reports the optimum with its twins,
every start, the evaluations spent, and the paper's designs scored on the same samples.
"""

from __future__ import annotations

import math
from typing import Any

from worker.common.progress import ProgressReporter
from worker.contract import JobContext, JobOutcome
from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.errata import (
    example_number,
    optimisation_errata_notes,
    optimisation_paper_comparison,
)
from worker.families.spherical_parallel.jobs.design_entries import design_entry, indices_entry
from worker.families.spherical_parallel.jobs.optimisation_artifacts import (
    CSV_NAME,
    NPZ_NAME,
    optimisation_artifacts,
)
from worker.families.spherical_parallel.jobs.optimum import optimum_entry, presented_optimum
from worker.families.spherical_parallel.jobs.workspace_sampling import (
    FloatArray,
    kinematic_workspace,
    sampling_entry,
    workspace_entry,
    workspace_samples,
)
from worker.families.spherical_parallel.optimisation_spec import SCREEN_PER_START, OptimisationSpec

__all__ = ["run_optimisation", "solve"]

_SOLVER = (
    "scipy.optimize.least_squares (dogbox) on residuals sqrt(1 - 1/kappa_k^2), whose sum of "
    "squares is n (1 - mean(1/kappa^2)); link angles parametrised over the rectangle of eq 19 "
    "(a1 - a2 = s D1, a1 + a2 - 180 = t D2, s, t in [-1, 1]; u in [0, 1] with one held); "
    "each start is the best of a seeded screen of the design space (see 'screening')"
)
_SCREEN_RULE = (
    "candidates drawn uniformly in the solver's variable box, each link-angle variable put "
    "on a bound (an edge of the design space, eq 19) with probability 1/3; ranked by eq 30 "
    "(if asked), then mean(1/kappa^2); the starts are the best candidates that differ by "
    "more than 10% of the box along some variable"
)


def solve(spec: OptimisationSpec, samples: FloatArray, progress: ProgressReporter
          ) -> sp.OptimisationResult:  # fmt: skip
    """Run the kinematics' multi-start optimisation, progress advancing after each start."""
    ws = kinematic_workspace(spec.workspace)
    bounds = {name: (math.radians(pair[0]), math.radians(pair[1]))
              for name in ("beta", "gamma")
              if (pair := getattr(spec.bounds, f"{name}_deg")) is not None}  # fmt: skip

    def on_start(done: int, total: int) -> None:
        progress.report(5.0 + 70.0 * done / total, f"optimisation: {done} of {total} starts done")

    return sp.optimise(
        ws, samples, free=spec.free, identical_platforms=spec.identical_platforms,
        bounds=bounds or None, starts=spec.starts, seed=spec.seed,
        singularity_tolerance=spec.singularity_tolerance, branch=spec.branch,
        fixed={name: math.radians(v) for name, v in spec.held.items()}, on_start=on_start,
        max_nfev=spec.max_evaluations_per_start, screen=SCREEN_PER_START,
    )  # fmt: skip


def run_optimisation(spec: OptimisationSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + artifacts + notes out."""
    progress = ProgressReporter(ctx)
    progress.report(0.0, "workspace samples")
    ws = kinematic_workspace(spec.workspace)
    samples, layout = workspace_samples(spec.workspace)
    progress.report(
        2.0,
        f"screening {spec.starts * SCREEN_PER_START} candidate designs for {spec.starts} starts",
    )
    outcome = solve(spec, samples, progress)
    progress.report(76.0, "result")
    shown = presented_optimum(outcome, ws, samples, spec.branch, spec.identical_platforms)
    optimum = None if shown is None else optimum_entry(outcome, shown, ws)
    gamma = None if spec.identical_platforms else spec.held.get("gamma")
    example = example_number(spec.workspace, gamma, spec.identical_platforms)
    paper = optimisation_paper_comparison(example, samples, spec.branch, optimum)
    result: dict[str, Any] = {
        "success": outcome.success,
        "message": outcome.message,
        "optimum": optimum,
        "starts": [
            _start_entry(s, outcome.best_start, samples, spec.branch) for s in outcome.starts
        ],
        "evaluations": outcome.evaluations,
        "screening": {
            "candidates_per_start": SCREEN_PER_START,
            "candidates": spec.starts * SCREEN_PER_START,
            "evaluations": outcome.screen_evaluations,
            "rule": _SCREEN_RULE,
        },
        "budget": {
            "starts": spec.starts,
            "max_evaluations_per_start": spec.max_evaluations_per_start,
        },
        "free": list(spec.free),
        "held_deg": spec.held,
        "identical_platforms": spec.identical_platforms,
        "bounds_deg": _bounds(spec),
        "variables": list(outcome.variables),
        "solver": _SOLVER,
        "branch": spec.branch,
        "seed": spec.seed,
        "singularity_tolerance": spec.singularity_tolerance,
        "workspace": workspace_entry(spec.workspace),
        "sampling": sampling_entry(layout),
        "paper": paper,
        "data": {"csv": CSV_NAME, "npz": NPZ_NAME},
    }
    notes = _notes(spec, result)
    errata = optimisation_errata_notes(paper, optimum)
    artifacts = optimisation_artifacts(spec, ws, samples, outcome, shown, paper, progress)
    progress.report(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(notes), errata=tuple(errata))


def _bounds(spec: OptimisationSpec) -> dict[str, list[float]]:
    out = {}
    for name in ("beta", "gamma"):
        if name in spec.free:
            given = getattr(spec.bounds, f"{name}_deg")
            default = sp.DEFAULT_BOUNDS[name]
            pair = given if given is not None else tuple(math.degrees(v) for v in default)
            out[f"{name}_deg"] = [round(float(v), 10) for v in pair]
    return out


def _start_entry(
    start: sp.StartOutcome, best: int | None, samples: FloatArray, branch: int
) -> dict[str, Any]:
    """One start as reported; ``indices`` of its end design when that is feasible."""
    score = start.mean_square_inverse_condition
    indices = None
    if start.design is not None and start.feasible:
        indices = indices_entry(sp.workspace_indices(start.design, samples, branch))
    return {
        "index": start.index,
        "start": None if start.start_design is None else design_entry(start.start_design),
        "end": None if start.design is None else design_entry(start.design),
        "x0": list(start.x0),
        "x": list(start.x),
        "converged": start.converged,
        "status": start.status,
        "message": start.message,
        "nfev": start.nfev,
        "evaluations": start.evaluations,
        "feasible": start.feasible,
        "mean_square_inverse_condition": score if math.isfinite(score) else None,
        "indices": indices,
        "best": start.index == best,
    }


def _angles_text(design: dict[str, Any]) -> str:
    """'(a1, a2, beta)' or, when gamma is not 0, '(a1, a2, beta, gamma)', 2 decimals."""
    names = ("alpha1_deg", "alpha2_deg", "beta_deg", "gamma_deg")
    shown = names if design["gamma_deg"] else names[:3]
    return "(" + ", ".join(f"{design[n]:.2f}" for n in shown) + ")"


def _notes(spec: OptimisationSpec, result: dict[str, Any]) -> list[str]:
    notes = []
    starts = result["starts"]
    stopped = [s["index"] for s in starts if not s["converged"]]
    if stopped:
        notes.append(
            f"{len(stopped)} of {len(starts)} starts ({', '.join(map(str, stopped))}) stopped "
            f"at the evaluation budget (max_nfev = {spec.max_evaluations_per_start}) before "
            "converging; their ends are reported as they are."
        )
    optimum = result["optimum"]
    if optimum is None:
        notes.append(f"No design: {result['message']}. Infeasible designs are never scored; "
                     "widen the bounds, free more parameters or relax the singularity "
                     "tolerance.")  # fmt: skip
        return notes
    found = optimum["found_as"]
    if found is not None:
        notes.append(
            f"The solver ended at {_angles_text(found)}; shown is {_angles_text(optimum)}, which "
            f"scores the same on these samples with the same branch ({found['relation']})."
        )
    least = optimum["workspace_minimum"]["inverse_condition"]
    if optimum["design_space"]["on_edge"]:
        notes.append(
            "The optimum sits on the edge of the design space (eq 19; margins "
            f"{optimum['design_space']['margins_deg'][0]:.2g}°, "
            f"{optimum['design_space']['margins_deg'][1]:.2g}°), where the workspace boundary "
            f"touches a leg-folding singularity: 1/kappa falls to {least:.3g} at psi = "
            f"{optimum['workspace_minimum']['psi_deg']}° on the closed workspace, while the "
            f"least sampled value is {optimum['min_inverse_condition']:.4f}."
        )
    same = [t for t in optimum["twins"] if t["indices"]["mean_square_inverse_condition"]]
    if same:
        listed = "; ".join(f"{_angles_text(t)} branch {t['branch']:+d}" for t in same)
        notes.append(
            "Twin optima with the same conditioning (docs/methods/spherical-parallel.md, "
            f"'Twins'): {listed}."
        )
    tolerance = spec.singularity_tolerance
    if tolerance is not None:
        det2 = optimum["min_abs_det_a"] ** 2
        notes.append(f"eq 30 holds at every sample: min det(A)^2 = {det2:.4g} >= lambda = "
                     f"{tolerance:g}.")  # fmt: skip
    return notes
