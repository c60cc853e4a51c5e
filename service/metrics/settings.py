"""The metrics section of the settings: whether the service exports metrics
(``DEXLAB_METRICS``)."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field

__all__ = ["MetricsSettings"]


class MetricsSettings(BaseModel):
    """``DEXLAB_METRICS=0`` turns ``/metrics`` off (it answers 404)."""

    model_config = ConfigDict(extra="ignore", frozen=True)

    metrics: bool = Field(
        True, description="Serve Prometheus metrics at /metrics (0: off, the route is gone)."
    )
