"""Work limits of the planar3r jobs, checked by the service before a job is queued.

Cost is counted in grid points x orientations tested: the exact closed form costs one
unit per grid point; under joint limits the exact events cost one per point and sub-arc
between events (at most 21), orientation sampling one per point and sample.
"""

from __future__ import annotations

import numpy as np

from worker.families.planar_serial.design_spec import POLISH_EVALUATIONS_PER_VARIABLE, DesignSpec
from worker.families.planar_serial.jobs.dexterity_evaluation import limited_joints
from worker.families.planar_serial.kinematics.limited_exact import event_count
from worker.families.planar_serial.specs import DexterityMapSpec, GridSpec, SynthesisSpec

__all__ = [
    "COST_LIMIT",
    "SYNC_COST_LIMIT",
    "TIME_LIMIT_S",
    "design_calls",
    "design_cost",
    "design_evaluations",
    "design_time_limit",
    "dexterity_map_cost",
    "synthesis_cost",
]

#: Largest accepted cost: a 2001 x 2001 map sampled every 0.5° (720 samples) fits.
COST_LIMIT = 3_000_000_000
#: Requests up to this cost may be answered synchronously (``Prefer: wait=N``) and
#: previewed by the live explorer: an exact map of up to 101 x 101 points, under joint
#: limits too (exact events: at most 21 sub-arcs a node; ~10 ms of arithmetic).
SYNC_COST_LIMIT = 101 * 101 * 21
#: Wall-clock limit of one job attempt, in seconds.
TIME_LIMIT_S = 1800.0
#: The least time limit of a planar3r-design attempt, however cheap.
MIN_DESIGN_TIME_LIMIT_S = 300.0


def _grid_points(grid: GridSpec) -> int:
    return grid.points_per_axis**2


def _samples(spec: DexterityMapSpec | SynthesisSpec) -> int:
    """Orientations tested per grid point under the joint limits; 1 without limits.

    Limits that all span the full turn [-180, 180] are run by the exact closed form.
    """
    limited = limited_joints(spec.joint_limits_deg, spec.orientation_step_deg, spec.method)
    return 1 if limited is None else limited.evaluations_per_point


def dexterity_map_cost(spec: DexterityMapSpec) -> int:
    """Grid points x (orientations tested per point under joint limits, else 1)."""
    return _grid_points(spec.grid) * _samples(spec)


def synthesis_cost(spec: SynthesisSpec) -> int:
    """Grid points x (2 + orientations tested per point in Case 3, with joint limits).

    Cases 1 and 2 are closed-form maps (one unit per point each).
    """
    case_3 = _samples(spec) if spec.joint_limits_deg is not None else 0
    return _grid_points(spec.grid) * (2 + case_3)


def design_evaluations(spec: DesignSpec) -> int:
    """Most designs the search evaluates: per start, population x (generations + 1)
    for differential evolution, the polish (at most 200 per free variable) and one per
    generation for the convergence record."""
    variables = spec.free_variables
    global_stage = spec.population_size * variables * (spec.max_generations + 1)
    one_by_one = POLISH_EVALUATIONS_PER_VARIABLE * variables + spec.max_generations
    return spec.starts * (global_stage + one_by_one)


def design_calls(spec: DesignSpec) -> int:
    """Most evaluations of d_z the search makes (each pays numpy's per-call overhead):
    per start, one per generation of differential evolution (its population at once),
    one per design of the polish and of the convergence record."""
    variables = spec.free_variables
    one_by_one = POLISH_EVALUATIONS_PER_VARIABLE * variables + spec.max_generations
    return spec.starts * (spec.max_generations + 1 + one_by_one)


#: The fixed cost of one evaluation of d_z (numpy's and the optimiser's per-call
#: overhead), in units: about as much as 200 points with 17 sub-arcs each.
DESIGN_CALL_UNITS = 3400


def design_cost(spec: DesignSpec) -> int:
    """Designs evaluated x evaluation points x orientations tested per point, plus
    3400 units per evaluation of d_z (its fixed overhead), plus the two maps of the
    plots (grid points x orientations tested).

    Exact d_z tests one orientation per point without joint limits, one per sub-arc
    between events (at most 21) under them.
    """
    limits = spec.joint_limits_deg
    if limits is None or all(lo <= -180.0 and hi >= 180.0 for lo, hi in limits):
        per_point = 1
    else:
        radians = np.radians(np.asarray(limits, dtype=float))
        per_point = event_count(radians) + 1
    points = len(spec.task_points or ()) + (
        spec.trajectory.samples if spec.trajectory is not None else 0
    )
    search = design_evaluations(spec) * points * per_point + design_calls(spec) * DESIGN_CALL_UNITS
    return search + 2 * _grid_points(spec.grid) * per_point


def design_time_limit(spec: DesignSpec) -> float:
    """The time limit of one attempt: in proportion to the cost (a job at COST_LIMIT
    gets TIME_LIMIT_S, more than 5 times what it needs on one core), at least
    MIN_DESIGN_TIME_LIMIT_S; so it grows with ``starts`` as the work does."""
    share = design_cost(spec) / COST_LIMIT
    return min(TIME_LIMIT_S, max(MIN_DESIGN_TIME_LIMIT_S, share * TIME_LIMIT_S))
