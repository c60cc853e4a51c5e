"""The study kernel of ``planar2dof-conditioning-map`` (:mod:`worker.study_kernels`).

A design study varying the dimensions (``l1``, ``l2``, ``e``) and the conditioning
limit (``inverse_condition_limit``) of one robot type in one working mode evaluates
1/kappa on every design's grid at once, in tiles of designs x grid rows
(:mod:`~worker.families.planar_parallel.kinematics.study_kernel`): ``summary``'s
reachable nodes and area and the least, largest and mean 1/kappa; W_kappa0's grid
area, and its ``area``, ``rectangle_region_area`` and largest 1/kappa (value and
place) by the job's own column search, design by design (its adaptive refinement is
per robot); and the numbers that echo the inputs (``l1``, ``l2``, ``e``, ``delta``,
``working_mode``, the limit, the grid).  The pressure angles, the isotropic point, the
boundary and the given points are the job's alone.

Refusals, exactly as the process makes them: the first of ``l1``, ``l2``, ``e``,
``inverse_condition_limit`` out of its range (pydantic's field errors, ``e`` between 0
and 1e-6 included), then the model's checks in its order: eq (12)'s l2 >= l1 (at
``inputs``), the lengths' ratio (at the length it names), chains that cannot meet (at
``e``), a grid whose sides are out of scale with the robot (at ``grid.bounds``).  No
shortcut: every refusal is checked.  The numbers are the job's to the bit (the same
formulas node by node, the same search for W_kappa0), but for the mean 1/kappa, summed
in tiles (to about 1e-15).
"""

from __future__ import annotations

from worker.families.planar_parallel.result_paths import GRID_PATHS, REGION_PATHS
from worker.study_kernels import KernelPlan, KernelRequest, StudyKernel

__all__ = ["CONDITIONING_MAP_KERNEL", "COVERS", "GRID_PATHS", "REGION_PATHS"]

#: Paths the kernel echoes (GRID_PATHS, REGION_PATHS: :mod:`.result_paths`).
ECHO_PATHS = (
    "l1", "l2", "e", "delta", "working_mode[]", "w_kappa0.inverse_condition_limit",
    "discretisation.grid.bounds[]", "discretisation.grid.points_per_axis",
    "discretisation.grid.step[]",
)  # fmt: skip
COVERS = (*ECHO_PATHS, *GRID_PATHS, *REGION_PATHS)
#: Seconds per unit of cost (a 1/kappa evaluation) for one design, batched: W_kappa0's
#: search (about 0.1 s for its ~330,000 evaluations, priced at 801 x 321) sets it; a
#: grid node alone takes about a tenth of it (bench/design_study.py measures both).
SECONDS_PER_COST = 4e-7


def _prepare(request: KernelRequest) -> KernelPlan:
    # lazy: the kernel's arithmetic (scipy) loads when a study runs, not with the registry
    from worker.families.planar_parallel.study_plan import ConditioningMapPlan

    return ConditioningMapPlan.of(request)


CONDITIONING_MAP_KERNEL = StudyKernel(
    covers=COVERS,
    varies={"l1": 1.0, "l2": 1.0, "e": 0.5, "inverse_condition_limit": 0.5},
    prepare=_prepare,
    seconds_per_cost=SECONDS_PER_COST,
    description="1/kappa over every design's grid (reachable nodes, least, largest and "
    "mean) batched over designs and grid rows; W_kappa0's areas by the job's column "
    "search, design by design; l1, l2, e and the conditioning limit varied.",
)
