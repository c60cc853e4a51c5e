"""Fair scheduling and worker priority on a real `dexlab serve`, embedded and Celery over
Redis, with two worker processes and with one.

One key queues 20 heavy jobs; another key's small job then finishes within the time
the running heavy job still needs plus 2 s (a first-in first-out queue would make it
wait for all twenty).  Worker processes run at a higher niceness than the API.
"""

from __future__ import annotations

from collections.abc import Iterator
from datetime import datetime
from pathlib import Path

import httpx
import pytest

from tests.integration.servers import Deployment, deployment, wait_for, wait_terminal

pytestmark = pytest.mark.integration

SECRETS = {
    "heavy": "heavy-secret-5b1e7c0d93",
    "light": "light-secret-0a4f6e2c81",
    "root": "root-secret-7c3d9e1f05",
}
API_KEYS = f"heavy:{SECRETS['heavy']},light:{SECRETS['light']},root:{SECRETS['root']}:admin"
MAP_URL = "/v1/processes/planar3r-dexterity-map/execution"
SMALL_URL = "/v1/processes/fourbar-grashof/execution"
SMALL = {"lengths": [2, 7, 9, 6], "ground": 1, "plots": False}


def heavy(tag: int) -> dict[str, object]:
    """A joint-limited map of about 5 s on one core (not cheap: above its sync limit)."""
    return {
        "links": [15, 14, 8 + tag * 1e-6],
        "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
        "grid": {"points_per_axis": 401},
        "orientation_step_deg": 0.5,
        "method": "orientation-sampling",
    }


@pytest.fixture(
    scope="module",
    params=[("embedded", 2), ("embedded", 1), ("celery-redis", 2), ("celery-redis", 1)],
    ids=lambda p: f"{p[0]}-{p[1]}-worker{'s' if p[1] > 1 else ''}",
)
def fair(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[tuple[Deployment, int]]:
    backend, workers = request.param
    env = {"DEXLAB_API_KEYS": API_KEYS}
    with deployment(backend, tmp_path_factory.mktemp("fair"), workers=workers, env=env) as dep:
        yield dep, workers


def as_key(dep: Deployment, name: str) -> httpx.Client:
    headers = {"Authorization": f"Bearer {SECRETS[name]}"}
    return httpx.Client(base_url=dep.base_url, headers=headers, timeout=30.0)


def seconds(stamp: str) -> float:
    return datetime.fromisoformat(stamp.replace("Z", "+00:00")).timestamp()


def test_a_small_job_overtakes_another_keys_queue(fair: tuple[Deployment, int]) -> None:
    dep, workers = fair
    with as_key(dep, "heavy") as owner, as_key(dep, "light") as other:
        queued = []
        for n in range(20):
            r = owner.post(MAP_URL, json={"inputs": heavy(n)})
            assert r.status_code == 201, r.text
            queued.append(r.json()["jobID"])
        try:
            for job_id in queued[:workers]:  # every worker process is busy
                wait_for(owner, job_id, lambda d: d["status"] == "running", timeout=60)
            statuses = {j: owner.get(f"/v1/jobs/{j}").json()["status"] for j in queued}
            running = [j for j, status in statuses.items() if status == "running"]
            assert len(running) == workers, running
            r = other.post(SMALL_URL, json={"inputs": SMALL})
            assert r.status_code == 201, r.text
            small = wait_terminal(other, r.json()["jobID"], timeout=90)
            assert small["status"] == "successful", small
            finishes = [
                seconds(doc["finished"])
                for doc in (owner.get(f"/v1/jobs/{j}").json() for j in running)
                if doc["finished"] is not None
            ]
            assert finishes, "no running heavy job finished before the small one"
            # Within the running heavy job's remaining time, plus 2 s.
            assert seconds(small["finished"]) <= min(finishes) + 2.0, (small, finishes)
            later = [owner.get(f"/v1/jobs/{j}").json() for j in queued[workers:]]
            assert sum(d["status"] != "accepted" for d in later) <= workers, later
        finally:
            for job_id in queued:
                owner.delete(f"/v1/jobs/{job_id}")


def _niceness(pid: int) -> int:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return int(fields[16])  # field 19 of stat(5): nice (fields[0] is field 3, the state)


def test_worker_processes_run_at_a_lower_priority_than_the_api(
    fair: tuple[Deployment, int],
) -> None:
    dep, _ = fair
    with as_key(dep, "root") as root:
        r = root.post(SMALL_URL, json={"inputs": SMALL})
        done = wait_terminal(root, r.json()["jobID"])
        assert done["status"] == "successful", done
        worker_pid = int(done["worker_id"].rsplit(":", 1)[1])
    assert dep.api is not None
    assert _niceness(worker_pid) > _niceness(dep.api.pid)
    assert _niceness(worker_pid) - _niceness(dep.api.pid) == 10  # DEXLAB_WORKER_NICE
    logs = "".join(p.read_text(errors="replace") for p in dep.data_dir.glob("*.log"))
    assert "runs at niceness 10" in logs
