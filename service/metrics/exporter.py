"""The app's metrics: its registry, the ``/metrics`` route and the latency middleware."""

from __future__ import annotations

from collections.abc import Iterable

from fastapi import APIRouter, FastAPI, Request, Response
from prometheus_client import CollectorRegistry, generate_latest
from prometheus_client.exposition import CONTENT_TYPE_PLAIN_0_0_4

from service.metrics.http_latency import HttpLatency, http_latency_histogram
from service.metrics.job_collector import JobStoreCollector
from worker.store.base import JobStore

__all__ = ["Metrics", "PrometheusText", "install_metrics"]


class PrometheusText(Response):
    """The Prometheus text exposition format, version 0.0.4."""

    media_type = CONTENT_TYPE_PLAIN_0_0_4


class Metrics:
    """One app's metrics registry; the job figures while the store is open."""

    def __init__(self) -> None:
        self.registry = CollectorRegistry()
        self.http_latency = http_latency_histogram(self.registry)
        self._jobs: JobStoreCollector | None = None

    def watch_store(
        self, store: JobStore, process_ids: Iterable[str], live_within_s: float
    ) -> None:
        """Export ``store``'s job figures (the lifespan calls it once the store is open)."""
        self.unwatch_store()
        self._jobs = JobStoreCollector(store, process_ids, live_within_s)
        self.registry.register(self._jobs)

    def unwatch_store(self) -> None:
        """Stop reading the store (before it closes)."""
        if self._jobs is not None:
            self.registry.unregister(self._jobs)
            self._jobs = None

    def exposition(self) -> bytes:
        """Every family in the text format (this reads the store)."""
        return generate_latest(self.registry)


def _metrics_router() -> APIRouter:
    router = APIRouter(tags=["health"])

    @router.get(
        "/metrics",
        summary="Prometheus metrics",
        response_class=PrometheusText,
        responses={200: {
            "description": "Jobs submitted, finished, attempts and retries, duration and "
            "queue-wait histograms by process, the queue, live workers, HTTP latency by "
            "route (Prometheus text format 0.0.4).",
            "content": {CONTENT_TYPE_PLAIN_0_0_4: {"schema": {"type": "string"}}},
        }},
    )  # fmt: skip
    def metrics(request: Request) -> PrometheusText:
        exporter: Metrics = request.app.state.metrics
        return PrometheusText(exporter.exposition())

    return router


def install_metrics(app: FastAPI) -> Metrics:
    """Add ``/metrics`` and the latency middleware to ``app`` (call it after the other
    middleware, so latency covers them); the lifespan then calls
    :meth:`Metrics.watch_store`."""
    metrics = Metrics()
    app.state.metrics = metrics
    app.add_middleware(HttpLatency, histogram=metrics.http_latency, routes=lambda: app.routes)
    app.include_router(_metrics_router())
    return metrics
