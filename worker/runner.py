"""One worker process: claim a job, run it under a lease, store the outcome, repeat.

Claims take jobs in fair order (:mod:`worker.store.scheduling`); a loop made with
``prefer_cheap`` takes a cheap job first when one is queued.  While a job runs, a guard
thread renews the lease.  It stops the whole process (``os._exit``) when the job is
dismissed, when another attempt took the job over, or when the job's time limit passes
(after recording the failure); the pool then starts a fresh process in its place.
Worker processes run at a lower scheduling priority than the API
(:func:`lower_priority`), so requests stay quick while every core runs jobs.
"""

from __future__ import annotations

import contextlib
import logging
import os
import signal
import socket
import sys
import threading
import time
from collections.abc import Callable, Sequence
from typing import Any

from pydantic import ValidationError

from worker.contract import JobStatus
from worker.errors import StoreUnavailable
from worker.logs import configure_logging, log_context
from worker.processes import ProcessRegistry, worker_registry
from worker.progress import StoreProgress
from worker.result_commit import commit_outcome, error_document, record_failure
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.store.base import Claim, JobStore, NewJob

__all__ = ["AttemptGuard", "WorkerLoop", "lower_priority", "worker_id_for", "worker_main"]

log = logging.getLogger("dexlab.worker")

#: Exit codes of a worker process that stopped itself on purpose.
EXIT_DISMISSED = 3
EXIT_TIME_LIMIT = 4
EXIT_LEASE_LOST = 5


def worker_id_for(pid: int, host: str | None = None) -> str:
    """The ID a worker process registers under: ``host:pid``."""
    return f"{host or socket.gethostname()}:{pid}"


class AttemptGuard(threading.Thread):
    """Renews a running attempt's lease and enforces dismissal and the time limit."""

    def __init__(
        self,
        store: JobStore,
        claim: Claim,
        settings: WorkerSettings,
        worker_id: str,
        deadline: float,
    ) -> None:
        super().__init__(name=f"guard-{claim.job.job_id}", daemon=True)
        self._store = store
        self._claim = claim
        self._settings = settings
        self._worker_id = worker_id
        self._deadline = deadline
        self._done = threading.Event()

    def stop(self) -> None:
        self._done.set()

    def run(self) -> None:
        with log_context(job_id=self._claim.job.job_id):
            self._guard()

    def _guard(self) -> None:
        job = self._claim.job
        interval = self._settings.heartbeat_seconds
        while not self._done.wait(max(0.05, min(interval, self._deadline - time.time()))):
            if time.time() >= self._deadline:
                self._stop_for_time_limit()
            try:
                ack = self._store.heartbeat(
                    job.job_id, self._claim.lease_token, self._settings.lease_seconds
                )
            except Exception as exc:  # the store is down or locked: keep guarding
                log.warning("job %s: heartbeat failed (%s); still guarding", job.job_id, exc)
                continue
            try:
                self._store.worker_heartbeat(self._worker_id)
            except Exception as exc:
                log.warning("worker %s: heartbeat failed (%s)", self._worker_id, exc)
            if not ack.owner:
                dismissed = ack.status is JobStatus.DISMISSED
                log.warning(
                    "job %s %s; stopping this process",
                    job.job_id,
                    "was dismissed" if dismissed else "is no longer ours",
                )
                os._exit(EXIT_DISMISSED if dismissed else EXIT_LEASE_LOST)

    def _stop_for_time_limit(self) -> None:
        job = self._claim.job
        error = {
            "type": "time-limit-exceeded",
            "title": "Time limit exceeded",
            "detail": (
                f"Attempt {job.attempts} exceeded the job's time limit of "
                f"{job.time_limit_s:g} s and was stopped."
            ),
        }
        try:
            self._store.fail(job.job_id, self._claim.lease_token, error)
        except Exception:  # the lease lapses and the next attempt meets the limit again
            log.exception("job %s: could not record the time limit", job.job_id)
        log.warning("job %s exceeded its time limit; stopping", job.job_id)
        os._exit(EXIT_TIME_LIMIT)


class WorkerLoop:
    """Claims and runs jobs until told to stop or orphaned by its parent."""

    def __init__(
        self,
        settings: WorkerSettings,
        store: JobStore,
        registry: ProcessRegistry,
        prefer_cheap: bool = False,
        on_queued: Callable[[Sequence[str]], None] | None = None,
    ) -> None:
        self.settings = settings
        self.store = store
        self.registry = registry
        self.prefer_cheap = prefer_cheap
        #: Told the IDs of jobs this loop queued (a study's chunks, a study queued again
        #: to assemble): a broker deployment sends them; the local pool polls instead.
        self.on_queued = on_queued
        self.worker_id = worker_id_for(os.getpid())
        self._stop = threading.Event()

    def claim(self) -> Claim | None:
        """The next job in fair order (a cheap one first if this loop prefers them)."""
        return self.store.claim_next(
            self.worker_id,
            self.settings.lease_seconds,
            prefer_cheap=self.prefer_cheap,
            max_running_per_owner=self.settings.max_running_per_key,
        )

    def request_stop(self) -> None:
        self._stop.set()

    def run(self, parent_pid: int | None = None) -> None:
        if not self._register():
            return
        last_beat = time.monotonic()
        trouble = _Backoff()
        try:
            while not self._stop.is_set():
                if parent_pid is not None and os.getppid() != parent_pid:
                    log.warning("parent process went away; worker %s exits", self.worker_id)
                    return
                try:
                    if time.monotonic() - last_beat >= self.settings.heartbeat_seconds:
                        self.store.worker_heartbeat(self.worker_id)
                        last_beat = time.monotonic()
                    claim = self.claim()
                except StoreUnavailable as exc:
                    log.warning("worker %s: the store is unavailable (%s)", self.worker_id, exc)
                    self._stop.wait(trouble.next_pause())
                    continue
                trouble.reset()
                if claim is None:
                    self._stop.wait(self.settings.poll_seconds)
                    continue
                self.execute(claim)
        finally:
            with contextlib.suppress(StoreUnavailable):
                self.store.unregister_worker(self.worker_id)

    def _register(self) -> bool:
        """Register with the store, waiting out store trouble; False if told to stop."""
        trouble = _Backoff()
        while not self._stop.is_set():
            try:
                self.store.register_worker(self.worker_id, socket.gethostname(), os.getpid())
                return True
            except StoreUnavailable as exc:
                log.warning("worker %s cannot register yet: %s", self.worker_id, exc)
                self._stop.wait(trouble.next_pause())
        return False

    @property
    def _give_up_after_s(self) -> float:
        """How long a finished attempt keeps trying to commit through store trouble."""
        return 2.0 * self.settings.lease_seconds

    def execute(self, claim: Claim) -> None:
        with log_context(job_id=claim.job.job_id):
            self._execute(claim)

    def _execute(self, claim: Claim) -> None:
        job = claim.job
        log.info("worker %s runs job %s (attempt %d)", self.worker_id, job.job_id, job.attempts)
        deadline = time.time() + job.time_limit_s
        guard = AttemptGuard(self.store, claim, self.settings, self.worker_id, deadline)
        guard.start()
        try:  # the guard renews the lease until the outcome is committed
            definition = self.registry.get(job.process_id)
            if definition is not None and definition.fan_out is not None and job.phase is None:
                self._split(claim, definition, guard)
                return
            outcome = self._run_job(claim)
            if outcome is not None:
                result, artifacts = outcome
                commit_outcome(self.store, claim, result, artifacts, self._give_up_after_s)
        finally:
            guard.stop()
        if job.parent_id is not None:
            self._notify_parent(job.parent_id)

    def _split(self, claim: Claim, definition: Any, guard: AttemptGuard) -> None:
        """A fan-out job's first attempt: its children queued, itself parked (it holds
        no worker while they run; worker.store.fan_out)."""
        job = claim.job
        steps = definition.fan_out
        try:
            inputs = definition.inputs_model.model_validate(job.inputs)
            child = self.registry.get(steps.child_process)
            if child is None:
                raise RuntimeError(f"this worker does not know the process {steps.child_process!r}")
            children = [
                NewJob(
                    process_id=child.id,
                    inputs=child_inputs,
                    time_limit_s=self.settings.time_limit_for(child.time_limit_s),
                    max_attempts=job.max_attempts,
                    owner=job.owner,
                    parent_id=job.job_id,
                )
                for child_inputs in steps.split(inputs)
            ]
            allow_partial = bool(steps.allow_partial(inputs))
        except (Exception, ValidationError) as exc:
            log.exception("job %s could not be split", job.job_id)
            record_failure(self.store, claim, error_document(exc), self._give_up_after_s)
            return
        guard.stop()  # the split drops the lease: no heartbeat may follow it
        guard.join()
        ids = self.store.split(job.job_id, claim.lease_token, children, allow_partial=allow_partial)
        if ids is None:
            log.warning("job %s was lost while it split", job.job_id)
            return
        log.info("job %s split into %d jobs", job.job_id, len(ids))
        if self.on_queued is not None:
            self.on_queued(ids or [job.job_id])

    def _notify_parent(self, parent_id: str) -> None:
        """Send the parent on if this job's end queued it to assemble."""
        if self.on_queued is None:
            return
        try:
            parent = self.store.get_job(parent_id)
        except StoreUnavailable:  # the sweeper re-sends undispatched jobs
            return
        if (
            parent is not None
            and parent.status is JobStatus.ACCEPTED
            and parent.phase == "assembling"
        ):
            self.on_queued([parent_id])

    def _run_job(self, claim: Claim) -> tuple[dict[str, Any], Any] | None:
        job = claim.job
        definition = self.registry.get(job.process_id)
        if definition is None:
            error = {
                "type": "no-such-process",
                "title": "Unknown process",
                "detail": f"This worker does not know the process {job.process_id!r}.",
            }
            record_failure(self.store, claim, error, self._give_up_after_s)
            return None
        try:
            inputs = definition.inputs_model.model_validate(job.inputs)
            context = StoreProgress(self.store, job.job_id, claim.lease_token)
            context.report_progress(0.0, "started")
            if definition.fan_out is not None and job.phase == "assembling":
                children = self.store.child_results(job.job_id)
                outcome = definition.fan_out.assemble(inputs, children, context)
            else:
                outcome = definition.run(inputs, context)
        except (Exception, ValidationError) as exc:
            log.exception("job %s raised", job.job_id)
            record_failure(self.store, claim, error_document(exc), self._give_up_after_s)
            return None
        result = dict(outcome.result)
        result["notes"] = list(outcome.all_notes)
        result["paper_errata"] = list(outcome.errata)
        return result, list(outcome.artifacts)


class _Backoff:
    """Growing, capped pauses while the store is in trouble."""

    def __init__(self, first_s: float = 0.2, cap_s: float = 5.0) -> None:
        self._first = first_s
        self._cap = cap_s
        self._next = first_s

    def next_pause(self) -> float:
        pause = self._next
        self._next = min(2 * self._next, self._cap)
        return pause

    def reset(self) -> None:
        self._next = self._first


#: Exit code of a worker process that could not start (e.g. the store cannot be opened).
EXIT_STARTUP = 6


def _beat_forever(liveness: Any) -> None:
    """Tell the supervisor this process runs, twice a second, whatever the job does (a
    frozen, e.g. SIGSTOPped, process stops beating and is killed)."""
    while True:
        liveness.value = time.time()
        time.sleep(0.5)


def lower_priority(increment: int, what: str) -> int:
    """Lower this process's scheduling priority by ``increment`` (``os.nice``), log it
    for ``what`` (e.g. "worker process 12"), and return the niceness it now has."""
    before = os.nice(0)
    now = os.nice(increment) if increment else before
    log.info(
        "%s runs at niceness %d (DEXLAB_WORKER_NICE=%d above the %d it started with), "
        "so the API comes first",
        what,
        now,
        increment,
        before,
    )
    return now


def worker_main(
    settings_data: dict[str, Any],
    parent_pid: int | None = None,
    liveness: Any = None,
    log_level: int = logging.INFO,
    prefer_cheap: bool = False,
) -> None:
    """Entry point of a pool process (spawned): lower its priority, build resources,
    then loop (taking cheap jobs first with ``prefer_cheap``).  It logs at its
    supervisor's ``log_level``, in ``DEXLAB_LOG_FORMAT`` (inherited)."""
    configure_logging(level=log_level)
    if liveness is not None:
        threading.Thread(
            target=_beat_forever, args=(liveness,), name="liveness", daemon=True
        ).start()
    settings = WorkerSettings.model_validate(settings_data)
    lower_priority(settings.worker_nice, f"worker process {os.getpid()}")
    try:
        store = open_store(settings.resolved_store_url(), retry_s=settings.store_retry_seconds)
    except Exception as exc:  # the supervisor backs off and says why
        log.error("worker process %d cannot open the job store: %s", os.getpid(), exc)
        sys.exit(EXIT_STARTUP)
    loop = WorkerLoop(settings, store, worker_registry(), prefer_cheap=prefer_cheap)
    signal.signal(signal.SIGTERM, lambda *_: loop.request_stop())
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the supervisor decides when we stop
    loop.run(parent_pid=parent_pid)
