"""Work limits of the spm jobs, checked by the service before a job is queued.

Cost is counted in pose evaluations: one inverse kinematics + 1/kappa at one
orientation (about 2 µs vectorised). Fixed work is priced in the same unit, by time:

* every design scored also pays :data:`DESIGN_OVERHEAD` (the per-call work, ~0.6 ms);
* the least 1/kappa on the closed workspace is a grid of :data:`WORKSPACE_MINIMUM_COST`
  poses;
* a design-space width (eq 19) is closed-form for a full torsion turn (1) and a grid
  search with polishing for a limited range (:data:`LIMITED_WIDTH_COST`).

conditioning map: samples + given orientations + map and sweep points + the minimum.
design space: betas x width + (index map) points² x (samples + overhead).
optimisation: starts x (evaluation budget x (1 + free variables) + the screened
candidates) x (samples + overhead, + a width search per evaluation when a limited torsion
range meets a free beta or gamma), + the figures' index map, the twins and the minimum.
"""

from __future__ import annotations

from worker.families.spherical_parallel.optimisation_spec import (
    INDEX_MAP_POINTS,
    SCREEN_PER_START,
    OptimisationSpec,
)
from worker.families.spherical_parallel.specs import (
    SWEEP_POINTS,
    ConditioningMapSpec,
    DesignSpaceSpec,
)
from worker.families.spherical_parallel.workspace_spec import WorkspaceSpec

__all__ = [
    "CONDITIONING_MAP_COST_LIMIT",
    "CONDITIONING_MAP_SYNC_COST_LIMIT",
    "CONDITIONING_MAP_TIME_LIMIT_S",
    "COST_UNIT",
    "DESIGN_OVERHEAD",
    "DESIGN_SPACE_COST_LIMIT",
    "DESIGN_SPACE_SYNC_COST_LIMIT",
    "DESIGN_SPACE_TIME_LIMIT_S",
    "LIMITED_WIDTH_COST",
    "OPTIMISATION_COST_LIMIT",
    "OPTIMISATION_TIME_LIMIT_S",
    "WORKSPACE_MINIMUM_COST",
    "conditioning_map_cost",
    "design_space_cost",
    "optimisation_cost",
]

COST_UNIT = "pose evaluations (inverse kinematics + 1/kappa at one orientation)"
DESIGN_OVERHEAD = 300
WORKSPACE_MINIMUM_COST = 24 * 13 * 72
LIMITED_WIDTH_COST = 5000

#: 500,000 poses: e.g. 100 x 50 x 100 samples (about 0.6 GB of work arrays at the peak).
CONDITIONING_MAP_COST_LIMIT = 500_000
#: Up to 100,000 (the default 144 samples with the default maps and sweeps: 38,575) may be
#: answered synchronously.
CONDITIONING_MAP_SYNC_COST_LIMIT = 100_000
CONDITIONING_MAP_TIME_LIMIT_S = 600.0

#: About 100 s of work: e.g. 721 betas with a limited torsion range and a 101² index map
#: on 4,000 samples.
DESIGN_SPACE_COST_LIMIT = 50_000_000
#: The paper's Figs 5-6 (3 betas and a 31² index map on 144 samples: 426,687) fit.
DESIGN_SPACE_SYNC_COST_LIMIT = 1_000_000
DESIGN_SPACE_TIME_LIMIT_S = 600.0

#: About 10-20 minutes: e.g. 16 starts x 200 evaluations on 1,000 samples with 4 variables.
OPTIMISATION_COST_LIMIT = 500_000_000
OPTIMISATION_TIME_LIMIT_S = 1800.0


def _width_cost(workspace: WorkspaceSpec) -> int:
    return 1 if workspace.full_turn else LIMITED_WIDTH_COST


def conditioning_map_cost(spec: ConditioningMapSpec) -> int:
    """samples + orientations + map points + sweep points + the closed-workspace minimum."""
    maps = len(spec.map_torsions) * spec.map_grid.azimuth * spec.map_grid.tilt
    return (
        spec.workspace.samples.count
        + len(spec.orientations or ())
        + maps
        + len(spec.sweeps) * SWEEP_POINTS
        + WORKSPACE_MINIMUM_COST
        + _width_cost(spec.workspace)
    )


def design_space_cost(spec: DesignSpaceSpec) -> int:
    """betas x width search (+ the index map's designs x (samples + overhead))."""
    cost = len(spec.betas) * _width_cost(spec.workspace)
    if spec.index_map is not None:
        designs = spec.index_map.points_per_side**2
        cost += designs * (spec.workspace.samples.count + DESIGN_OVERHEAD)
    return cost


def optimisation_cost(spec: OptimisationSpec) -> int:
    """starts x (budget x (1 + variables) + screen) x per-evaluation work, + the figures'
    fixed work."""
    samples = spec.workspace.samples.count
    per_evaluation = samples + DESIGN_OVERHEAD
    if not spec.workspace.full_turn and {"beta", "gamma"} & set(spec.free):
        per_evaluation += LIMITED_WIDTH_COST
    per_start = spec.max_evaluations_per_start * (1 + spec.solver_variables) + SCREEN_PER_START
    evaluations = spec.starts * per_start
    figures = INDEX_MAP_POINTS**2 * (samples + DESIGN_OVERHEAD) if spec.plots else 0
    return evaluations * per_evaluation + figures + 4 * samples + WORKSPACE_MINIMUM_COST
