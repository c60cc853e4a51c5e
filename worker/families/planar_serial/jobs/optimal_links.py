"""The ``planar3r-design`` job: link lengths (and the base) chosen for a task under the
joint limits it really has, against the paper's rule (eqs 10-11) under the same limits.

The search is :mod:`.link_search` (differential evolution over the exact d_z, then
Nelder-Mead); the figures and data files are :mod:`.optimum_artifacts`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.common.progress import ProgressReporter
from worker.contract import JobContext, JobOutcome
from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.design_spec import DesignSpec
from worker.families.planar_serial.jobs.dexterity_evaluation import FULL_DEXTERITY_TOL
from worker.families.planar_serial.jobs.link_search import (
    Design,
    DesignObjective,
    SearchOutcome,
    SearchSpace,
    search,
)
from worker.families.planar_serial.jobs.optimum_artifacts import design_artifacts
from worker.families.planar_serial.jobs.task_points import shortfall_notes
from worker.families.planar_serial.jobs.trajectories import (
    task_distance_range,
    trajectory_samples,
    trajectory_summary,
)

__all__ = ["STALL_FRACTION", "run_design"]

FloatArray = NDArray[np.float64]

#: The search counts as converged when the last quarter of its generations brought less
#: than 1% of its whole gain in score (from the first generation's best to the last's).
STALL_FRACTION = 0.25
STALL_SHARE = 0.01


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
        objective, seed=spec.seed, population_size=spec.population_size,
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
    distances = task_distance_range(spec.trajectory, spec.task_points)
    d_min, d_max = distances.d_min, distances.d_max
    if spec.round_distances:
        d_min, d_max = float(math.floor(d_min)), float(math.ceil(d_max))
    l3 = spec.paper_l3 if spec.paper_l3 is not None else (spec.total_length_max - d_max - 1) / 2
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
    scores = [entry["score"] for entry in outcome.history]
    tail = max(1, math.ceil(STALL_FRACTION * len(scores)))
    late_gain = scores[-tail - 1] - scores[-1] if len(scores) > tail else math.inf
    stalled = late_gain <= STALL_SHARE * (scores[0] - scores[-1]) + 1e-12
    met = spec.objective == "max_min_dz" or objective.meets_target(outcome.best)
    if not met:
        message = (
            f"no design within the bounds keeps d_z >= {spec.dz_target:g} at every point: "
            f"the best found reaches {outcome.best.min_dz:.6f}"
        )
    elif stalled:
        message = (
            f"converged: the last {tail} generations brought less than "
            f"{100 * STALL_SHARE:g}% of the search's gain"
        )
    else:
        message = (
            f"the best design was still improving in the last {tail} generations (more "
            f"than {100 * STALL_SHARE:g}% of the search's gain): more max_generations may "
            "do better"
        )
    return {
        "success": bool(met and stalled),
        "message": message,
        "seed": spec.seed,
        "evaluations": outcome.evaluations,
        "generations": outcome.global_stage["generations"],
        "best_per_generation": outcome.history,
        "global_search": outcome.global_stage,
        "polish": outcome.polish,
    }


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
