"""Dispatch selection, the sweeper (with a recording fake dispatcher) and time limits."""

from __future__ import annotations

import time
from pathlib import Path

from worker.dispatch import LocalDispatch, make_dispatcher
from worker.dispatch.celery.dispatch import CeleryDispatch, Sweeper
from worker.registry import worker_registry
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.store.base import NewJob


class RecordingDispatch:
    def __init__(self, waiting: int | None = None) -> None:
        self.sent: list[tuple[str, float]] = []
        self.waiting = waiting

    def dispatch(self, job_id: str, time_limit_s: float) -> None:
        self.sent.append((job_id, time_limit_s))

    def waiting_messages(self) -> int | None:
        return self.waiting

    def close(self) -> None:
        pass


def test_no_broker_means_the_local_pool(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    dispatcher = make_dispatcher(WorkerSettings(), store, worker_registry())
    assert isinstance(dispatcher, LocalDispatch)
    dispatcher.close()


def test_broker_url_means_celery_without_connecting(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    settings = WorkerSettings(broker_url="redis://127.0.0.1:1/0")
    dispatcher = make_dispatcher(settings, store, worker_registry())
    assert isinstance(dispatcher, CeleryDispatch)
    conf = dispatcher.app.conf
    assert conf.task_acks_late and conf.task_reject_on_worker_lost
    assert conf.worker_prefetch_multiplier == 1
    assert conf.accept_content == ["json"] and conf.task_serializer == "json"
    dispatcher.close()


def test_sweeper_resends_lost_and_expired_jobs(tmp_path: Path) -> None:
    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    settings = WorkerSettings(redispatch_after_s=0.01)
    fake = RecordingDispatch()
    sweeper = Sweeper(settings, store, fake, worker_id="h:1")
    store.register_worker("h:1", "h", 1)
    lost, _ = store.create_job(NewJob("p", {}, time_limit_s=30, max_attempts=3))
    running, _ = store.create_job(NewJob("p", {}, time_limit_s=40, max_attempts=3))
    store.mark_dispatched(running.job_id)
    time.sleep(0.02)
    claim = store.claim_job(running.job_id, "w", 10).claim
    assert claim is not None
    assert sweeper.sweep() == 1 and fake.sent == [(lost.job_id, 30)]
    store.mark_dispatched(lost.job_id)
    store.expire_leases_of("w")  # the worker running it died
    fake.sent.clear()
    sweeper.sweep()
    assert (running.job_id, 40) in fake.sent


def test_sweeper_resends_only_what_the_brokers_queue_lacks(tmp_path: Path) -> None:
    """A backlog older than redispatch_after_s is not lost while the queue holds a
    message for each waiting job; the deficit is re-sent, oldest first.  (Half a
    second overdue, so that a loaded machine's pauses between the sweeps below do not
    make the jobs just sent overdue again.)"""
    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    jobs = [store.create_job(NewJob("p", {}, time_limit_s=30, max_attempts=3))[0]
            for _ in range(4)]  # fmt: skip
    for job in jobs:
        store.mark_dispatched(job.job_id)
    time.sleep(0.6)
    fake = RecordingDispatch(waiting=4)
    sweeper = Sweeper(WorkerSettings(redispatch_after_s=0.5), store, fake)
    assert sweeper.sweep() == 0 and fake.sent == []
    fake.waiting = 5  # more messages than jobs (duplicates, a retry on its way)
    assert sweeper.sweep() == 0
    fake.waiting = 1  # three were lost
    assert sweeper.sweep() == 3
    assert [job_id for job_id, _ in fake.sent] == [j.job_id for j in jobs[:3]]
    for job_id, _ in fake.sent:
        store.mark_dispatched(job_id)  # as CeleryDispatch.dispatch does
    fake.sent.clear()
    assert sweeper.sweep() == 1  # the queue still lacks three: the fourth is sent
    assert fake.sent == [(jobs[3].job_id, 30)]
    store.mark_dispatched(jobs[3].job_id)
    assert sweeper.sweep() == 0  # every job was sent again just now: none is overdue
    time.sleep(0.6)
    fake.waiting = None  # the broker cannot say: every overdue job is sent again
    assert sweeper.sweep() == 4
    assert store.accepted_count(2) == 2 and store.accepted_count(10) == 4


def test_sweepers_sweeping_at_once_resend_the_deficit_once(tmp_path: Path) -> None:
    """The API's sweeper and each worker's see the same deficit at the same instant
    and pick the same overdue jobs: between them they re-send each once, not once
    each."""
    import threading
    from typing import Any

    store = open_store(f"sqlite:///{tmp_path / 'j.db'}")
    jobs = [store.create_job(NewJob("p", {}, time_limit_s=30, max_attempts=3))[0]
            for _ in range(6)]  # fmt: skip
    time.sleep(0.02)
    together = threading.Barrier(3)

    class AtOnce:
        """The store, except that every sweeper has chosen before any takes."""

        def __getattr__(self, name: str) -> Any:
            return getattr(store, name)

        def take_overdue(self, job_ids: list[str], older_than_s: float) -> list[str]:
            together.wait(5)
            return store.take_overdue(job_ids, older_than_s)

    fakes = [RecordingDispatch(waiting=2) for _ in range(3)]  # four messages were lost
    settings = WorkerSettings(redispatch_after_s=0.01)
    sweepers = [Sweeper(settings, AtOnce(), fake) for fake in fakes]  # type: ignore[arg-type]
    threads = [threading.Thread(target=s.sweep) for s in sweepers]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    sent = [job_id for fake in fakes for job_id, _ in fake.sent]
    assert sorted(sent) == sorted(j.job_id for j in jobs[:4])


def test_time_limits_stay_below_the_brokers_redelivery_window() -> None:
    assert WorkerSettings().time_limit_for(1800) == 1800
    assert WorkerSettings(max_time_limit_s=60).time_limit_for(1800) == 60
    amqp = WorkerSettings(broker_url="amqp://guest:guest@127.0.0.1:5672//")
    assert amqp.time_limit_for(1800) == 0.9 * 1800
    redis = WorkerSettings(broker_url="redis://127.0.0.1:6379/0", broker_visibility_timeout_s=1000)
    assert redis.time_limit_for(1800) == 900


def test_each_celery_app_has_its_own_task_and_no_duplicate_warning() -> None:
    """`dexlab worker` makes two apps (one to work, one to send): neither may receive
    the other's task (Celery warns of a duplicate task name when one does)."""
    import warnings

    from worker.dispatch.celery.app import RUN_JOB, create_celery_app
    from worker.dispatch.celery.worker import run_delivered_job

    settings = WorkerSettings(broker_url="redis://127.0.0.1:1/0")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        apps = [create_celery_app(settings, run_delivered_job) for _ in range(3)]
        tasks = [app.tasks[RUN_JOB] for app in apps]
        sender = create_celery_app(settings)
    assert len({id(task) for task in tasks}) == 3
    assert all(task.app is app for task, app in zip(tasks, apps, strict=True))
    assert RUN_JOB not in sender.tasks  # a sender sends by name


def test_a_delivery_runs_further_jobs_only_inside_its_messages_time_limit() -> None:
    """A job started late in a delivery must still end inside the message's hard time
    limit: the batch gets at most half the slack between that limit and the longest
    job."""
    from worker.dispatch.celery.worker import delivery_batch_s

    redis = "redis://127.0.0.1:6379/0"
    registry = worker_registry()
    assert delivery_batch_s(WorkerSettings(broker_url=redis), registry) == 0.05
    assert delivery_batch_s(WorkerSettings(broker_url=redis, delivery_batch_s=0), registry) == 0
    tight = WorkerSettings(broker_url=redis, broker_visibility_timeout_s=1.0)
    # Jobs capped at 0.9 s, messages' hard limit 0.95 s: 0.05 s of slack, half of it.
    assert abs(delivery_batch_s(tight, registry) - 0.025) < 1e-9
