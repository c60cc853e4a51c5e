"""Work limits of the serial-arm jobs, checked before a job is queued.

``serial-indices`` costs configurations x joints (a forward pass, a Jacobian and an SVD
each, about a microsecond a joint).
"""

from __future__ import annotations

from worker.families.serial.specs import MAX_CONFIGURATIONS, SerialIndicesSpec

__all__ = ["INDICES_COST_LIMIT", "INDICES_SYNC_COST_LIMIT", "TIME_LIMIT_S", "indices_cost"]

INDICES_COST_LIMIT = MAX_CONFIGURATIONS * 12
#: Up to this cost (a thousand configurations of a 12-joint arm) answered synchronously.
INDICES_SYNC_COST_LIMIT = 12_000
TIME_LIMIT_S = 300.0


def indices_cost(spec: SerialIndicesSpec) -> int:
    """Configurations x joints."""
    return len(spec.configurations) * len(spec.configurations[0])
