"""Work limits of the serial-arm jobs, checked before a job is queued.

``serial-indices`` costs configurations x joints (a forward pass, a Jacobian and an SVD
each, about a microsecond a joint).  ``serial-reach`` costs targets x seeds x
max_iterations x joints: the damped least-squares work if no seed converged early.
"""

from __future__ import annotations

from worker.families.serial.reach_spec import SerialReachSpec
from worker.families.serial.specs import MAX_CONFIGURATIONS, SerialIndicesSpec

__all__ = [
    "INDICES_COST_LIMIT",
    "INDICES_SYNC_COST_LIMIT",
    "REACH_COST_LIMIT",
    "REACH_SYNC_COST_LIMIT",
    "TIME_LIMIT_S",
    "indices_cost",
    "reach_cost",
]

INDICES_COST_LIMIT = MAX_CONFIGURATIONS * 12
#: Up to this cost (a thousand configurations of a 12-joint arm) answered synchronously.
INDICES_SYNC_COST_LIMIT = 12_000
TIME_LIMIT_S = 300.0


def indices_cost(spec: SerialIndicesSpec) -> int:
    """Configurations x joints."""
    return len(spec.configurations) * len(spec.configurations[0])


#: serial-reach: e.g. 2,000 targets x 8 seeds x 200 iterations x 12 joints.
REACH_COST_LIMIT = 40_000_000
#: Up to this (e.g. 20 targets x 8 seeds x 200 iterations x 6 joints) answered synchronously.
REACH_SYNC_COST_LIMIT = 200_000


def reach_cost(spec: SerialReachSpec) -> int:
    """Targets x seeds x max_iterations x joints."""
    return len(spec.targets) * spec.seeds * spec.max_iterations * spec.arm().joints
