"""A Celery delivery runs the next jobs too, taking a waiting message off the queue
for each (``DEXLAB_DELIVERY_BATCH_S``): fewer deliveries than jobs, every job run once,
and no message left over; with the setting at 0, one delivery per job; pool processes
killed in the middle of their batches lose no job."""

from __future__ import annotations

import os
import re
import signal
import time
from pathlib import Path

import pytest
from kombu import Connection

from tests.integration.servers import deployment, wait_terminal
from tests.integration.test_server import alive, pid_of

pytestmark = pytest.mark.integration

URL = "/v1/processes/fourbar-grashof/execution"
JOBS = 40


def _waiting(broker: str, queue: str) -> int:
    with Connection(broker, connect_timeout=5) as conn:
        try:
            _, count, _ = conn.default_channel.queue_declare(queue=queue, passive=True)
        except conn.channel_errors:  # Redis deletes an empty list: no queue, no message
            return 0
        return int(count)


@pytest.mark.parametrize("batch_s", ["0.05", "0"])
@pytest.mark.parametrize("backend", ["celery-redis", "celery-rabbitmq"])
def test_a_delivery_runs_the_next_jobs_each_once_with_a_message_each(
    backend: str, batch_s: str, tmp_path: Path
) -> None:
    with deployment(backend, tmp_path, workers=0, env={"DEXLAB_DELIVERY_BATCH_S": batch_s}) as dep:
        broker, queue = dep.env["DEXLAB_BROKER_URL"], dep.env["DEXLAB_QUEUE"]
        ids = [
            dep.client.post(
                URL,
                json={"inputs": {"lengths": [2, 3, 4, 5 + n / 1e6], "ground": 0, "plots": False}},
            ).json()["jobID"]
            for n in range(JOBS)
        ]
        # A publish is not confirmed: the broker may count the last ones a moment later.
        deadline = time.monotonic() + 10
        while _waiting(broker, queue) < JOBS and time.monotonic() < deadline:
            time.sleep(0.1)
        assert _waiting(broker, queue) == JOBS
        dep.start_worker(1)
        for job_id in ids:
            assert wait_terminal(dep.client, job_id)["status"] == "successful"
        deadline = time.monotonic() + 20  # messages left over are delivered and dropped
        while _waiting(broker, queue) and time.monotonic() < deadline:
            time.sleep(0.2)
        assert _waiting(broker, queue) == 0
        time.sleep(1)  # the last deliveries' lines
        log = (tmp_path / "worker-0.log").read_text(errors="replace")
        runs = re.findall(r"runs job (\S+) \(attempt (\d+)\)", log)
        assert sorted(runs) == sorted((job_id, "1") for job_id in ids)  # each once
        received = len(re.findall(r"dexlab\.run_job\[\S+\] received", log))
        if batch_s == "0":
            assert received == JOBS
        else:
            assert received <= JOBS // 2, received
        assert "re-sending job" not in log + (tmp_path / "api.log").read_text(errors="replace")


def _submit(client: object, count: int) -> list[str]:
    return [
        client.post(  # type: ignore[attr-defined]
            URL, json={"inputs": {"lengths": [2, 3, 4, 5 + n / 1e6], "ground": 0, "plots": False}}
        ).json()["jobID"]
        for n in range(count)
    ]


@pytest.mark.parametrize("backend", ["celery-redis", "celery-rabbitmq"])
def test_pool_processes_killed_in_the_middle_of_their_batches_lose_no_job(
    backend: str, tmp_path: Path
) -> None:
    """Batches of up to 5 s (a whole drain); the process that ran the 60th job, and
    later the one that ran the 300th, is SIGKILLed while it goes on with the next:
    every job still ends successful, a killed attempt is retried once its lease lapses,
    and the queue ends empty."""
    jobs = 600
    with deployment(backend, tmp_path, workers=0, env={"DEXLAB_DELIVERY_BATCH_S": "5"}) as dep:
        broker, queue = dep.env["DEXLAB_BROKER_URL"], dep.env["DEXLAB_QUEUE"]
        ids = _submit(dep.client, jobs)
        dep.start_worker(2)
        killed = []
        for index in (60, 300):
            deadline = time.monotonic() + 60
            while (doc := dep.client.get(f"/v1/jobs/{ids[index]}").json())["status"] != (
                "successful"
            ):
                assert time.monotonic() < deadline, doc
                time.sleep(0.01)
            victim = pid_of(doc)
            if alive(victim):
                os.kill(victim, signal.SIGKILL)
                killed.append(victim)
        assert killed, "the drain ended before a pool process could be killed"
        finals = [wait_terminal(dep.client, job_id, timeout=120) for job_id in ids]
        assert {f["status"] for f in finals} == {"successful"}
        retried = [f["jobID"] for f in finals if f["attempts"] > 1]
        # At most the job each killed process was running, and the one whose outcome it
        # was committing.
        assert len(retried) <= 2 * len(killed), retried
        deadline = time.monotonic() + 30
        while _waiting(broker, queue) and time.monotonic() < deadline:
            time.sleep(0.2)
        assert _waiting(broker, queue) == 0
