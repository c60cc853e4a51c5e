"""Work limits of the planar3r jobs, checked by the service before a job is queued.

Cost is counted in grid points x orientation samples: the exact closed form costs one
unit per grid point, orientation sampling under joint limits one per point and sample.
"""

from __future__ import annotations

from worker.families.planar_serial.jobs.dexterity_evaluation import orientation_sampling
from worker.families.planar_serial.specs import DexterityMapSpec, GridSpec, SynthesisSpec

__all__ = [
    "COST_LIMIT",
    "SYNC_COST_LIMIT",
    "TIME_LIMIT_S",
    "dexterity_map_cost",
    "synthesis_cost",
]

#: Largest accepted cost: a 2001 x 2001 map sampled every 0.5° (720 samples) fits.
COST_LIMIT = 3_000_000_000
#: Requests up to this cost may be answered synchronously (``Prefer: wait=N``): an
#: exact map of up to 101 x 101 points.
SYNC_COST_LIMIT = 101 * 101
#: Wall-clock limit of one job attempt, in seconds.
TIME_LIMIT_S = 1800.0


def _grid_points(grid: GridSpec) -> int:
    return grid.points_per_axis**2


def _samples(spec: DexterityMapSpec | SynthesisSpec) -> int:
    """Orientation samples per grid point under the joint limits; 1 without limits.

    Limits that all span the full turn [-180, 180] are run by the exact closed form.
    """
    sampling = orientation_sampling(spec.joint_limits_deg, spec.orientation_step_deg)
    return 1 if sampling is None else sampling.samples


def dexterity_map_cost(spec: DexterityMapSpec) -> int:
    """Grid points x (orientation samples under joint limits, else 1)."""
    return _grid_points(spec.grid) * _samples(spec)


def synthesis_cost(spec: SynthesisSpec) -> int:
    """Grid points x (2 + orientation samples of Case 3 when joint limits are given).

    Cases 1 and 2 are exact maps (one unit per point each); Case 3 is sampled.
    """
    case_3 = _samples(spec) if spec.joint_limits_deg is not None else 0
    return _grid_points(spec.grid) * (2 + case_3)
