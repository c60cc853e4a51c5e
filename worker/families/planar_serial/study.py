"""The study kernel of ``planar3r-dexterity-map`` (:mod:`worker.study_kernels`).

A design study varying the links (``links[0]``, ``links[1]``, ``links[2]``) evaluates
every design at the task points and along the trajectory at once
(:mod:`~worker.families.planar_serial.kinematics.study_kernel`): each task point's d_z,
D, region and position, the trajectory's eq (4) statistics, and the numbers that echo
the inputs (``links``, the grid, the radial section).  Under joint limits d_z is exact
by events, as the job computes it; with method ``orientation-sampling`` the kernel
runs the job's own sampling design by design.  The grid's ``summary`` and ``areas``
come from each design's own map over its own grid, only when a study reads them:
with revolute joints a tile of designs' maps at once (the closed form, node by node
as the job's map), under joint limits each map as the job computes it; both summed
up by the job's own functions (:mod:`~.jobs.map_statistics`).  The regions,
the bands along the ray and the radial section are not computed: a study of these
paths runs per design.

Refusals, exactly as the process makes them: the first link outside [1e-6, 1e6] (in
the order l1, l2, l3: pydantic's), then links whose longest is more than 1e6 times the
shortest (at ``inputs.links``), then a grid (given ``bounds``) that holds no point of
the reachable annulus (at ``inputs.grid.bounds``).  A task point or trajectory out of
reach is a warning, not a refusal: its d_z is 0.
"""

from __future__ import annotations

from worker.families.planar_serial.result_paths import MAP_PATHS
from worker.families.planar_serial.study_plan import DexterityMapPlan
from worker.study_kernels import KernelPlan, KernelRequest, StudyKernel

__all__ = ["COVERS", "DEXTERITY_MAP_KERNEL", "MAP_PATHS", "SECONDS_PER_POINT_EVALUATION"]

_TASK_POINTS = ("x", "y", "distance", "d_z", "D", "region")
_TRAJECTORY = ("samples", "d_z_mean", "D_mean", "d_z_min", "fully_dexterous_fraction")
_ECHOES = (
    "links[]",
    "discretisation.grid.bounds[]",
    "discretisation.grid.points_per_axis",
    "discretisation.grid.step[]",
    "discretisation.radial_section.angle_deg",
    "discretisation.radial_section.samples",
    "discretisation.radial_section.d_to",
)
COVERS = (
    *_ECHOES,
    *MAP_PATHS,
    *(f"task_points[].{name}" for name in _TASK_POINTS),
    *(f"trajectory.{name}" for name in _TRAJECTORY),
)
#: Seconds per unit of the plan's cost (a point x an orientation tested there: a
#: sub-arc between events under joint limits) for one design, batched: about 0.12 µs
#: for task points under joint limits, 0.12 µs a node for revolute maps and 0.16 µs a
#: node and sub-arc for limited maps on the 2-core test machine at load 5
#: (bench/design_study.py measures it).
SECONDS_PER_POINT_EVALUATION = 1.5e-7


def _prepare(request: KernelRequest) -> KernelPlan:
    return DexterityMapPlan.of(request)


DEXTERITY_MAP_KERNEL = StudyKernel(
    covers=COVERS,
    varies={"links[]": 10.0},
    prepare=_prepare,
    seconds_per_cost=SECONDS_PER_POINT_EVALUATION,
    description="d_z at every task point and along the trajectory (exact, joint limits "
    "included) of many arms at once; the links varied.",
)
