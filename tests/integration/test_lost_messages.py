"""Lost broker messages are sent again; a long backlog is not (the Celery backends).

A delivery claims the next job in fair order whichever job its message names, so the
sweeper re-sends only as many overdue jobs as the broker's queue lacks messages for
(worker.dispatch.celery.dispatch.Sweeper._lost).  Here the API runs alone (its sweeper
every 0.5 s, re-sending after 1 s), the queue is read and emptied with kombu, and a
worker drains it at the end.
"""

from __future__ import annotations

import time
from contextlib import ExitStack
from pathlib import Path

import pytest
from kombu import Connection, Queue

from tests.integration.servers import backend_env, deployment, wait_terminal
from worker.dispatch.celery.dispatch import CeleryDispatch
from worker.registry import default_registry
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.store.base import NewJob

pytestmark = pytest.mark.integration

URL = "/v1/processes/fourbar-grashof/execution"
JOBS = 4


def _waiting(broker: str, queue: str) -> int:
    with Connection(broker, connect_timeout=5) as conn:
        _, count, _ = conn.default_channel.queue_declare(queue=queue, passive=True)
        return int(count)


def _resent(log: Path) -> int:
    return log.read_text(errors="replace").count("re-sending job")


@pytest.mark.parametrize("backend", ["celery-redis", "celery-rabbitmq"])
def test_a_backlog_is_not_sent_twice_and_lost_messages_are_sent_again(
    backend: str, tmp_path: Path
) -> None:
    env = {"DEXLAB_REDISPATCH_AFTER_S": "1"}
    with deployment(backend, tmp_path, workers=0, env=env) as dep:
        broker, queue = dep.env["DEXLAB_BROKER_URL"], dep.env["DEXLAB_QUEUE"]
        body = {"inputs": {"lengths": [2, 3, 4, 5], "ground": 0, "plots": False}}
        ids = [dep.client.post(URL, json=body).json()["jobID"] for _ in range(JOBS)]
        # A publish is not confirmed: the broker may count the last ones a moment later.
        deadline = time.monotonic() + 10
        while _waiting(broker, queue) < JOBS and time.monotonic() < deadline:
            time.sleep(0.1)
        assert _waiting(broker, queue) == JOBS
        time.sleep(3)  # six sweeps, every job overdue: the queue holds one for each
        assert _waiting(broker, queue) == JOBS
        assert _resent(tmp_path / "api.log") == 0

        with Connection(broker, connect_timeout=5) as conn:  # the broker loses three
            channel = conn.default_channel
            for _ in range(3):
                assert Queue(queue).bind(channel).get(no_ack=True) is not None
        assert _waiting(broker, queue) == 1
        deadline = time.monotonic() + 20
        while _waiting(broker, queue) < JOBS and time.monotonic() < deadline:
            time.sleep(0.2)
        time.sleep(2)  # more sweeps: nothing more is missing
        assert _waiting(broker, queue) == JOBS
        assert _resent(tmp_path / "api.log") == 3

        dep.start_worker(1)
        for job_id in ids:
            assert wait_terminal(dep.client, job_id)["status"] == "successful"


@pytest.mark.parametrize("backend", ["celery-redis", "celery-rabbitmq"])
def test_the_dispatcher_counts_waiting_messages_on_one_kept_connection(
    backend: str, tmp_path: Path
) -> None:
    with ExitStack() as stack:
        env = backend_env(backend, stack)
        settings = WorkerSettings(
            broker_url=env["DEXLAB_BROKER_URL"],
            queue=env["DEXLAB_QUEUE"],
            store_url=env["DEXLAB_STORE_URL"],
            data_dir=tmp_path,
        )
        store = open_store(settings.resolved_store_url())
        stack.callback(store.close)
        dispatcher = CeleryDispatch(settings, store, default_registry())
        stack.callback(dispatcher.close)
        for _ in range(3):
            job, _ = store.create_job(NewJob("fourbar-grashof", {}, 30, 3))
            dispatcher.dispatch(job.job_id, 30)
        counts = [dispatcher.waiting_messages() for _ in range(5)]
        assert counts == [3] * 5
        kept = dispatcher._kept
        assert kept is not None and dispatcher.waiting_messages() == 3
        assert dispatcher._kept is kept  # one connection, a channel per count
        # A queue the broker does not have: None (the sweeper then re-sends as before),
        # and the next count opens a new connection.
        other = CeleryDispatch(
            settings.model_copy(update={"queue": "dexlab-no-such"}), store, default_registry()
        )
        stack.callback(other.close)
        assert other.waiting_messages() is None and other._kept is None
        assert dispatcher.waiting_messages() == 3
        # Taking a message (a delivery running one more job): one at a time, none left.
        assert [dispatcher.take_waiting_message() for _ in range(4)] == [True] * 3 + [False]
        assert dispatcher._kept is kept
        # (Redis deletes an empty list, and then cannot tell an empty queue from none.)
        assert dispatcher.waiting_messages() in (0, None)
        assert other.take_waiting_message() is False
