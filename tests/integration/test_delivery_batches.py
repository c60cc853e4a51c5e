"""A Celery delivery runs the next jobs too, taking a waiting message off the queue
for each (``DEXLAB_DELIVERY_BATCH_S``): fewer deliveries than jobs, every job run once,
and no message left over; with the setting at 0, one delivery per job."""

from __future__ import annotations

import re
import time
from pathlib import Path

import pytest
from kombu import Connection

from tests.integration.servers import deployment, wait_terminal

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
