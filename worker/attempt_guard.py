"""The guard of a worker loop's running attempt: renews its lease, enforces dismissal
and the time limit.

One guard thread serves a worker loop for its whole life (a thread per job cost a
thread start, and a wait for the new thread to be scheduled, on every job).  The loop
hands it each attempt (:meth:`AttemptGuard.watch`), says when the attempt's work is done
and its outcome is being committed (:meth:`AttemptGuard.committing`), and takes it back
(:meth:`AttemptGuard.release`, which waits for a heartbeat in flight, so no write for
the attempt follows it).

While the attempt computes, the guard stops the whole process (``os._exit``; the pool
or Celery starts a fresh one) when the job is dismissed, when another attempt took it
over, or when its time limit passes (after recording the failure).  While the outcome
is committed it only renews the lease: the commit is fenced and finds out by itself.
"""

from __future__ import annotations

import logging
import os
import threading
import time
from dataclasses import dataclass

from worker.contract import JobStatus
from worker.logs import log_context
from worker.progress import StoreProgress
from worker.settings import WorkerSettings
from worker.store.base import Claim, JobStore

__all__ = ["EXIT_DISMISSED", "EXIT_LEASE_LOST", "EXIT_TIME_LIMIT", "AttemptGuard"]

log = logging.getLogger("dexlab.worker")

#: Exit codes of a worker process that stopped itself on purpose.
EXIT_DISMISSED = 3
EXIT_TIME_LIMIT = 4
EXIT_LEASE_LOST = 5


@dataclass
class _Watch:
    """The attempt being guarded."""

    claim: Claim
    deadline: float
    progress: StoreProgress | None
    next_beat: float
    committing: bool = False

    @property
    def due(self) -> float:
        """When the guard must act next: a heartbeat, or the time limit while the
        attempt computes."""
        return self.next_beat if self.committing else min(self.next_beat, self.deadline)


class AttemptGuard(threading.Thread):
    """Renews the lease of the attempt a worker loop runs (one thread per loop).

    The thread wakes once a heartbeat interval (sooner for a time limit), whether or
    not the loop changed attempts meanwhile: handing it an attempt and taking it back
    do not wake it, so a stream of short jobs costs it nothing.
    """

    def __init__(self, store: JobStore, settings: WorkerSettings, worker_id: str) -> None:
        super().__init__(name="attempt-guard", daemon=True)
        self._store = store
        self._settings = settings
        self._worker_id = worker_id
        self._changed = threading.Condition()
        self._acting = threading.Lock()  # held while a heartbeat acts for an attempt
        self._watch: _Watch | None = None
        self._wakes_at = float("inf")

    def watch(self, claim: Claim, deadline: float, progress: StoreProgress | None = None) -> None:
        """Guard this attempt (until :meth:`release`) with this time limit (a
        ``time.time()``); each heartbeat writes ``progress``'s held-back report."""
        with self._changed:
            next_beat = time.time() + self._settings.heartbeat_seconds
            self._watch = _Watch(claim, deadline, progress, next_beat)
            if min(deadline, next_beat) < self._wakes_at:
                self._changed.notify()
        if not self.is_alive():
            self.start()

    def committing(self) -> None:
        """The attempt's work is done: from now on only renew its lease."""
        with self._changed:
            if self._watch is not None:
                self._watch.committing = True

    def release(self) -> None:
        """Stop guarding the attempt; returns once no heartbeat for it is in flight."""
        with self._acting, self._changed:
            self._watch = None

    def run(self) -> None:
        while True:
            with self._changed:
                watch = self._watch
                now = time.time()
                wake = now + self._settings.heartbeat_seconds
                if watch is not None:
                    wake = min(wake, watch.due)
                self._wakes_at = wake
                self._changed.wait(max(0.01, wake - now))
                self._wakes_at = float("inf")
                watch = self._watch
                now = time.time()
                if watch is None or now < watch.due:
                    continue
            with self._acting:
                if self._watch is watch:
                    with log_context(job_id=watch.claim.job.job_id):
                        self._beat(watch)
                    watch.next_beat = time.time() + self._settings.heartbeat_seconds

    def _beat(self, watch: _Watch) -> None:
        job = watch.claim.job
        if not watch.committing and time.time() >= watch.deadline:
            self._stop_for_time_limit(watch.claim)
        try:
            ack = self._store.heartbeat(
                job.job_id, watch.claim.lease_token, self._settings.lease_seconds
            )
        except Exception as exc:  # the store is down or locked: keep guarding
            log.warning("job %s: heartbeat failed (%s); still guarding", job.job_id, exc)
            return
        try:
            self._store.worker_heartbeat(self._worker_id)
        except Exception as exc:
            log.warning("worker %s: heartbeat failed (%s)", self._worker_id, exc)
        if ack.owner:
            if watch.progress is not None:
                watch.progress.flush()
            return
        if watch.committing:  # the fenced commit finds out by itself
            return
        dismissed = ack.status is JobStatus.DISMISSED
        log.warning(
            "job %s %s; stopping this process",
            job.job_id,
            "was dismissed" if dismissed else "is no longer ours",
        )
        os._exit(EXIT_DISMISSED if dismissed else EXIT_LEASE_LOST)

    def _stop_for_time_limit(self, claim: Claim) -> None:
        job = claim.job
        error = {
            "type": "time-limit-exceeded",
            "title": "Time limit exceeded",
            "detail": (
                f"Attempt {job.attempts} exceeded the job's time limit of "
                f"{job.time_limit_s:g} s and was stopped."
            ),
        }
        try:
            self._store.fail(job.job_id, claim.lease_token, error)
        except Exception:  # the lease lapses and the next attempt meets the limit again
            log.exception("job %s: could not record the time limit", job.job_id)
        log.warning("job %s exceeded its time limit; stopping", job.job_id)
        os._exit(EXIT_TIME_LIMIT)
