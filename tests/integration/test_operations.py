"""Operations on a real deployment, embedded and Celery over Redis: `/metrics` counts
the jobs whoever runs them (the Celery workers are other processes, reading and writing
the same store), and every log line of the API, the pool and the workers is one JSON
object carrying its request or job ID."""

from __future__ import annotations

import json
import time
import uuid
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from prometheus_client.parser import text_string_to_metric_families
from prometheus_client.samples import Sample

from tests.integration.servers import Deployment, deployment, wait_terminal

pytestmark = pytest.mark.integration

PROCESS = "planar3r-dexterity-map"
MAP_URL = f"/v1/processes/{PROCESS}/execution"
#: A job that finishes well within the deployment's time limit (~2 s with its plots),
#: and one that would take several times the limit.
QUICK = {"links": [3, 2, 1], "grid": {"points_per_axis": 11}}
SLOW = {"links": [15, 14, 8], "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
        "grid": {"points_per_axis": 801}, "orientation_step_deg": 0.5,
        "method": "orientation-sampling"}  # fmt: skip
TIME_LIMIT_S = "6"
LINE_FIELDS = {"time", "level", "logger", "message", "process"}


@pytest.fixture(scope="module", params=["embedded", "celery-redis"])
def ops_server(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Deployment]:
    """One worker process, JSON logs, and a time limit the slow job exceeds."""
    env = {"DEXLAB_LOG_FORMAT": "json", "DEXLAB_MAX_TIME_LIMIT_S": TIME_LIMIT_S}
    with deployment(str(request.param), tmp_path_factory.mktemp("ops"), workers=1,
                    env=env) as dep:  # fmt: skip
        yield dep


def scrape(client: httpx.Client) -> list[Sample]:
    r = client.get("/metrics")
    assert r.status_code == 200
    assert r.headers["content-type"] == "text/plain; version=0.0.4; charset=utf-8"
    return [s for family in text_string_to_metric_families(r.text) for s in family.samples]


def value(found: Iterable[Sample], name: str, **labels: str) -> float:
    matching = [s.value for s in found if s.name == name and s.labels == labels]
    assert len(matching) == 1, (name, labels, matching)
    return matching[0]


def submit(client: httpx.Client, inputs: dict[str, Any], **headers: str) -> httpx.Response:
    r = client.post(MAP_URL, json={"inputs": inputs}, headers=headers)
    assert r.status_code == 201, r.text
    return r


def check_histograms(found: list[Sample]) -> None:
    """Every histogram series: buckets cumulative, ``+Inf`` equal to ``_count``."""
    series: dict[tuple[str, tuple[tuple[str, str], ...]], list[Sample]] = {}
    for s in found:
        if s.name.endswith("_bucket"):
            labels = tuple(sorted((k, v) for k, v in s.labels.items() if k != "le"))
            series.setdefault((s.name.removesuffix("_bucket"), labels), []).append(s)
    assert any(name == "dexlab_job_duration_seconds" for name, _ in series)
    for (name, labels), buckets in series.items():
        bounds = [float(b.labels["le"]) for b in buckets]
        counts = [b.value for b in buckets]
        assert bounds == sorted(bounds) and bounds[-1] == float("inf"), name
        assert counts == sorted(counts), (name, labels, counts)
        assert counts[-1] == value(found, f"{name}_count", **dict(labels)), name


def test_job_counters_move_as_jobs_run(ops_server: Deployment) -> None:
    client = ops_server.client
    before = scrape(client)
    failing = submit(client, SLOW).json()["jobID"]
    quick = submit(client, QUICK).json()["jobID"]
    waiting = submit(client, {**QUICK, "links": [3, 2, 1.5]}).json()["jobID"]
    assert client.delete(f"/v1/jobs/{waiting}").status_code == 200  # the one worker is busy
    assert wait_terminal(client, failing, timeout=60)["status"] == "failed"
    assert wait_terminal(client, quick, timeout=60)["status"] == "successful"
    after = scrape(client)

    def moved(name: str, **labels: str) -> float:
        return value(after, name, **labels) - value(before, name, **labels)

    assert moved("dexlab_jobs_submitted_total", process=PROCESS) == 3
    for status in ("successful", "failed", "dismissed"):
        assert moved("dexlab_jobs_finished_total", process=PROCESS, status=status) == 1, status
    assert moved("dexlab_job_attempts_total", process=PROCESS) >= 2
    assert moved("dexlab_job_duration_seconds_count", process=PROCESS) == 2
    assert moved("dexlab_job_duration_seconds_sum", process=PROCESS) >= float(TIME_LIMIT_S)
    assert moved("dexlab_job_queue_wait_seconds_count", process=PROCESS) >= 2
    for status in ("accepted", "running"):
        assert value(after, "dexlab_queue_depth", process=PROCESS, status=status) == 0
    # The time limit stopped a pool process and a new one took its place: it counts as
    # live from its first heartbeat, which may follow the scrape above by a moment.
    deadline = time.monotonic() + 15.0
    while value(after, "dexlab_workers_live") < 1 and time.monotonic() < deadline:
        time.sleep(0.25)
        after = scrape(client)
    assert value(after, "dexlab_workers_live") >= 1
    assert value(after, "dexlab_store_up") == 1
    check_histograms(after)
    latency = "dexlab_http_request_duration_seconds_count"
    assert value(after, latency, route="/v1/jobs/{job_id}", method="GET", status="200") >= 2
    assert value(after, latency, route=MAP_URL, method="POST", status="201") >= 3
    routes = {s.labels["route"] for s in after if "route" in s.labels}
    assert not any(job in route for route in routes for job in (failing, quick, waiting))


def log_lines(dep: Deployment) -> dict[str, list[dict[str, Any]]]:
    """Each log file's lines, every one parsed as JSON (a line that is not fails)."""
    parsed: dict[str, list[dict[str, Any]]] = {}
    for path in sorted(dep.data_dir.glob("*.log")):
        lines = []
        for number, text in enumerate(path.read_text().splitlines(), start=1):
            try:
                line = json.loads(text)
            except json.JSONDecodeError:
                pytest.fail(f"{path.name}:{number} is not a JSON line: {text!r}")
            assert isinstance(line, dict), (path.name, line)
            assert line.keys() >= LINE_FIELDS, (path.name, line)
            lines.append(line)
        parsed[path.name] = lines
    return parsed


def wait_for_lines(dep: Deployment, found: Any, timeout: float = 15) -> dict[str, Any]:
    """The parsed logs once ``found(logs)`` holds (a line may lag the status)."""
    deadline = time.monotonic() + timeout
    while True:
        logs = log_lines(dep)
        if found(logs) or time.monotonic() > deadline:
            return logs
        time.sleep(0.2)


def test_every_log_line_is_json_and_carries_its_request_or_job(ops_server: Deployment) -> None:
    client = ops_server.client
    request_id = f"ops-{uuid.uuid4().hex[:12]}"
    r = submit(client, {**QUICK, "links": [3, 2, 1.25]}, **{"X-Request-ID": request_id})
    assert r.headers["X-Request-ID"] == request_id
    generated = client.get("/health/live").headers["X-Request-ID"]
    job_id = r.json()["jobID"]
    assert wait_terminal(client, job_id, timeout=60)["status"] == "successful"

    def job_seen(logs: dict[str, Any]) -> bool:
        return any(line.get("job_id") == job_id for lines in logs.values() for line in lines)

    logs = wait_for_lines(ops_server, job_seen)
    every = [line for lines in logs.values() for line in lines]
    access = [line for line in logs["api.log"] if line["logger"] == "uvicorn.access"]
    assert access and all("request_id" in line for line in access)
    assert any(line["request_id"] == request_id and line["method"] == "POST" for line in access)
    assert any(line["request_id"] == generated for line in access)
    # Every line that names the job carries its ID (a request for it: the request's).
    naming = [line for line in every if job_id in line["message"]]
    assert naming
    for line in naming:
        assert line.get("job_id") == job_id or "request_id" in line, line
    assert any(line.get("job_id") == job_id and line["logger"] == "dexlab.worker"
               for line in every)  # fmt: skip
    if ops_server.backend != "embedded":
        # Celery's own task lines carry the job their message named.  A delivery claims
        # the next job in fair order, which may be another one (a dismissed job's message
        # can run this job), so the delivery's job ID is the task ID in the line.
        worker_lines = [line for name, lines in logs.items() if name.startswith("worker")
                        for line in lines]  # fmt: skip
        task_lines = [line for line in worker_lines if line["logger"].startswith("celery")
                      and "dexlab.run_job[" in line["message"]]  # fmt: skip
        assert task_lines, worker_lines[-20:]
        for line in task_lines:
            delivered = line["message"].split("dexlab.run_job[", 1)[1].split("]", 1)[0]
            assert line.get("job_id") == delivered, line


def test_a_deployment_without_metrics_answers_404(tmp_path: Path) -> None:
    with deployment("embedded", tmp_path, workers=0, env={"DEXLAB_METRICS": "0"}) as dep:
        r = dep.client.get("/metrics")
        assert r.status_code == 404
        assert r.headers["content-type"] == "application/problem+json"
