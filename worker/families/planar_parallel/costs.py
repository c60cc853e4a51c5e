"""Work limits of the planar2dof jobs, checked by the service before a job is queued.

Cost is counted in 1/kappa evaluations (one inverse kinematics + eq 7 at one point).
The rectangle search of one delta is priced at :data:`RECTANGLE_SEARCH_COST`
evaluations, about what it takes in time (a column scan of 257 x 160 points, its
root refinements and the boundary check; ~17 ms, like 60,000 mesh points).
"""

from __future__ import annotations

from worker.families.planar_parallel.discretisation import (
    BOUNDARY_COLUMNS,
    BOUNDARY_ROWS,
    FIG9_MESH,
    MAP_POINTS_PER_AXIS,
)
from worker.families.planar_parallel.specs import (
    DEFAULT_DELTA_RANGE,
    DEFAULT_DELTA_STEP,
    ConditioningMapSpec,
    OptimisationSpec,
    sweep_deltas,
)

__all__ = [
    "CONDITIONING_MAP_COST_LIMIT",
    "CONDITIONING_MAP_SYNC_COST_LIMIT",
    "CONDITIONING_MAP_TIME_LIMIT_S",
    "COST_UNIT",
    "OPTIMISATION_COST_LIMIT",
    "OPTIMISATION_TIME_LIMIT_S",
    "RECTANGLE_SEARCH_COST",
    "conditioning_map_cost",
    "optimisation_cost",
]

COST_UNIT = "1/kappa evaluations"
#: One delta's rectangle search, in 1/kappa evaluations (time-equivalent).
RECTANGLE_SEARCH_COST = 60_000
#: The W_kappa0 boundary search: a scan of columns x rows (plus refinements).
BOUNDARY_SEARCH_COST = BOUNDARY_COLUMNS * BOUNDARY_ROWS
#: Fixed work of the optimisation's figures: the Fig. 9 mesh and the map behind Fig. 6.
FIGURE_COST = FIG9_MESH**2 + MAP_POINTS_PER_AXIS**2

#: A 2001 x 2001 map with W_kappa0 and 1000 points (4,262,122) fits.
CONDITIONING_MAP_COST_LIMIT = 5_000_000
#: Up to this cost a map is answered synchronously (``Prefer: wait=N``) and previewed
#: by the live explorer: the paper's figures (a 301 x 301 grid with W_kappa0's exact
#: boundary and a few given points: a few seconds as a job, plots included; a preview,
#: which skips the boundary, ~70 ms on 201 x 201).
CONDITIONING_MAP_SYNC_COST_LIMIT = 301 * 301 + BOUNDARY_SEARCH_COST + 1000
#: About 12x the default sweep (151 deltas, 101² mesh: 10,754,353): e.g. 1501 deltas
#: (step 0.001) on a 101² mesh, or the default sweep on an 801² mesh.
OPTIMISATION_COST_LIMIT = 120_000_000
#: Wall-clock limits of one attempt, in seconds (a 2001² map spends most of its time
#: writing a 400 MB CSV; the largest sweep takes about a minute).
CONDITIONING_MAP_TIME_LIMIT_S = 900.0
OPTIMISATION_TIME_LIMIT_S = 600.0


def conditioning_map_cost(spec: ConditioningMapSpec) -> int:
    """Grid points + given points (+ the boundary search when a limit is given)."""
    boundary = BOUNDARY_SEARCH_COST if spec.inverse_condition_limit is not None else 0
    return spec.grid.points_per_axis**2 + len(spec.points or ()) + boundary


def optimisation_cost(spec: OptimisationSpec) -> int:
    """deltas x (mean_mesh² + the rectangle search) + the figures' fixed work.

    A single delta also pays for S_max's rectangles over the paper's range.
    """
    per_delta = spec.mean_mesh**2 + RECTANGLE_SEARCH_COST
    if spec.delta is None:
        return spec.sweep_size * per_delta + FIGURE_COST
    reference = len(sweep_deltas(*DEFAULT_DELTA_RANGE, DEFAULT_DELTA_STEP))
    return per_delta + reference * (4 + RECTANGLE_SEARCH_COST) + FIGURE_COST
