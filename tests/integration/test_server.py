"""Real `dexlab serve` / `dexlab worker` processes: the user's path, and its faults.

Fault tests kill the real process running the current attempt, mid-progress, and
assert what the next attempt does.  Each test runs on every backend.
"""

from __future__ import annotations

import os
import signal
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.integration.servers import (
    BACKENDS,
    TERMINAL,
    Deployment,
    deployment,
    kill_group,
    wait_for,
    wait_terminal,
)

pytestmark = pytest.mark.integration

MAP_URL = "/v1/processes/planar3r-dexterity-map/execution"
PAPER_LIMITS = [[-150, 150], [-150, 150], [-175, 175]]
TINY_MAP = {"links": [3, 2, 1], "grid": {"points_per_axis": 11}}
#: The lease in the test deployments (servers.FAST_ENV) and the slack a retry may take.
LEASE_S = 4.0


def long_job(tag: int = 0) -> dict[str, Any]:
    """A joint-limited map that runs for several seconds with steady progress."""
    return {
        "links": [15, 14, 8 + tag * 1e-6],
        "joint_limits_deg": PAPER_LIMITS,
        "grid": {"points_per_axis": 401},
        "orientation_step_deg": 0.5,
        "method": "orientation-sampling",
    }


def pid_of(status: dict[str, Any]) -> int:
    return int(status["worker_id"].rsplit(":", 1)[1])


def alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    try:  # a zombie awaiting its parent's wait() is gone for our purposes
        with open(f"/proc/{pid}/stat") as f:
            return f.read().split(")")[-1].split()[0] != "Z"
    except (FileNotFoundError, ProcessLookupError):  # it exited while we read
        return False


def wait_dead(pid: int, timeout: float = 15) -> None:
    deadline = time.monotonic() + timeout
    while alive(pid):
        assert time.monotonic() < deadline, f"process {pid} is still alive"
        time.sleep(0.05)


def running_with_progress(minimum: float) -> Any:
    return lambda d: d["status"] == "running" and d["progress"] >= minimum


def test_paper_example_runs_to_success_with_downloadable_plots(server: Deployment) -> None:
    client = server.client
    example = client.get("/v1/processes/planar3r-synthesis").json()["examples"][0]
    r = client.post(
        "/v1/processes/planar3r-synthesis/execution", json={"inputs": example["inputs"]}
    )
    assert r.status_code == 201, r.text
    status = wait_terminal(client, r.json()["jobID"])
    assert status["status"] == "successful", status
    results = client.get(f"{r.headers['Location']}/results").json()
    pngs = [a for a in results["artifacts"] if a["media_type"] == "image/png"]
    assert pngs
    for artifact in pngs:
        body = client.get(artifact["href"])
        assert body.status_code == 200 and body.content.startswith(b"\x89PNG")


def test_pool_process_killed_mid_job_is_retried_and_succeeds(server: Deployment) -> None:
    client = server.client
    job_id = client.post(MAP_URL, json={"inputs": long_job(1)}).json()["jobID"]
    first = wait_for(client, job_id, running_with_progress(10))
    assert first["attempts"] == 1
    victim = pid_of(first)
    killed_at = time.monotonic()
    os.kill(victim, signal.SIGKILL)
    wait_dead(victim)
    second = wait_for(client, job_id, lambda d: d["attempts"] == 2 or d["status"] != "running")
    # Retried within the documented bound: the lease, plus a sweep and a poll.
    assert time.monotonic() - killed_at < LEASE_S + 6, second
    final = wait_terminal(client, job_id, timeout=300)
    assert final["status"] == "successful", (final, server.log())
    assert final["attempts"] == 2
    assert pid_of(final) != victim
    results = client.get(f"/v1/jobs/{job_id}/results").json()
    assert results["result"]["method"] == "orientation-sampling"
    names = [a["name"] for a in results["artifacts"]]
    assert len(names) == len(set(names))  # one stored result, no duplicated artifacts


def test_dismissing_a_running_job_stops_its_process(server: Deployment) -> None:
    client = server.client
    job_id = client.post(MAP_URL, json={"inputs": long_job(2)}).json()["jobID"]
    running = wait_for(client, job_id, running_with_progress(5))
    victim = pid_of(running)
    r = client.delete(f"/v1/jobs/{job_id}")
    assert r.status_code == 200 and r.json()["status"] == "dismissed"
    wait_dead(victim)
    time.sleep(LEASE_S + 1.0)  # a redelivery of the job's message must not revive it
    after = client.get(f"/v1/jobs/{job_id}").json()
    assert after["status"] == "dismissed" and after["attempts"] == 1
    gone = client.get(f"/v1/jobs/{job_id}/results")
    assert gone.status_code == 410
    # The stopped process was replaced and the deployment still serves jobs.
    small = client.post(MAP_URL, json={"inputs": TINY_MAP})
    assert wait_terminal(client, small.json()["jobID"])["status"] == "successful"


@pytest.fixture(scope="module", params=BACKENDS)
def strict_server(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Deployment]:
    """A deployment whose jobs get a 2 s time limit and at most 2 attempts."""
    with deployment(
        str(request.param),
        tmp_path_factory.mktemp("dexlab-strict"),
        workers=1,
        env={"DEXLAB_MAX_TIME_LIMIT_S": "2", "DEXLAB_MAX_ATTEMPTS": "2"},
    ) as dep:
        yield dep


def test_job_over_its_time_limit_fails_with_reason(strict_server: Deployment) -> None:
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


def test_job_whose_worker_keeps_dying_fails_after_bounded_attempts(
    strict_server: Deployment,
) -> None:
    client = strict_server.client
    slow = {
        "links": [15, 14, 8],
        "joint_limits_deg": PAPER_LIMITS,
        "grid": {"points_per_axis": 301},
        "orientation_step_deg": 1,
        "method": "orientation-sampling",
    }
    job_id = client.post(MAP_URL, json={"inputs": slow}).json()["jobID"]
    for attempt in (1, 2):
        status = wait_for(
            client, job_id, lambda d, a=attempt: d["status"] == "running" and d["attempts"] == a
        )
        victim = pid_of(status)
        os.kill(victim, signal.SIGKILL)
        wait_dead(victim)
    final = wait_terminal(client, job_id, timeout=60)
    assert final["status"] == "failed", final
    assert final["error"]["type"] == "worker-lost"
    assert "2 allowed" in final["error"]["detail"]


def test_jobs_survive_an_api_restart(backend: str, tmp_path: Path) -> None:
    """A job committed before 201 is still there, and runs, after the API dies."""
    with deployment(backend, tmp_path, workers=0) as dep:
        r = dep.client.post(MAP_URL, json={"inputs": TINY_MAP})
        assert r.status_code == 201
        job_id = r.json()["jobID"]
        dep.kill_api()
        dep.start_api(local_pool=1)
        if backend != "embedded":
            dep.start_worker(1)
        assert wait_terminal(dep.client, job_id)["status"] == "successful"


def test_whole_worker_killed_mid_job_is_retried_by_another(backend: str, tmp_path: Path) -> None:
    """Kill every process of the `dexlab worker` running a job, as when its machine
    dies: the lease runs out and another worker runs the job to success."""
    with deployment(backend, tmp_path, workers=0, worker_processes=2) as dep:
        client = dep.client
        job_id = client.post(MAP_URL, json={"inputs": long_job(4)}).json()["jobID"]
        first = wait_for(client, job_id, running_with_progress(10))
        victim_pid = pid_of(first)
        victim = next(w for w in dep.workers if victim_pid in group_pids(w.pid))
        victim_group = group_pids(victim.pid)
        killed_at = time.monotonic()
        kill_group(victim)
        victim.wait(timeout=10)
        wait_dead(victim_pid)
        second = wait_for(client, job_id, lambda d: d["attempts"] == 2, timeout=60)
        assert time.monotonic() - killed_at < LEASE_S + 8, second
        final = wait_terminal(client, job_id, timeout=300)
        assert final["status"] == "successful", (final, dep.log())
        assert final["attempts"] == 2 and pid_of(final) not in victim_group


def test_two_workers_share_a_batch(backend: str, tmp_path: Path) -> None:
    """Two `dexlab worker`s on one store (and broker): every job runs once, both work."""
    with deployment(backend, tmp_path, workers=0, worker_processes=2) as dep:
        client = dep.client
        slow_tiny = {
            "links": [15, 14, 8],
            "joint_limits_deg": PAPER_LIMITS,
            "grid": {"points_per_axis": 41},
            "orientation_step_deg": 2,
            "method": "orientation-sampling",
        }
        ids = [
            client.post(
                MAP_URL, json={"inputs": {**slow_tiny, "links": [15, 14, 8 + n / 10]}}
            ).json()["jobID"]
            for n in range(8)
        ]
        # Which processes belong to which worker, sampled while the jobs run: a Celery
        # worker may replace a pool child after its job, and a finished child is gone.
        groups: dict[int, set[int]] = {w.pid: set() for w in dep.workers}
        deadline = time.monotonic() + 180
        while True:
            for w in dep.workers:
                groups[w.pid].update(group_pids(w.pid))
            docs = [client.get(f"/v1/jobs/{job_id}").json() for job_id in ids]
            if all(d["status"] in TERMINAL for d in docs) or time.monotonic() > deadline:
                break
            time.sleep(0.1)
        finals = [wait_terminal(client, job_id, timeout=5) for job_id in ids]
        assert all(f["status"] == "successful" and f["attempts"] == 1 for f in finals), finals
        ran_on = {g for f in finals for g, pids in groups.items() if pid_of(f) in pids}
        assert ran_on == set(groups), f"only {ran_on} of {set(groups)} did any work"


def group_pids(session_leader: int) -> list[int]:
    """Every process in the session a worker was started in (the worker's processes)."""
    pids = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except (FileNotFoundError, ProcessLookupError, IndexError):
                continue
            if int(stat[3]) == session_leader:  # field 6 of /proc/PID/stat: session ID
                pids.append(int(entry.name))
    return pids
