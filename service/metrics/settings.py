"""Whether the service exports metrics (environment ``DEXLAB_METRICS``)."""

from __future__ import annotations

from pydantic import Field
from pydantic_settings import BaseSettings, SettingsConfigDict

__all__ = ["MetricsSettings"]


class MetricsSettings(BaseSettings):
    """``DEXLAB_METRICS=0`` turns ``/metrics`` off (it answers 404)."""

    model_config = SettingsConfigDict(env_prefix="DEXLAB_", extra="ignore", frozen=True)

    metrics: bool = Field(
        True, description="Serve Prometheus metrics at /metrics (0: off, the route is gone)."
    )
