"""The ``planar3r-design`` job: link lengths (and the base) chosen for a task under the
joint limits it really has, against the paper's rule (eqs 10-11) under the same limits.

The search is :mod:`.link_search` (independent starts of differential evolution over the
exact d_z, each polished by Nelder-Mead; success only when two starts agree on the best
score); the score is :mod:`.design_objective`; the figures and data files are
:mod:`.optimum_artifacts`.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.common.progress import ProgressReporter
from worker.contract import JobContext, JobOutcome
from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.design_spec import DesignSpec
from worker.families.planar_serial.jobs.design_objective import (
    Design,
    DesignObjective,
    SearchSpace,
)
from worker.families.planar_serial.jobs.dexterity_evaluation import FULL_DEXTERITY_TOL
from worker.families.planar_serial.jobs.link_search import (
    AGREEMENT_TOL,
    SearchOutcome,
    StartOutcome,
    search,
)
from worker.families.planar_serial.jobs.optimum_artifacts import design_artifacts
from worker.families.planar_serial.jobs.task_points import shortfall_notes
from worker.families.planar_serial.jobs.trajectories import trajectory_samples, trajectory_summary

__all__ = ["run_design"]

FloatArray = NDArray[np.float64]


def run_design(spec: DesignSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + artifacts + notes out."""
    progress = ProgressReporter(ctx)
    progress.report(0.0, "starting")
    task_xy = np.asarray(spec.task_points or (), dtype=float).reshape(-1, 2)
    path = trajectory_samples(spec.trajectory) if spec.trajectory is not None else None
    points = task_xy if path is None else np.concatenate([task_xy, path])
    space = SearchSpace(np.asarray(spec.search_bounds), spec.total_length_max, spec.base_box)
    objective = DesignObjective(points, _limits_rad(spec), spec.objective, spec.dz_target, space)
    outcome = search(
        objective, seed=spec.seed, starts=spec.starts, population_size=spec.population_size,
        generations=spec.max_generations, on_generation=progress.span(2.0, 85.0, "search"),
    )  # fmt: skip
    progress.report(85.0, "the paper's rule")
    rule = _paper_rule(spec, objective)
    result = {
        "objective": spec.objective,
        "dz_target": spec.dz_target if spec.objective == "min_length" else None,
        "joint_limits_deg": None
        if spec.joint_limits_deg is None
        else [list(pair) for pair in spec.joint_limits_deg],
        "method": "exact-closed-form" if objective.joint_limits_rad is None else "exact-events",
        "optimum": _design_entry(spec, objective, outcome.best, task_xy.shape[0]),
        "paper_rule": rule,
        "improvement": _improvement(spec, objective, outcome.best, rule),
        "convergence": _convergence(spec, objective, outcome),
        "search_space": {
            "link_bounds": [list(pair) for pair in spec.search_bounds],
            "l3_held": spec.held_l3,
            "l3_chosen": _l3_chosen(spec),
            "total_length_max": spec.total_length_max,
            "base_box": None if spec.base_box is None else list(spec.base_box),
            "free_variables": spec.free_variables,
        },
        "evaluation_points": {"task_points": int(task_xy.shape[0]),
                              "trajectory_samples": 0 if path is None else int(path.shape[0])},
        "length_unit": spec.length_unit,
    }  # fmt: skip
    notes = _notes(spec, result)
    progress.report(88.0, "maps and plots")
    artifacts = design_artifacts(spec, result, outcome, task_xy, path)
    progress.report(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(notes))


def _l3_chosen(spec: DesignSpec) -> str:
    if spec.link_bounds is not None:
        return "designed within link_bounds" if spec.held_l3 is None else "link_bounds (lo = hi)"
    return "l3" if spec.l3 is not None else "the paper rule's l3 for total_length_max"


def _limits_rad(spec: DesignSpec) -> FloatArray | None:
    limits = spec.joint_limits_deg
    if limits is None or all(lo <= -180.0 and hi >= 180.0 for lo, hi in limits):
        return None
    return np.asarray(np.radians(np.asarray(limits, dtype=float)), dtype=np.float64)


def _design_entry(
    spec: DesignSpec, objective: DesignObjective, design: Design, task_count: int
) -> dict[str, Any]:
    """links, base, min/mean d_z, total, per task point d_z, the trajectory summary."""
    task_dz, path_dz = design.d_z[:task_count], design.d_z[task_count:]
    return {
        "links": list(design.links),
        "base": list(design.base),
        "min_dz": design.min_dz,
        "mean_dz": design.mean_dz,
        "total_length": design.total_length,
        "meets_target": objective.meets_target(design) if spec.objective == "min_length" else None,
        "task_points": [
            {"label": label, "x": float(x), "y": float(y), "d_z": float(dz)}
            for label, (x, y), dz in zip(
                spec.labels, objective.points[:task_count], task_dz, strict=True
            )
        ],
        "trajectory": trajectory_summary(path_dz) if path_dz.size else None,
    }


def _paper_rule(spec: DesignSpec, objective: DesignObjective) -> dict[str, Any] | None:
    """Eqs (10)-(11) from the task's distance range, base at the origin, same limits."""
    d_min, d_max = spec.rule_distances
    l3 = spec.paper_l3 if spec.paper_l3 is not None else spec.budget_l3
    if l3 <= 0.0:
        return None
    links = planar_serial.synthesise_links(d_min, d_max, l3)
    design = objective.evaluate(links, (0.0, 0.0))
    count = len(spec.task_points or ())
    return {
        **_design_entry(spec, objective, design, count),
        "l3_chosen": "paper_l3" if spec.paper_l3 is not None else "fills total_length_max",
        "d_min_used": d_min,
        "d_max_used": d_max,
    }


def _improvement(
    spec: DesignSpec, objective: DesignObjective, best: Design, rule: dict[str, Any] | None
) -> dict[str, Any] | None:
    if rule is None:
        return None
    if spec.objective == "max_min_dz":
        gain = best.min_dz - rule["min_dz"]
        return {
            "min_dz": gain,
            "relative": gain / rule["min_dz"] if rule["min_dz"] > 0 else None,
        }
    return {
        "total_length": rule["total_length"] - best.total_length,
        "paper_rule_meets_target": rule["meets_target"],
        "optimum_meets_target": objective.meets_target(best),
    }


def _convergence(
    spec: DesignSpec, objective: DesignObjective, outcome: SearchOutcome
) -> dict[str, Any]:
    kept, agreeing = outcome.kept, outcome.agreeing
    met = spec.objective == "max_min_dz" or objective.meets_target(outcome.best)
    confirmed = len(agreeing) >= 2
    quantity = "smallest d_z" if spec.objective == "max_min_dz" else "total length"
    if not met:
        message = (
            f"no design within the bounds keeps d_z >= {spec.dz_target:g} at every point: "
            f"the best found reaches {outcome.best.min_dz:.6f}"
        )
    elif confirmed:
        message = (
            f"confirmed: {len(agreeing)} of {spec.starts} independent starts reach the best "
            f"score within {AGREEMENT_TOL:g}"
        )
    elif spec.starts == 1:
        message = "not confirmed: one start cannot be checked against another (starts >= 2)"
    else:
        others = [s for s in sorted(outcome.starts, key=lambda s: s.score) if s is not kept]
        reached = list(dict.fromkeys(f"{_objective_value(spec, s.best):.6g}" for s in others))
        message = (
            f"not confirmed: only start {kept.index} of {spec.starts} reaches the best "
            f"{quantity}, {_objective_value(spec, kept.best):.6g}; "
            f"{'the other start' if len(others) == 1 else 'the others'} stopped at "
            + ", ".join(reached[:4])
            + (", ..." if len(reached) > 4 else "")
            + ": the best found may not be the optimum (more starts may tell)"
        )
    return {
        "success": bool(met and confirmed),
        "message": message,
        "seed": spec.seed,
        "starts": [
            _start_entry(spec, objective, start, start.index in agreeing)
            for start in outcome.starts
        ],
        "kept_start": kept.index,
        "agreeing_starts": len(agreeing),
        "agreement_tol": AGREEMENT_TOL,
        "evaluations": outcome.evaluations,
        "generations": kept.global_stage["generations"],
        "best_per_generation": kept.history,
        "global_search": kept.global_stage,
        "polish": kept.polish,
    }


def _objective_value(spec: DesignSpec, design: Design) -> float:
    """What the objective drives: the smallest d_z, or the total length."""
    return design.min_dz if spec.objective == "max_min_dz" else design.total_length


def _start_entry(
    spec: DesignSpec, objective: DesignObjective, start: StartOutcome, agrees: bool
) -> dict[str, Any]:
    return {
        "start": start.index,
        "seed": start.seed,
        "score": start.score,
        "min_dz": start.best.min_dz,
        "total_length": start.best.total_length,
        "meets_target": objective.meets_target(start.best)
        if spec.objective == "min_length" else None,
        "links": list(start.best.links),
        "base": list(start.best.base),
        "agrees_with_best": agrees,
        "evaluations": start.evaluations,
    }  # fmt: skip


def _notes(spec: DesignSpec, result: dict[str, Any]) -> list[str]:
    optimum, rule = result["optimum"], result["paper_rule"]
    links = ", ".join(f"{v:.4f}" for v in optimum["links"])
    notes = [
        f"Optimum links ({links}), total {optimum['total_length']:.4f} {spec.length_unit}, "
        f"base at ({optimum['base'][0]:.4g}, {optimum['base'][1]:.4g}): smallest d_z "
        f"{optimum['min_dz']:.4f} over the task."
    ]
    if rule is None:
        notes.append(
            "The paper's rule is not reported: total_length_max leaves no positive l3 "
            "(d_max + 2 l3 + 1 <= total_length_max); give paper_l3 to compare."
        )
    else:
        rule_links = ", ".join(f"{v:.4f}" for v in rule["links"])
        notes.append(
            f"The paper's rule (eqs 10-11, base at the origin) gives ({rule_links}), total "
            f"{rule['total_length']:.4f}, smallest d_z {rule['min_dz']:.4f} under the same "
            "joint limits."
        )
    if not result["convergence"]["success"]:
        notes.append(f"Search: {result['convergence']['message']}.")
    short = [e for e in optimum["task_points"] if e["d_z"] < 1.0 - FULL_DEXTERITY_TOL]
    notes += shortfall_notes(short, "optimum: ")
    return notes
