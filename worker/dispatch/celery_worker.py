"""The worker side of Celery: running a delivered job, and ``dexlab worker``'s main.

A delivery claims its job in the store.  If another attempt holds a live lease (its
process may have just died), the task is retried once the lease can have expired; if
the job is finished or dismissed, the delivery is dropped.  Each pool process builds
its own store connection the first time it runs a task (after the fork).

Logging stays as ``dexlab worker`` configured it (:mod:`worker.logs`): Celery is told
that logging is set up, so its lines, its task lines (which carry the task ID, the job
ID) and the prefork children's lines all share the one format.
"""

from __future__ import annotations

import logging
import os
import socket
from dataclasses import dataclass
from typing import Any

from celery import Celery, signals

from worker.contract import JobStatus
from worker.dispatch.celery_app import create_celery_app
from worker.dispatch.celery_dispatch import CeleryDispatch, Sweeper
from worker.logs import log_context, stdout_as_log_lines
from worker.processes import default_registry
from worker.runner import WorkerLoop, worker_id_for
from worker.settings import WorkerSettings
from worker.store import open_store

__all__ = ["run_celery_worker", "run_delivered_job"]

log = logging.getLogger("dexlab.celery")


@dataclass(frozen=True)
class _ProcessRuntime:
    pid: int
    loop: WorkerLoop


def _loop_for_this_process(app: Celery) -> WorkerLoop:
    runtime: _ProcessRuntime | None = getattr(app, "dexlab_runtime", None)
    if runtime is None or runtime.pid != os.getpid():
        settings: WorkerSettings = app.dexlab_settings
        store = open_store(settings.resolved_store_url(), retry_s=settings.store_retry_seconds)
        runtime = _ProcessRuntime(os.getpid(), WorkerLoop(settings, store, default_registry()))
        app.dexlab_runtime = runtime
    return runtime.loop


def run_delivered_job(app: Celery, job_id: str) -> float | None:
    """Run the delivered job if it can be claimed; seconds to retry after, or None."""
    with log_context(job_id=job_id):
        return _run_delivered_job(app, job_id)


def _run_delivered_job(app: Celery, job_id: str) -> float | None:
    loop = _loop_for_this_process(app)
    attempt = loop.store.claim_job(job_id, loop.worker_id, loop.settings.lease_seconds)
    if attempt.claim is not None:
        loop.execute(attempt.claim)
        return None
    if attempt.status is JobStatus.RUNNING and attempt.retry_after_s is not None:
        log.info(
            "job %s is held by a live lease; retrying in %.1f s", job_id, attempt.retry_after_s
        )
        return attempt.retry_after_s + 0.5
    log.info(
        "dropping a delivery of job %s (%s)",
        job_id,
        attempt.status.value if attempt.status else "unknown job",
    )
    return None


def _logging_is_set_up(**_: Any) -> None:
    """Celery's ``setup_logging`` signal: with a receiver, Celery leaves logging alone."""


def run_celery_worker(
    settings: WorkerSettings, log_level: str = "INFO", json_lines: bool = False
) -> None:
    """``dexlab worker`` with a broker: a Celery worker with ``settings.workers``
    prefork processes, plus a sweeper thread in the main process.  Logging must be
    configured already; with ``json_lines`` Celery's start-up banner is dropped and
    what it prints (its shutdown notices) becomes log lines, so that every line of
    the output is JSON."""
    signals.setup_logging.connect(_logging_is_set_up, weak=False, dispatch_uid="dexlab")
    if json_lines:
        stdout_as_log_lines("celery.stdout")
    store = open_store(settings.resolved_store_url(), retry_s=settings.store_retry_seconds)
    app = create_celery_app(settings)
    dispatcher = CeleryDispatch(settings, store)
    worker_id = worker_id_for(os.getpid())
    store.register_worker(worker_id, socket.gethostname(), os.getpid())
    sweeper = Sweeper(settings, store, dispatcher, worker_id=worker_id)
    sweeper.start()
    argv: list[Any] = [
        *(["--quiet"] if json_lines else []),
        "worker",
        f"--concurrency={settings.workers}",
        "--pool=prefork",
        f"--loglevel={log_level}",
        f"--queues={settings.queue}",
        "--prefetch-multiplier=1",
        "-O",
        "fair",
        "--without-gossip",
        "--without-mingle",
        f"--hostname=dexlab-{os.getpid()}@{socket.gethostname()}",
    ]
    try:
        app.worker_main(argv=argv)
    finally:
        sweeper.stop()
        store.unregister_worker(worker_id)
        dispatcher.close()
