"""The worker side of Celery: running a delivered job, and ``dexlab worker``'s main.

**A delivery means "claim the next job in fair order".**  Each submitted job sends one
message (its ID as the task ID), but the process that receives it claims whatever job
the store's fair order names (:mod:`worker.store.scheduling`: the owner whose last
claim is oldest, then its oldest job; pool process 0 takes a cheap job first).  The
broker's queue is first-in first-out, so a message that meant "run this job" would
make another owner's job, or a small one, wait behind every message sent before it;
the store sees every queued job and decides fairly, the same way for the local pool
and for Celery.  Messages stay one per job, so there is always a message for each
queued job: a claim uses one message and one job, and a message that finds nothing
to claim is dropped.

**A delivery of short jobs runs several** (``DEXLAB_DELIVERY_BATCH_S``): once its job is
done it claims the next one in fair order, runs it, and takes one waiting message off
the queue for it, until the time is up or no message waits (:func:`_run_further_jobs`).

**A job's outcome is committed behind it**, on a thread of the pool process
(``commit_behind``, :class:`worker.runner.WorkerLoop`), while the next job is claimed
and run, or Celery acknowledges the message and hands the process its next one; the
next commit, and the process's shutdown, wait for it.  The lease is renewed until the
commit is made, so a process that dies in between leaves a job that is retried as
always (its lease lapses and the sweeper sends it again): the acknowledgement was
never what kept a job, the store is.

When nothing is claimable, the delivered job itself decides: held by another
attempt's live lease (its process may have just died), the task is retried once the
lease can have expired; waiting behind its owner's running cap, it is retried shortly;
finished or dismissed, the delivery is dropped.  Each pool process builds its own
store connection the first time it runs a task (after the fork); the job modules are
loaded before the fork.  The pool processes run at a lower scheduling priority than
the API (``DEXLAB_WORKER_NICE``), and the main process runs the sweepers.

**A frozen pool process is killed** (:mod:`worker.liveness`): each pool process beats
in its slot (its pool index, kept by the process started in its place) of a board the
main process made before the fork, and the main process's watchdog SIGKILLs one that
showed no sign of life (no beat, no CPU time) for a lease.  Billiard then starts a new
process in its slot and returns the message it held to the queue; the job it was
running has lost its lease by then and is retried as for a process that died.
Without it a SIGSTOPped process would hold its slot, and its message, for ever.

Logging stays as ``dexlab worker`` configured it (:mod:`worker.logs`): Celery is told
that logging is set up, so its lines, its task lines (which carry the task ID, the job
ID) and the prefork children's lines all share the one format.
"""

from __future__ import annotations

import logging
import os
import socket
import time
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any

from celery import Celery, signals
from celery.utils.log import current_process_index

from worker.contract import JobStatus
from worker.dispatch.celery.app import create_celery_app
from worker.dispatch.celery.dispatch import (
    CeleryDispatch,
    Sweeper,
    hard_time_limit,
    longest_time_limit,
)
from worker.errors import StoreUnavailable
from worker.liveness import LivenessBoard, Watchdog, frozen_after_s
from worker.logs import log_context, stdout_as_log_lines
from worker.pool_process import lower_priority
from worker.processes import ProcessRegistry
from worker.registry import preload_job_modules, worker_registry
from worker.retention import RetentionSweeper
from worker.runner import WorkerLoop, worker_id_for
from worker.settings import WorkerSettings
from worker.store import open_store

__all__ = ["run_celery_worker", "run_delivered_job"]

log = logging.getLogger("dexlab.celery")


@dataclass(frozen=True)
class _ProcessRuntime:
    pid: int
    loop: WorkerLoop
    sender: _Sender
    #: How long a delivery may go on running further jobs (seconds; 0: never).
    batch_s: float


def _runtime_for_this_process(app: Celery) -> _ProcessRuntime:
    runtime: _ProcessRuntime | None = getattr(app, "dexlab_runtime", None)
    if runtime is None or runtime.pid != os.getpid():
        settings: WorkerSettings = app.dexlab_settings
        store = open_store(settings.resolved_store_url(), retry_s=settings.store_retry_seconds)
        # The pool's first process prefers cheap jobs (its index is kept when replaced).
        cheap = current_process_index(base=0) == 0
        registry = worker_registry()
        sender = _Sender(settings, store, registry)
        loop = WorkerLoop(
            settings,
            store,
            registry,
            prefer_cheap=cheap,
            on_queued=sender.send,
            commit_behind=True,
        )
        runtime = _ProcessRuntime(os.getpid(), loop, sender, delivery_batch_s(settings, registry))
        app.dexlab_runtime = runtime
    return runtime


def run_delivered_job(app: Celery, job_id: str) -> float | None:
    """Run the delivered job if it can be claimed; seconds to retry after, or None."""
    with log_context(job_id=job_id):
        return _run_delivered_job(app, job_id)


def delivery_batch_s(settings: WorkerSettings, registry: ProcessRegistry) -> float:
    """How long a delivery may go on running further jobs: ``delivery_batch_s``, but
    at most half the slack between a message's hard time limit and the longest job (a
    job started late in a delivery must still end inside its message's limit, and so
    inside the broker's redelivery window)."""
    longest = longest_time_limit(settings, registry)
    slack = hard_time_limit(settings, longest) - longest
    return max(0.0, min(settings.delivery_batch_s, slack / 2))


class _Sender:
    """Sends the jobs a pool process queued (a study's chunks, a study to assemble):
    one message each, as for a submission; and takes waiting messages off the queue
    for a delivery's further jobs (broker connections made on first use)."""

    def __init__(self, settings: WorkerSettings, store: Any, registry: ProcessRegistry) -> None:
        self._dispatch = CeleryDispatch(settings, store, registry)
        self._taker: ThreadPoolExecutor | None = None

    def send(self, job_ids: Any) -> None:
        for job_id in job_ids:
            self._dispatch.dispatch(job_id, 0.0)

    def take_behind(self) -> Future[bool]:
        """Take one waiting message off the queue (``CeleryDispatch``, whose kept
        connection only this thread uses), on a thread of its own (one broker round
        trip less before the next claim); its future says whether one was waiting."""
        if self._taker is None:
            self._taker = ThreadPoolExecutor(1, thread_name_prefix="take")
        return self._taker.submit(self._dispatch.take_waiting_message)


def _run_delivered_job(app: Celery, job_id: str) -> float | None:
    runtime = _runtime_for_this_process(app)
    loop = runtime.loop
    until = time.monotonic() + runtime.batch_s
    claim = loop.claim()  # the next job in fair order, whichever message brought us here
    if claim is not None:
        # Its lines carry the job it runs (the delivery's task ID is on Celery's lines).
        with log_context(job_id=claim.job.job_id):
            if claim.job.job_id != job_id:
                log.info("job %s runs on another job's delivery (fair order)", claim.job.job_id)
            loop.execute(claim)
        _run_further_jobs(runtime, until)
        return None
    attempt = loop.store.claim_job(
        job_id,
        loop.worker_id,
        loop.settings.lease_seconds,
        max_running_per_owner=loop.settings.max_running_per_key,
    )
    if attempt.claim is not None:
        loop.execute(attempt.claim)
        return None
    if attempt.status is JobStatus.RUNNING and attempt.retry_after_s is not None:
        log.info(
            "job %s is held by a live lease; retrying in %.1f s", job_id, attempt.retry_after_s
        )
        return attempt.retry_after_s + 0.5
    if attempt.status is JobStatus.ACCEPTED and attempt.retry_after_s is not None:
        log.info("job %s waits for its owner's running cap", job_id)
        return attempt.retry_after_s
    log.info(
        "dropping a delivery of job %s (%s)",
        job_id,
        attempt.status.value if attempt.status else "unknown job",
    )
    return None


def _run_further_jobs(runtime: _ProcessRuntime, until: float) -> None:
    """Until ``until`` (a ``time.monotonic()``), while messages wait: claim the next job
    in fair order, run it, and take a waiting message off the queue for it (on a thread,
    while the next job is claimed).

    Short jobs then run back to back, their outcomes committed behind the next claim,
    instead of one per delivery through Celery's main process (a broker round trip to
    acknowledge and another to fetch, for a job of a millisecond).  Messages and queued
    jobs stay paired: a job run here takes one message, and when none waited (the rest
    are on their way to other processes) the delivery ends; the surplus message that
    arrives later finds nothing and is dropped.  A process that dies here is what
    it always was: the delivery's own message goes back to the queue (it is
    acknowledged when the delivery ends), and the running job's lease lapses and the
    sweeper sends it again."""
    taken: Future[bool] | None = None
    while time.monotonic() < until:
        if taken is not None and not taken.result():  # no message waited for the last
            return
        try:
            claim = runtime.loop.claim()
        except StoreUnavailable as exc:  # what ran is committed or retried; stop here
            log.warning("the store is unavailable (%s); this delivery runs no more jobs", exc)
            return
        if claim is None:
            return
        with log_context(job_id=claim.job.job_id):
            runtime.loop.execute(claim)
        taken = runtime.sender.take_behind()


def _settle_at_exit(app: Celery) -> None:
    """Celery's ``worker_process_shutdown`` in a pool process: the outcome still being
    committed is committed before the process exits."""
    runtime: _ProcessRuntime | None = getattr(app, "dexlab_runtime", None)
    if runtime is not None and runtime.pid == os.getpid():
        runtime.loop.settle()


def _init_pool_process(settings: WorkerSettings, board: LivenessBoard) -> None:
    """Celery's ``worker_process_init`` in a new pool process: beat in its slot of the
    board, and run the jobs at a lower priority (the main process only receives
    messages and hands them over, and keeps its own priority so that the pool is never
    kept waiting for its next message)."""
    slot = current_process_index(base=0)
    if slot is not None and 0 <= slot < board.slots:
        board.start_beating(slot)
    else:  # not expected with a fixed-size pool; it is then not watched
        log.warning("Celery pool process %d has no slot (index %s)", os.getpid(), slot)
    lower_priority(settings.worker_nice, f"Celery pool process {os.getpid()}")


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
    # Made before the pool forks, so every pool process shares it.
    board = LivenessBoard(settings.workers)
    signals.worker_process_init.connect(
        lambda **_: _init_pool_process(settings, board), weak=False, dispatch_uid="dexlab-init"
    )
    # Loaded once here, before Celery forks its pool: a pool process (and one started in
    # place of a process that stopped) has them from the start, not on its first job.
    started = time.monotonic()
    modules = preload_job_modules()
    log.info("loaded %d job modules in %.2f s", len(modules), time.monotonic() - started)
    store = open_store(settings.resolved_store_url(), retry_s=settings.store_retry_seconds)
    app = create_celery_app(settings, run_delivered_job)
    signals.worker_process_shutdown.connect(
        lambda **_: _settle_at_exit(app), weak=False, dispatch_uid="dexlab-settle"
    )
    dispatcher = CeleryDispatch(settings, store, worker_registry())
    worker_id = worker_id_for(os.getpid())
    store.register_worker(worker_id, socket.gethostname(), os.getpid())
    sweeper = Sweeper(settings, store, dispatcher, worker_id=worker_id)
    sweeper.start()
    watchdog = Watchdog(board, frozen_after_s(settings))
    watchdog.start()
    retention = RetentionSweeper(settings, store)
    retention.start()
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
        watchdog.stop()
        sweeper.stop()
        retention.stop()
        store.unregister_worker(worker_id)
        dispatcher.close()
