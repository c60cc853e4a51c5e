"""The ``serial-reach`` job: which target poses the arm reaches within its joint limits.

Inverse kinematics for every target at once: the closed form for a planar 3R arm
(:mod:`..kinematics.planar_3r`), damped least squares from seeded starts otherwise
(:mod:`..kinematics.inverse`); then the dexterity indices of each solution
(:mod:`..kinematics.indices`) and the share of targets reached (docs/methods/serial.md).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from worker.common.figures import figure_artifacts
from worker.common.progress import ProgressReporter
from worker.contract import Artifact, JobContext, JobOutcome
from worker.families.serial.jobs.indices import arm_description
from worker.families.serial.kinematics.arm import SerialArm
from worker.families.serial.kinematics.chain import forward_kinematics, jacobian, joint_frames
from worker.families.serial.kinematics.indices import (
    inverse_condition,
    manipulability,
    task_jacobian,
)
from worker.families.serial.kinematics.inverse import (
    IKSolution,
    PoseTargets,
    seed_configurations,
    solve_damped_least_squares,
)
from worker.families.serial.kinematics.planar_3r import planar_3r_geometry, solve_planar_3r
from worker.families.serial.plots.reach import reach_figure
from worker.families.serial.reach_spec import SerialReachSpec

__all__ = ["CLOSED_FORM", "NUMERICAL", "run_serial_reach", "solve_targets"]

#: The solver names the result reports.
CLOSED_FORM = "closed-form planar 3R"
NUMERICAL = "damped least squares"
#: Reached solutions drawn in the figure (the first ones).
DRAWN = 4


def solve_targets(
    spec: SerialReachSpec, arm: SerialArm, targets: PoseTargets
) -> tuple[str, IKSolution]:
    """The solver used and its solutions: closed form for a planar 3R arm (unless the
    spec asks for the numerical solver), whose unreached targets the numerical solver
    tries too (it finds their closest configuration, and a position-only target whose
    feasible tool angles fall between the closed form's scan steps)."""
    rng = np.random.default_rng(spec.seed)
    geometry = planar_3r_geometry(arm) if spec.solver == "auto" else None
    if geometry is None:
        starts = seed_configurations(arm, targets.count, spec.seeds, rng)
        return NUMERICAL, solve_damped_least_squares(arm, targets, starts,
                                                     spec.max_iterations, restarts=rng)  # fmt: skip
    closed = solve_planar_3r(arm, geometry, targets)
    missing = np.flatnonzero(~closed.reached)
    if missing.size == 0:
        return CLOSED_FORM, closed
    starts = seed_configurations(arm, missing.size, spec.seeds, rng)
    numerical = solve_damped_least_squares(arm, targets.take(missing), starts,
                                           spec.max_iterations, restarts=rng)  # fmt: skip
    return CLOSED_FORM, closed.replaced(missing, numerical)


def _maybe(value: float, present: bool) -> float | None:
    return float(value) if present else None


def _target_entries(
    spec: SerialReachSpec, arm: SerialArm, targets: PoseTargets, solution: IKSolution
) -> tuple[list[dict[str, Any]], np.ndarray, np.ndarray]:
    """One result entry per target, and the manipulability and inverse condition of
    every solution (t,)."""
    task = task_jacobian(jacobian(arm, solution.q), arm.planar)
    measure = manipulability(task)
    kappa = inverse_condition(task, spec.characteristic_length)
    shown = np.where(arm.prismatic, solution.q, np.degrees(solution.q))
    entries = []
    for k, target in enumerate(spec.targets):
        reached = bool(solution.reached[k])
        rpy = target.rpy_deg
        oriented = rpy is not None
        residual = {
            "position": float(solution.position_residual[k]),
            "orientation_deg": _maybe(np.degrees(solution.orientation_residual[k]), oriented),
        }
        tolerance = {
            "position": float(targets.position_tolerance[k]),
            "orientation_deg": _maybe(np.degrees(targets.orientation_tolerance[k]), oriented),
        }
        entries.append(
            {
                "position": targets.positions[k].tolist(),
                "rpy_deg": None if rpy is None else list(rpy),
                "reached": reached,
                "configuration": shown[k].tolist(),
                "residual": residual,
                "tolerance": tolerance,
                "solutions": int(solution.solutions[k]),
                "manipulability": _maybe(measure[k], reached),
                "inverse_condition": _maybe(kappa[k], reached),
            }
        )
    return entries, measure, kappa


def _summary(solution: IKSolution, measure: np.ndarray, kappa: np.ndarray) -> dict[str, Any]:
    reached = solution.reached
    count = int(reached.sum())
    some = count > 0
    return {
        "targets": int(reached.size),
        "reached": count,
        "reached_share": count / reached.size,
        "manipulability_min": _maybe(measure[reached].min() if some else 0.0, some),
        "manipulability_mean": _maybe(measure[reached].mean() if some else 0.0, some),
        "inverse_condition_min": _maybe(kappa[reached].min() if some else 0.0, some),
        "inverse_condition_mean": _maybe(kappa[reached].mean() if some else 0.0, some),
    }


def run_serial_reach(spec: SerialReachSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + figure out."""
    progress = ProgressReporter(ctx)
    progress.report(0.0, "inverse kinematics")
    arm = spec.arm()
    targets = spec.pose_targets(arm)
    solver, solution = solve_targets(spec, arm, targets)
    progress.report(70.0, "indices")
    entries, measure, kappa = _target_entries(spec, arm, targets, solution)
    summary = _summary(solution, measure, kappa)
    result = {
        "arm": arm_description(spec.robot, arm),
        "length_unit": spec.length_unit,
        "characteristic_length": spec.characteristic_length,
        "solver": solver,
        "seeds": spec.seeds,
        "seed": spec.seed,
        "max_iterations": spec.max_iterations,
        "targets": entries,
        "summary": summary,
    }
    artifacts: tuple[Artifact, ...] = ()
    if spec.plots:
        progress.report(85.0, "plots")
        drawn = solution.q[np.flatnonzero(solution.reached)[:DRAWN]]
        figure = reach_figure(arm, targets.positions, solution.reached,
                              joint_frames(arm, drawn), forward_kinematics(arm, drawn),
                              spec.length_unit)  # fmt: skip
        artifacts = figure_artifacts(figure, "reach", "Targets reached or not, and the arm "
                                     "at a few solutions")  # fmt: skip
    progress.report(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(_notes(spec, solver)))


def _notes(spec: SerialReachSpec, solver: str) -> list[str]:
    if solver == CLOSED_FORM:
        notes = ["Planar 3R arm: closed-form inverse kinematics (both elbow branches, "
                 "moved into the joint limits by whole turns); a position-only target scans "
                 "the tool angle in 0.2 degree steps and keeps the most manipulable "
                 "solution. Targets the closed form does not reach are tried by damped "
                 f"least squares too ({spec.seeds} seeded start(s), seed {spec.seed}), for "
                 "their closest configuration."]  # fmt: skip
    else:
        notes = [f"Damped least squares (Levenberg-Marquardt) from {spec.seeds} seeded "
                 f"start(s) per target (seed {spec.seed}), at most {spec.max_iterations} "
                 "iterations, stuck starts restarted; of the starts that converged, the "
                 "most manipulable solution is reported."]  # fmt: skip
    notes.append("A target not reached reports the closest configuration found and its "
                 "residual; its manipulability and inverse condition are null.")  # fmt: skip
    if spec.characteristic_length is not None:
        notes.append(f"The inverse condition number divides the linear rows by the "
                     f"characteristic length {spec.characteristic_length:g} "
                     f"{spec.length_unit}.")  # fmt: skip
    return notes
