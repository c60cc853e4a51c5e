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
A loop whose outcomes are committed on a thread of their own may start its next
attempt meanwhile, so the guard may hold a committing attempt beside the computing
one; a stop waits for such commits to end (a lease at most), so that stopping for one
job never undoes another's finished work.
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
    """An attempt being guarded."""

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
        #: The attempt computing (at most one) and those whose outcome is being committed
        #: (replaced, never changed in place, so a heartbeat can read it unlocked).
        self._watches: list[_Watch] = []
        self._exiting = False
        self._wakes_at = float("inf")

    def watch(self, claim: Claim, deadline: float, progress: StoreProgress | None = None) -> None:
        """Guard this attempt (until :meth:`release`) with this time limit (a
        ``time.time()``); each heartbeat writes ``progress``'s held-back report."""
        with self._changed:
            next_beat = time.time() + self._settings.heartbeat_seconds
            self._watches = [*self._watches, _Watch(claim, deadline, progress, next_beat)]
            if min(deadline, next_beat) < self._wakes_at:
                self._changed.notify()
        if not self.is_alive():
            self.start()

    def committing(self, claim: Claim) -> None:
        """The attempt's work is done: from now on only renew its lease (while the loop
        may already be running its next attempt)."""
        with self._changed:
            for watch in self._watches:
                if watch.claim is claim:
                    watch.committing = True

    def release(self, claim: Claim) -> None:
        """Stop guarding the attempt; returns once no heartbeat for it is in flight."""
        with self._acting, self._changed:
            self._watches = [w for w in self._watches if w.claim is not claim]
            if self._exiting:  # it waits for the commits to end
                self._changed.notify_all()

    def run(self) -> None:
        while True:
            with self._changed:
                now = time.time()
                wake = min([now + self._settings.heartbeat_seconds]
                           + [w.due for w in self._watches])  # fmt: skip
                self._wakes_at = wake
                self._changed.wait(max(0.01, wake - now))
                self._wakes_at = float("inf")
                now = time.time()
                due = [w for w in self._watches if now >= w.due]
            for watch in due:
                code: int | None = None
                with self._acting:
                    if not any(w is watch for w in self._watches):
                        continue  # released meanwhile
                    with log_context(job_id=watch.claim.job.job_id):
                        code = self._beat(watch)
                    watch.next_beat = time.time() + self._settings.heartbeat_seconds
                if code is not None:
                    self._exit(code)

    def _exit(self, code: int) -> None:
        """Stop the process, once the outcomes being committed are committed (a lease
        at most: the stop must not wait for ever on a store in trouble)."""
        with self._changed:
            self._exiting = True
            self._changed.wait_for(
                lambda: not any(w.committing for w in self._watches),
                timeout=self._settings.lease_seconds,
            )
        os._exit(code)

    def _beat(self, watch: _Watch) -> int | None:
        """One heartbeat; the exit code when the process must stop."""
        job = watch.claim.job
        if not watch.committing and time.time() >= watch.deadline:
            self._fail_for_time_limit(watch.claim)
            return EXIT_TIME_LIMIT
        try:
            ack = self._store.heartbeat(
                job.job_id, watch.claim.lease_token, self._settings.lease_seconds
            )
        except Exception as exc:  # the store is down or locked: keep guarding
            log.warning("job %s: heartbeat failed (%s); still guarding", job.job_id, exc)
            return None
        try:
            self._store.worker_heartbeat(self._worker_id)
        except Exception as exc:
            log.warning("worker %s: heartbeat failed (%s)", self._worker_id, exc)
        if ack.owner:
            if watch.progress is not None:
                watch.progress.flush()
            return None
        if watch.committing:  # the fenced commit finds out by itself
            return None
        dismissed = ack.status is JobStatus.DISMISSED
        log.warning(
            "job %s %s; stopping this process",
            job.job_id,
            "was dismissed" if dismissed else "is no longer ours",
        )
        return EXIT_DISMISSED if dismissed else EXIT_LEASE_LOST

    def _fail_for_time_limit(self, claim: Claim) -> None:
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
