"""/metrics and the request ID, over the app's ASGI interface (the embedded store, no
pool); the job collector over a real SQLite store.  The counters moving as a real
server runs jobs on both backends: tests/integration/test_operations.py."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

import httpx
import pytest
from prometheus_client import CollectorRegistry, generate_latest
from prometheus_client.parser import text_string_to_metric_families
from prometheus_client.samples import Sample
from starlette.datastructures import Headers

from service.app import create_app
from service.config import Settings
from service.metrics.job_collector import JobStoreCollector
from service.request_id import request_id_for
from worker.errors import StoreUnavailable
from worker.store import open_store
from worker.store.base import JobStore, NewJob

pytestmark = pytest.mark.anyio


def samples(text: str) -> list[Sample]:
    return [s for family in text_string_to_metric_families(text) for s in family.samples]


def value(found: Iterable[Sample], name: str, **labels: str) -> float:
    matching = [s.value for s in found if s.name == name and s.labels == labels]
    assert len(matching) == 1, (name, labels, matching)
    return matching[0]


async def test_metrics_label_requests_by_route_template_never_the_raw_path(
    client: httpx.AsyncClient,
) -> None:
    assert (await client.get("/v1/jobs/no-such-job")).status_code == 404
    assert (await client.options("/v1/jobs/another-job")).status_code == 204
    assert (await client.get("/no/such/page")).status_code == 404
    assert (await client.request("BREW", "/health/live")).status_code == 405
    r = await client.get("/metrics")
    assert r.status_code == 200
    assert r.headers["content-type"] == "text/plain; version=0.0.4; charset=utf-8"
    found = samples(r.text)
    count = "dexlab_http_request_duration_seconds_count"
    assert value(found, count, route="/v1/jobs/{job_id}", method="GET", status="404") == 1
    assert value(found, count, route="/v1/jobs/{job_id}", method="OPTIONS", status="204") == 1
    assert value(found, count, route="unmatched", method="GET", status="404") == 1
    assert value(found, count, route="/health/live", method="other", status="405") == 1
    routes = {s.labels["route"] for s in found if "route" in s.labels}
    assert not any("no-such-job" in route or "another-job" in route for route in routes)
    assert value(found, "dexlab_store_up") == 1
    assert value(found, "dexlab_workers_live") == 0
    assert value(found, "dexlab_jobs_submitted_total", process="fourbar-grashof") == 0


async def test_metrics_are_documented_as_the_text_format(client: httpx.AsyncClient) -> None:
    operation = (await client.get("/openapi.json")).json()["paths"]["/metrics"]["get"]
    assert "text/plain; version=0.0.4; charset=utf-8" in operation["responses"]["200"]["content"]


async def test_metrics_off_means_no_route(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DEXLAB_METRICS", "0")
    app = create_app(Settings(data_dir=tmp_path, workers=0))
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://dexlab.test") as c:
            r = await c.get("/metrics")
            assert r.status_code == 404
            assert r.headers["content-type"] == "application/problem+json"
            assert "/metrics" not in (await c.get("/openapi.json")).json()["paths"]
            assert "x-request-id" in (await c.get("/health/live")).headers


async def test_a_request_id_is_echoed_or_made(client: httpx.AsyncClient) -> None:
    given = await client.get("/health/live", headers={"X-Request-ID": "trace-42:a/b"})
    assert given.headers["x-request-id"] == "trace-42:a/b"
    made = (await client.get("/health/live")).headers["x-request-id"]
    assert len(made) == 32 and int(made, 16) >= 0
    replaced = await client.get("/nope", headers={"X-Request-ID": "two words"})
    assert replaced.status_code == 404
    assert replaced.headers["x-request-id"] != "two words"


@pytest.mark.parametrize(
    ("given", "kept"),
    [("abc-123", True), ("a" * 128, True), ("a" * 129, False), ("x\ny", False),
     ("", False), ("-leading", False), ("é", False)],
)  # fmt: skip
def test_which_request_ids_are_kept(given: str, kept: bool) -> None:
    chosen = request_id_for(Headers({"x-request-id": given}))
    assert (chosen == given) is kept


def jobs_in(store: JobStore) -> None:
    """Two jobs of ``p`` (one successful, one failed) and one of ``q`` waiting."""
    for process_id in ("p", "p", "q"):
        store.create_job(NewJob(process_id, {}, time_limit_s=60, max_attempts=1))
    for outcome in ("ok", "fail"):
        claim = store.claim_next("w", 10)
        assert claim is not None
        if outcome == "ok":
            assert store.complete(claim.job.job_id, claim.lease_token, {}, [])
        else:
            error = {"type": "job-error", "title": "Job error", "detail": "boom"}
            assert store.fail(claim.job.job_id, claim.lease_token, error)
    store.register_worker("host:1", "host", 1)


def scrape(collector: Any) -> list[Sample]:
    registry = CollectorRegistry()
    registry.register(collector)
    return samples(generate_latest(registry).decode())


def test_the_collector_reads_counts_histograms_and_the_queue(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'jobs.db'}")
    jobs_in(store)
    found = scrape(JobStoreCollector(store, ["p", "q", "r"], live_within_s=60))
    assert value(found, "dexlab_jobs_submitted_total", process="p") == 2
    assert value(found, "dexlab_jobs_submitted_total", process="r") == 0
    assert value(found, "dexlab_job_attempts_total", process="p") == 2
    assert value(found, "dexlab_job_retries_total", process="p") == 0
    assert value(found, "dexlab_jobs_finished_total", process="p", status="successful") == 1
    assert value(found, "dexlab_jobs_finished_total", process="p", status="failed") == 1
    assert value(found, "dexlab_jobs_finished_total", process="q", status="dismissed") == 0
    assert value(found, "dexlab_queue_depth", process="q", status="accepted") == 1
    assert value(found, "dexlab_queue_depth", process="p", status="running") == 0
    assert value(found, "dexlab_workers_live") == 1
    for name in ("dexlab_job_duration_seconds", "dexlab_job_queue_wait_seconds"):
        buckets = [s for s in found if s.name == f"{name}_bucket" and s.labels["process"] == "p"]
        counts = [s.value for s in buckets]
        assert counts == sorted(counts)  # cumulative
        assert buckets[-1].labels["le"] == "+Inf"
        assert counts[-1] == value(found, f"{name}_count", process="p") == 2
        assert value(found, f"{name}_sum", process="p") >= 0
    store.close()


class DownStore:
    """A store that does not answer."""

    def __getattr__(self, name: str) -> Any:
        def unavailable(*args: Any, **kwargs: Any) -> Any:
            raise StoreUnavailable("the store is down")

        return unavailable


def test_a_store_that_does_not_answer_is_a_zero_not_an_error() -> None:
    found = scrape(JobStoreCollector(DownStore(), ["p"], live_within_s=60))  # type: ignore[arg-type]
    assert value(found, "dexlab_store_up") == 0
    assert not [s for s in found if s.name.startswith("dexlab_jobs_")]
