"""A frozen worker process is found and replaced, on every backend: the pool process
running a job and an idle one are SIGSTOPped; both are killed after a lease without
a sign of life, new processes take their places, the frozen job is retried to
success, and the worker then runs two jobs at once again.

(A process busy in code that holds the GIL is not frozen: tests/unit/worker/
test_liveness.py.)"""

from __future__ import annotations

import os
import signal
from contextlib import suppress
from datetime import datetime
from pathlib import Path
from typing import Any

import pytest

from tests.integration.servers import BACKENDS, Deployment, deployment, wait_for, wait_terminal
from tests.integration.test_faults import DeathWatch, freeze, full_log, poll
from tests.integration.test_server import MAP_URL, PAPER_LIMITS, alive, pid_of

pytestmark = pytest.mark.integration

#: A short lease: a process silent this long is frozen (the threshold is a lease).
LEASE_S = 2.0


def map_of(points_per_axis: int, tag: int) -> dict[str, Any]:
    """A joint-limited map without plots (401 points: about 1.5 s; 301: 0.7 s)."""
    return {
        "links": [15, 14, 8 + tag * 1e-6],
        "joint_limits_deg": PAPER_LIMITS,
        "grid": {"points_per_axis": points_per_axis},
        "orientation_step_deg": 1,
        "method": "orientation-sampling",
        "plots": False,
    }


def pool_pids(dep: Deployment) -> set[int]:
    """The live pool processes: the Celery worker's prefork children, or the API's
    spawned local pool (not multiprocessing's resource tracker)."""
    parent = dep.workers[0].pid if dep.workers else dep.api.pid  # type: ignore[union-attr]
    pids = set()
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            cmdline = (entry / "cmdline").read_bytes()
        except (FileNotFoundError, ProcessLookupError, IndexError):
            continue
        state, ppid = fields[0], int(fields[1])
        if ppid == parent and state != "Z" and (dep.workers or b"spawn_main" in cmdline):
            pids.add(int(entry.name))
    return pids


def at(doc: dict[str, Any], key: str) -> datetime:
    """A job's ``started`` or ``finished`` time."""
    return datetime.fromisoformat(doc[key])


@pytest.mark.parametrize("backend", BACKENDS)
def test_frozen_pool_processes_are_replaced_and_the_job_retried(
    backend: str, tmp_path: Path
) -> None:
    env = {"DEXLAB_LEASE_SECONDS": str(LEASE_S), "DEXLAB_HEARTBEAT_SECONDS": "0.5"}
    with deployment(backend, tmp_path, workers=2, env=env) as dep:
        client = dep.client
        first = poll(lambda: len(p := pool_pids(dep)) == 2 and p, 30, "two pool processes")
        job_id = client.post(MAP_URL, json={"inputs": map_of(401, 0)}).json()["jobID"]
        busy = pid_of(wait_for(client, job_id, lambda d: d["status"] == "running", 30))
        frozen = [busy, *(first - {busy})]
        for pid in frozen:
            freeze(pid)
        deaths = [DeathWatch(pid) for pid in frozen]
        try:
            assert client.get(f"/v1/jobs/{job_id}").json()["status"] == "running"
            poll(lambda: not any(alive(pid) for pid in frozen), LEASE_S + 6, "frozen ones killed")
            fresh = poll(
                lambda: len(p := pool_pids(dep)) == 2 and not p & set(frozen) and p,
                10,
                "two new pool processes",
            )
        finally:
            for death in deaths:
                death.stop()
            for pid in frozen:
                with suppress(ProcessLookupError):
                    os.kill(pid, signal.SIGCONT)
        for death in deaths:  # after a lease without a sign of life, not before
            assert death.after_s is not None and death.after_s > LEASE_S - 0.5, death.after_s
        retried = wait_terminal(client, job_id, timeout=30)
        assert retried["status"] == "successful" and retried["attempts"] == 2, retried
        assert pid_of(retried) in fresh, (retried, fresh)
        assert full_log(dep).count("showed no sign of life") == 2, dep.log()

        # Full capacity again: two jobs run at once, one on each new process.  (A pair
        # may miss each other once on a loaded machine, a process slowed as the other
        # ends its job; a second pair must then overlap.)
        pairs = []
        for attempt in range(2):
            pair = [
                client.post(MAP_URL, json={"inputs": map_of(401, 2 * attempt + n)}).json()["jobID"]
                for n in (1, 2)
            ]
            one, two = (wait_terminal(client, i, timeout=30) for i in pair)
            assert one["status"] == two["status"] == "successful", (one, two)
            assert {pid_of(one), pid_of(two)} == fresh, (one, two, fresh)
            pairs.append((one, two))
            overlap_start = max(at(one, "started"), at(two, "started"))
            overlap_end = min(at(one, "finished"), at(two, "finished"))
            if overlap_start < overlap_end:
                break
        else:
            pytest.fail(f"no two jobs ran at once: {pairs}")
        assert pool_pids(dep) == fresh
