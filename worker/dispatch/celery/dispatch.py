"""Sending job IDs to Celery, and the sweeper that re-sends lost ones.

A message names a job, but its delivery claims the next job in fair order
(:mod:`worker.dispatch.celery.worker`), which may be another job with a longer time
limit: so each message's Celery hard time limit is the longest any job may run (the
longest process time limit, capped as :meth:`WorkerSettings.time_limit_for` caps
every job's, and kept below the broker's redelivery window) plus a grace.  It is a
backstop: the worker's own guard stops a job at its own limit and records why.
"""

from __future__ import annotations

import logging
import threading
from contextlib import suppress
from typing import Any

from worker.dispatch.celery.app import RUN_JOB, create_celery_app
from worker.dispatch.port import Dispatcher
from worker.processes import ProcessRegistry
from worker.settings import WorkerSettings
from worker.store.base import JobStore

__all__ = ["CeleryDispatch", "Sweeper", "hard_time_limit", "longest_time_limit"]

log = logging.getLogger("dexlab.dispatch")

#: Celery's hard time limit is a backstop behind the worker's own (which records why).
HARD_LIMIT_GRACE_S = 60.0


class CeleryDispatch:
    """Sends ``dexlab.run_job(job_id)`` with the job ID as the task ID."""

    def __init__(
        self, settings: WorkerSettings, store: JobStore, registry: ProcessRegistry
    ) -> None:
        self.settings = settings
        self.store = store
        self.app = create_celery_app(settings)
        self._longest_s = longest_time_limit(settings, registry)
        self._kept: Any = None  # the broker connection kept for counting and taking

    def dispatch(self, job_id: str, time_limit_s: float) -> None:
        try:
            self.app.send_task(
                RUN_JOB,
                args=[job_id],
                task_id=job_id,
                queue=self.settings.queue,
                time_limit=hard_time_limit(self.settings, max(time_limit_s, self._longest_s)),
                retry=True,
                retry_policy={"max_retries": 2, "interval_start": 0.2, "interval_step": 0.5},
            )
        except Exception:  # the job is committed; the sweeper sends it again later
            log.exception("could not send job %s to the broker; it will be re-sent", job_id)
            return
        self.store.mark_dispatched(job_id)

    def waiting_messages(self) -> int | None:
        """The messages in the queue, not yet handed to a worker (a passive declare on
        a channel of its own, which Redis and RabbitMQ both answer), or None if the
        broker cannot say.  One connection is kept for it (the sweeper asks every sweep
        while jobs are overdue), and dropped on any error."""
        try:
            channel = self._kept_connection().channel()
            try:
                _, count, _ = channel.queue_declare(queue=self.settings.queue, passive=True)
            finally:
                with suppress(Exception):
                    channel.close()
            return int(count)
        except Exception as exc:  # the queue not declared yet, or the broker away
            log.debug("cannot count the broker's waiting messages: %s", exc)
            self._drop_kept()
            return None

    def take_waiting_message(self) -> bool:
        """Take one waiting message off the queue, acknowledged as it is taken (it is
        gone); True if there was one, False if none was waiting or the broker cannot
        say.  Messages are interchangeable (a delivery claims the next job in fair
        order), so a delivery that runs one more job takes one more message.  On the
        kept connection, dropped on any error."""
        try:
            message = self._kept_connection().default_channel.basic_get(
                queue=self.settings.queue, no_ack=True
            )
            return message is not None
        except Exception as exc:  # the broker away: this delivery runs no more jobs
            log.debug("cannot take a waiting message: %s", exc)
            self._drop_kept()
            return False

    def _kept_connection(self) -> Any:
        if self._kept is None:
            self._kept = self.app.connection_for_read()
            self._kept.ensure_connection(max_retries=1)
        return self._kept

    def _drop_kept(self) -> None:
        kept, self._kept = self._kept, None
        if kept is not None:
            with suppress(Exception):
                kept.release()

    def close(self) -> None:
        self._drop_kept()
        self.app.close()


def longest_time_limit(settings: WorkerSettings, registry: ProcessRegistry) -> float:
    """The longest time limit any job of ``registry``'s processes gets (seconds)."""
    return max((settings.time_limit_for(d.time_limit_s) for d in registry), default=0.0)


def hard_time_limit(settings: WorkerSettings, time_limit_s: float) -> float:
    """Celery's hard limit for a message whose job may run ``time_limit_s``: a grace
    beyond it, but short of the broker's redelivery window (a message must never be
    handed out again while its job runs)."""
    limit = time_limit_s + HARD_LIMIT_GRACE_S
    window = settings.broker_redelivery_window_s()
    if window is not None:
        limit = min(limit, max(time_limit_s, 0.95 * window))
    return limit


class Sweeper(threading.Thread):
    """Every ``sweep_seconds``: requeue jobs whose lease expired (their worker died)
    and send them again, and re-send accepted jobs whose message was lost
    (:meth:`_lost`).

    Runs beside the API (broker mode) and in each ``dexlab worker``; running several is
    harmless, since a job is claimed in the store exactly once per attempt.
    """

    def __init__(
        self,
        settings: WorkerSettings,
        store: JobStore,
        dispatcher: Dispatcher,
        worker_id: str | None = None,
    ) -> None:
        super().__init__(name="dexlab-sweeper", daemon=True)
        self.settings = settings
        self.store = store
        self.dispatcher = dispatcher
        self.worker_id = worker_id
        # Not ``_stop``: that name is threading.Thread's own method (join, is_alive and
        # the after-fork clean-up in Celery's prefork children call it).
        self._stopping = threading.Event()

    def stop(self) -> None:
        self._stopping.set()

    def sweep(self) -> int:
        """One pass; the number of jobs sent."""
        if self.worker_id is not None:
            self.store.worker_heartbeat(self.worker_id)
        job_ids = self.store.reap_expired()
        job_ids += self._lost()
        for job_id in dict.fromkeys(job_ids):
            job = self.store.get_job(job_id)
            if job is not None:
                log.info("re-sending job %s to the broker", job_id)
                self.dispatcher.dispatch(job_id, job.time_limit_s)
        return len(job_ids)

    def _lost(self) -> list[str]:
        """Jobs whose message may be lost: accepted jobs not claimed within
        ``redispatch_after_s`` of their last message, but only as many as the broker's
        queue lacks messages for the accepted jobs.  A delivery claims the next job in
        fair order whichever job its message names, so messages are interchangeable:
        while the queue holds one for every waiting job, none was lost, however long
        the backlog (re-sending would only pile up duplicates).  When the broker cannot
        say, every overdue job is sent again (duplicates are dropped on delivery).  The
        jobs chosen are marked dispatched in the store as they are chosen, only if still
        overdue: of the sweepers (the API's, each worker's) choosing at once, one
        re-sends each."""
        after_s = self.settings.redispatch_after_s
        overdue = self.store.undispatched(after_s)
        if not overdue:
            return []
        waiting = self.dispatcher.waiting_messages()
        if waiting is not None:
            missing = self.store.accepted_count(waiting + len(overdue)) - waiting
            overdue = overdue[: max(0, missing)]
        return self.store.take_overdue(overdue, after_s) if overdue else []

    def run(self) -> None:
        while not self._stopping.wait(self.settings.sweep_seconds):
            try:
                self.sweep()
            except Exception:  # a store or broker hiccup: try again next time
                log.exception("sweep failed")
