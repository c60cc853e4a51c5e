"""Jobs start at once on the embedded default: an idle pool process is woken by a hint
on its pool's wake-up socket, not found by polling (worker.dispatch.wake_ups).

Every deployment here polls only every 30 s (``DEXLAB_POLL_SECONDS``), so a job that
starts sooner was started by a wake-up: from the API (its pool in the API's process,
or two `dexlab worker` pools of their own), from the process that split a study into
chunks, from the one that ended a study's last chunk, and from a supervisor whose
process died holding a job.  A lost wake-up still costs no more than the poll interval.
"""

from __future__ import annotations

import os
import signal
import statistics
import time
from datetime import datetime
from pathlib import Path
from typing import Any

import pytest

from tests.integration.servers import deployment, wait_for, wait_terminal
from tests.integration.test_design_study import STUDY
from tests.integration.test_server import MAP_URL, long_job, pid_of, running_with_progress
from worker.dispatch.wake_ups import wake_up_dir

pytestmark = [pytest.mark.integration, pytest.mark.slow]

FOURBAR_URL = "/v1/processes/fourbar-grashof/execution"
STUDY_URL = "/v1/processes/design-study/execution"
#: Longer than any test here waits for a job: only a wake-up starts one in time.
LONG_POLL = {"DEXLAB_POLL_SECONDS": "30"}
#: 20 designs of about 0.25 s each, in 10 chunks.
SLOW_STUDY: dict[str, Any] = {
    **STUDY,
    "fixed": {**STUDY["fixed"], "grid": {"points_per_axis": 121},
              "method": "orientation-sampling", "orientation_step_deg": 2},
    "chunk_size": 2,
}  # fmt: skip


def seconds(ts: str) -> float:
    return datetime.fromisoformat(ts.replace("Z", "+00:00")).timestamp()


def trivial(n: int) -> dict[str, Any]:
    return {"inputs": {"lengths": [2, 3, 4, 5 + n * 1e-9], "ground": 0, "plots": False}}


def start_delays(client: Any, jobs: int, limit_s: float) -> list[float]:
    """Submit ``jobs`` trivial jobs one at a time, each after the last ended (the
    workers idle); each one's seconds from creation to start, each under ``limit_s``."""
    delays = []
    for n in range(jobs):
        job_id = client.post(FOURBAR_URL, json=trivial(n)).json()["jobID"]
        done = wait_terminal(client, job_id, timeout=limit_s + 30)
        assert done["status"] == "successful", done
        delays.append(seconds(done["started"]) - seconds(done["created"]))
        assert delays[-1] < limit_s, delays
    return delays


@pytest.mark.parametrize(
    "pools",
    [{"workers": 2}, {"worker_processes": 2}],
    ids=["pool-in-the-api", "two-dexlab-workers"],
)
def test_a_submitted_job_starts_at_once_on_an_idle_pool(
    pools: dict[str, int], tmp_path: Path
) -> None:
    with deployment("embedded", tmp_path, env=LONG_POLL, **pools) as dep:
        time.sleep(1.0)  # every process asleep after its first claim found nothing
        delays = start_delays(dep.client, 12, limit_s=1.0)
        assert statistics.median(delays) <= 0.1, delays


def test_a_studys_chunks_wake_every_idle_process_and_its_end_wakes_the_assembly(
    tmp_path: Path,
) -> None:
    with deployment("embedded", tmp_path, workers=3, env=LONG_POLL) as dep:
        client = dep.client
        time.sleep(1.0)
        study_id = client.post(STUDY_URL, json={"inputs": SLOW_STUDY}).json()["jobID"]
        done = wait_terminal(client, study_id, timeout=25)  # < one poll interval
        assert done["status"] == "successful", (done, dep.log())
        chunks = client.get("/v1/jobs", params={"parent": study_id, "limit": 100}).json()["jobs"]
        assert len(chunks) == 10 and {c["status"] for c in chunks} == {"successful"}
        queued = min(seconds(c["created"]) for c in chunks)
        first_starts: dict[str, float] = {}
        for chunk in sorted(chunks, key=lambda c: seconds(c["started"])):
            first_starts.setdefault(chunk["worker_id"], seconds(chunk["started"]) - queued)
        # The splitting process takes a chunk and wakes one idle process, which passes
        # the rest of the hint on to the third.
        assert len(first_starts) == 3, first_starts
        assert max(first_starts.values()) < 1.0, first_starts
        last_chunk_end = max(seconds(c["finished"]) for c in chunks)
        assert seconds(done["finished"]) - last_chunk_end < 3.0, (done, last_chunk_end)


def test_the_job_of_a_killed_process_is_retried_at_once_by_an_idle_one(tmp_path: Path) -> None:
    """The supervisor requeues the dead process's job and wakes the idle process,
    which takes it before the dead one's replacement has even started."""
    with deployment("embedded", tmp_path, workers=2, env=LONG_POLL) as dep:
        client = dep.client
        job_id = client.post(MAP_URL, json={"inputs": long_job(3)}).json()["jobID"]
        victim = pid_of(wait_for(client, job_id, running_with_progress(2), timeout=60))
        quick = client.post(FOURBAR_URL, json=trivial(0)).json()["jobID"]
        idle = pid_of(wait_terminal(client, quick, timeout=10))
        assert idle != victim
        time.sleep(0.5)  # asleep again
        os.kill(victim, signal.SIGKILL)
        retried = wait_for(
            client, job_id, lambda d: d["attempts"] == 2 and d["status"] == "running", timeout=20
        )
        assert pid_of(retried) == idle, retried
        client.delete(f"/v1/jobs/{job_id}")


def test_a_lost_wake_up_costs_a_poll_interval_at_most(tmp_path: Path) -> None:
    """The pool's socket is removed (the hints go nowhere): jobs start at the next
    poll, as before there were wake-ups."""
    poll_s = 1.5
    env = {"DEXLAB_POLL_SECONDS": str(poll_s)}
    with deployment("embedded", tmp_path, workers=1, env=env) as dep:
        directory = wake_up_dir(f"sqlite:///{tmp_path / 'jobs.db'}")
        assert directory is not None
        sockets = list(directory.glob("*.sock"))
        assert len(sockets) == 1, sockets  # the pool's
        sockets[0].unlink()
        time.sleep(0.5)
        delays = start_delays(dep.client, 4, limit_s=poll_s + 1.0)
        assert max(delays) > 0.1, delays  # found by a poll, not woken
