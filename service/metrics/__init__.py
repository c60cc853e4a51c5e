"""Prometheus metrics at ``/metrics`` (``DEXLAB_METRICS=0``: off).

Every family is named ``dexlab_...``.  The app owns its registry (never the
process-global one): HTTP latency is observed by this API process
(:mod:`service.metrics.http_latency`); the job figures are read from the store at each
scrape by a collector the app's lifespan registers
(:mod:`service.metrics.job_collector`), so they count jobs run by any process or
machine.
"""

from __future__ import annotations

from service.metrics.exporter import Metrics, install_metrics
from service.metrics.settings import MetricsSettings

__all__ = ["Metrics", "MetricsSettings", "install_metrics"]
