"""A real `dexlab serve` subprocess with its pool: the user's path, and its faults.

Fault tests kill the real process running the current attempt, mid-progress, and
assert what the next attempt does.
"""

from __future__ import annotations

import os
import signal
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.integration.servers import (
    Server,
    dexlab_command,
    start_server,
    stop_server,
    wait_for,
    wait_terminal,
)

pytestmark = pytest.mark.integration

MAP_URL = "/v1/processes/planar3r-dexterity-map/execution"
PAPER_LIMITS = [[-150, 150], [-150, 150], [-175, 175]]


def long_job(tag: int = 0) -> dict[str, Any]:
    """A joint-limited map that runs for several seconds with steady progress."""
    return {
        "links": [15, 14, 8 + tag * 1e-6],
        "joint_limits_deg": PAPER_LIMITS,
        "grid": {"points_per_axis": 401},
        "orientation_step_deg": 0.5,
    }


def pid_of(status: dict[str, Any]) -> int:
    return int(status["worker_id"].rsplit(":", 1)[1])


def alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    # A zombie awaiting its parent's wait() is gone for our purposes.
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().split(")")[-1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def wait_dead(pid: int, timeout: float = 15) -> None:
    deadline = time.monotonic() + timeout
    while alive(pid):
        assert time.monotonic() < deadline, f"process {pid} is still alive"
        time.sleep(0.05)


def running_with_progress(minimum: float) -> Any:
    return lambda d: d["status"] == "running" and d["progress"] >= minimum


def test_paper_example_runs_to_success_with_downloadable_plots(server: Server) -> None:
    client = server.client
    example = client.get("/v1/processes/planar3r-synthesis").json()["examples"][0]
    r = client.post("/v1/processes/planar3r-synthesis/execution",
                    json={"inputs": example["inputs"]})
    assert r.status_code == 201, r.text
    status = wait_terminal(client, r.json()["jobID"])
    assert status["status"] == "successful", status
    results = client.get(f"{r.headers['Location']}/results").json()
    pngs = [a for a in results["artifacts"] if a["media_type"] == "image/png"]
    assert pngs
    for artifact in pngs:
        body = client.get(artifact["href"])
        assert body.status_code == 200 and body.content.startswith(b"\x89PNG")


def test_worker_killed_mid_job_is_retried_and_succeeds(server: Server) -> None:
    client = server.client
    job_id = client.post(MAP_URL, json={"inputs": long_job(1)}).json()["jobID"]
    first = wait_for(client, job_id, running_with_progress(10))
    assert first["attempts"] == 1
    victim = pid_of(first)
    os.kill(victim, signal.SIGKILL)
    wait_dead(victim)
    final = wait_terminal(client, job_id, timeout=300)
    assert final["status"] == "successful", (final, server.log()[-3000:])
    assert final["attempts"] == 2
    assert pid_of(final) != victim
    results = client.get(f"/v1/jobs/{job_id}/results").json()
    assert results["result"]["method"] == "orientation-sampling"
    names = [a["name"] for a in results["artifacts"]]
    assert len(names) == len(set(names))  # one stored result, no duplicated artifacts


def test_dismissing_a_running_job_stops_its_process(server: Server) -> None:
    client = server.client
    job_id = client.post(MAP_URL, json={"inputs": long_job(2)}).json()["jobID"]
    running = wait_for(client, job_id, running_with_progress(5))
    victim = pid_of(running)
    r = client.delete(f"/v1/jobs/{job_id}")
    assert r.status_code == 200 and r.json()["status"] == "dismissed"
    wait_dead(victim)
    time.sleep(1.0)
    after = client.get(f"/v1/jobs/{job_id}").json()
    assert after["status"] == "dismissed" and after["attempts"] == 1
    gone = client.get(f"/v1/jobs/{job_id}/results")
    assert gone.status_code == 410
    # The pool replaced the stopped process and still serves jobs.
    small = client.post(MAP_URL, json={"inputs": {"links": [3, 2, 1],
                                                  "grid": {"points_per_axis": 11}}})
    assert wait_terminal(client, small.json()["jobID"])["status"] == "successful"


@pytest.fixture(scope="module")
def strict_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    """A server whose jobs get a 2 s time limit and at most 2 attempts."""
    srv = start_server(
        tmp_path_factory.mktemp("dexlab-strict"),
        workers=1,
        env={"DEXLAB_MAX_TIME_LIMIT_S": "2", "DEXLAB_MAX_ATTEMPTS": "2"},
    )
    yield srv
    stop_server(srv)


def test_job_over_its_time_limit_fails_with_reason(strict_server: Server) -> None:
    client = strict_server.client
    job_id = client.post(MAP_URL, json={"inputs": long_job(3)}).json()["jobID"]
    final = wait_terminal(client, job_id, timeout=60)
    assert final["status"] == "failed", final
    assert final["error"]["type"] == "time-limit-exceeded"
    assert "time limit of 2 s" in final["error"]["detail"]
    r = client.get(f"/v1/jobs/{job_id}/results")
    assert r.status_code == 500
    assert r.headers["content-type"] == "application/problem+json"
    assert r.json()["type"].endswith("/time-limit-exceeded")


def test_job_whose_worker_keeps_dying_fails_after_bounded_attempts(strict_server: Server) -> None:
    client = strict_server.client
    small_but_slow = {"links": [15, 14, 8], "joint_limits_deg": PAPER_LIMITS,
                      "grid": {"points_per_axis": 301}, "orientation_step_deg": 1}
    job_id = client.post(MAP_URL, json={"inputs": small_but_slow}).json()["jobID"]
    for attempt in (1, 2):
        status = wait_for(client, job_id,
                          lambda d, a=attempt: d["status"] == "running" and d["attempts"] == a)
        victim = pid_of(status)
        os.kill(victim, signal.SIGKILL)
        wait_dead(victim)
    final = wait_terminal(client, job_id, timeout=60)
    assert final["status"] == "failed", final
    assert final["error"]["type"] == "worker-lost"
    assert "2 allowed" in final["error"]["detail"]


def test_jobs_survive_a_server_restart(tmp_path: Path) -> None:
    """A job committed before 201 is still there (and runs) after the service restarts."""
    first = start_server(tmp_path, workers=0)
    try:
        r = first.client.post(MAP_URL, json={"inputs": {"links": [3, 2, 1],
                                                         "grid": {"points_per_axis": 11}}})
        assert r.status_code == 201
        job_id = r.json()["jobID"]
    finally:
        first.process.send_signal(signal.SIGKILL)
        first.process.wait(timeout=10)
        first.client.close()
    second = start_server(tmp_path, workers=1)
    try:
        assert wait_terminal(second.client, job_id)["status"] == "successful"
    finally:
        stop_server(second)


def test_separate_dexlab_worker_runs_jobs_for_an_api_only_server(tmp_path: Path) -> None:
    """`dexlab serve --workers 0` plus `dexlab worker` on the same store."""
    api = start_server(tmp_path, workers=0)
    log = (tmp_path / "worker.log").open("wb")
    worker = subprocess.Popen(
        [*dexlab_command(), "worker", "--data-dir", str(tmp_path), "--workers", "1"],
        stdout=log, stderr=subprocess.STDOUT, start_new_session=True,
        env={**os.environ, "DEXLAB_HEARTBEAT_SECONDS": "0.5"},
    )
    try:
        deadline = time.monotonic() + 60
        while api.client.get("/health/ready").status_code != 200:
            assert time.monotonic() < deadline, "the API never saw the worker"
            time.sleep(0.2)
        r = api.client.post(MAP_URL, json={"inputs": {"links": [3, 2, 1],
                                                       "grid": {"points_per_axis": 11}}})
        assert wait_terminal(api.client, r.json()["jobID"])["status"] == "successful"
    finally:
        worker.send_signal(signal.SIGTERM)
        try:
            worker.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(worker.pid, signal.SIGKILL)
        log.close()
        stop_server(api)
