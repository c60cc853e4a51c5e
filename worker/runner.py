"""One worker process: claim a job, run it under a lease, store the outcome, repeat.

Claims take jobs in fair order (:mod:`worker.store.scheduling`); a loop made with
``prefer_cheap`` takes a cheap job first when one is queued.  While a job runs, the
loop's guard thread (:mod:`worker.attempt_guard`) renews the lease.  It stops the whole
process (``os._exit``) when the job is dismissed, when another attempt took the job
over, or when the job's time limit passes (after recording the failure); the pool then
starts a fresh process in its place.
With nothing to claim, a local pool's process sleeps until a hint on its pool's wake-up
socket says jobs were queued, or ``poll_seconds`` at most (:mod:`worker.idle`).
A pool process's entry point is :mod:`worker.pool_process`.
"""

from __future__ import annotations

import contextlib
import logging
import os
import socket
import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Any

from pydantic import ValidationError

from worker.attempt_guard import AttemptGuard
from worker.contract import JobStatus
from worker.dispatch.wake_ups import WakeUpListener
from worker.errors import StoreUnavailable
from worker.idle import IdleWait
from worker.logs import log_context
from worker.processes import ProcessRegistry
from worker.progress import StoreProgress
from worker.provenance.build import provenance_block, result_key
from worker.provenance.stamp import stamp_outcome
from worker.result_commit import commit_outcome, error_document, record_failure
from worker.settings import WorkerSettings
from worker.store.base import Claim, JobStore, NewJob

__all__ = ["WorkerLoop", "worker_id_for"]

log = logging.getLogger("dexlab.worker")


def worker_id_for(pid: int, host: str | None = None) -> str:
    """The ID a worker process registers under: ``host:pid``."""
    return f"{host or socket.gethostname()}:{pid}"


class WorkerLoop:
    """Claims and runs jobs until told to stop or orphaned by its parent."""

    def __init__(
        self,
        settings: WorkerSettings,
        store: JobStore,
        registry: ProcessRegistry,
        prefer_cheap: bool = False,
        on_queued: Callable[[Sequence[str]], None] | None = None,
        commit_behind: bool = False,
        wake_ups: WakeUpListener | None = None,
    ) -> None:
        self.settings = settings
        self.store = store
        self.registry = registry
        self.prefer_cheap = prefer_cheap
        #: Told the IDs of jobs this loop queued (a study's chunks, a study queued again
        #: to assemble): a broker deployment sends them; the local pool wakes its idle
        #: processes.
        self.on_queued = on_queued
        self.worker_id = worker_id_for(os.getpid())
        self._stop = threading.Event()
        self._next_reap = 0.0
        #: Between jobs: sleeps on the pool's ``wake_ups`` (None: claims every
        #: ``poll_seconds``), beating meanwhile.
        self._idle = IdleWait(settings, store, self.worker_id, self._stop, wake_ups)
        self._guard = AttemptGuard(store, settings, self.worker_id)
        #: With ``commit_behind``, a job's outcome is committed on a thread of its own
        #: while the loop's caller goes on (a Celery delivery returns, so the broker's
        #: acknowledgement, the next message and the next claim overlap the commit); the
        #: next commit, and :meth:`settle`, wait for it.  The lease is renewed until it
        #: is committed, so a process that dies first leaves a job that is retried like
        #: any other.
        self._committer = (
            ThreadPoolExecutor(1, thread_name_prefix="commit") if commit_behind else None
        )
        self._pending: Future[None] | None = None

    def settle(self) -> None:
        """Wait for an outcome still being committed (before the next one is, when
        nothing else is claimable, and at exit)."""
        pending, self._pending = self._pending, None
        if pending is not None:
            pending.result()

    def claim(self) -> Claim | None:
        """The next job in fair order (a cheap one first if this loop prefers them),
        claimed while the previous outcome may still be being committed.  Jobs whose
        lease expired are requeued first, once a heartbeat interval (not before every
        claim: a lease lasts several intervals)."""
        claim = self._claim()
        if claim is None and self._pending is not None:
            # The outcome in flight may be what held the claim back (its job still counts
            # towards its owner's running cap): settle it and look again.
            self.settle()
            claim = self._claim()
        return claim

    def _claim(self) -> Claim | None:
        now = time.monotonic()
        reap = now >= self._next_reap
        claim = self.store.claim_next(
            self.worker_id,
            self.settings.lease_seconds,
            prefer_cheap=self.prefer_cheap,
            max_running_per_owner=self.settings.max_running_per_key,
            reap=reap,
        )
        if reap:
            self._next_reap = now + self.settings.heartbeat_seconds
        return claim

    def request_stop(self) -> None:
        """Stop after the current job, or at once when idle (safe in a signal handler)."""
        self._stop.set()
        self._idle.interrupt()

    def run(self, parent_pid: int | None = None) -> None:
        if not self._register():
            return
        trouble = _Backoff()
        try:
            while not self._stop.is_set():
                if parent_pid is not None and os.getppid() != parent_pid:
                    log.warning("parent process went away; worker %s exits", self.worker_id)
                    return
                try:
                    self._idle.beat_if_due()
                    claim = self._idle.claim_or_sleep(self.claim)
                except StoreUnavailable as exc:
                    log.warning("worker %s: the store is unavailable (%s)", self.worker_id, exc)
                    self._stop.wait(trouble.next_pause())
                    continue
                trouble.reset()
                if claim is not None:
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
        progress = StoreProgress(self.store, job.job_id, claim.lease_token)
        self._guard.watch(claim, time.time() + job.time_limit_s, progress)
        outcome = None
        try:  # the guard renews the lease until the outcome is committed
            definition = self.registry.get(job.process_id)
            if definition is not None and definition.fan_out is not None and job.phase is None:
                self._split(claim, definition)
                return
            outcome = self._run_job(claim, progress)
            self._guard.committing(claim)
        finally:
            if outcome is None:
                self._guard.release(claim)
        if outcome is None:  # it failed, and its failure is recorded
            if job.parent_id is not None:
                self._notify_parent(job.parent_id)
            return
        if self._committer is not None:
            self.settle()  # one outcome in flight at a time
            self._pending = self._committer.submit(self._commit_behind, claim, *outcome)
        else:
            self._commit(claim, *outcome)

    def _commit(self, claim: Claim, result: dict[str, Any], artifacts: Any) -> None:
        """Commit an attempt's outcome, stop guarding it, and send its parent on if it
        was a study's last chunk."""
        try:
            commit_outcome(self.store, claim, result, artifacts, self._give_up_after_s)
        finally:
            self._guard.release(claim)
        if claim.job.parent_id is not None:
            self._notify_parent(claim.job.parent_id)

    def _commit_behind(self, claim: Claim, result: dict[str, Any], artifacts: Any) -> None:
        with log_context(job_id=claim.job.job_id):
            try:
                self._commit(claim, result, artifacts)
            except Exception:  # the lease lapses and the job is retried
                log.exception("job %s: its outcome could not be committed", claim.job.job_id)

    def _split(self, claim: Claim, definition: Any) -> None:
        """A fan-out job's first attempt: its children queued, itself parked (it holds
        no worker while they run; worker.store.fan_out)."""
        job = claim.job
        steps = definition.fan_out
        try:
            inputs = definition.inputs_model.model_validate(job.inputs)
            child = self.registry.get(steps.child_process)
            if child is None:
                raise RuntimeError(f"this worker does not know the process {steps.child_process!r}")
            build = self.settings.build
            scope = job.reuse_scope if job.reuse_scope in ("owner", "all") else None
            children = [
                NewJob(
                    process_id=child.id,
                    inputs=child_inputs,
                    time_limit_s=self.settings.time_limit_for(child.time_limit_s),
                    max_attempts=job.max_attempts,
                    owner=job.owner,
                    parent_id=job.job_id,
                    # a re-run of the study reuses its stored chunks (worker.store.reuse)
                    result_key=result_key(
                        child.id, child.keyed_inputs(child_inputs), child.version, build
                    ),
                    reuse="all" if scope == "all" else ("owner" if scope else None),
                    share=job.shareable,
                )
                for child_inputs in steps.split(inputs)
            ]
            allow_partial = bool(steps.allow_partial(inputs))
        except (Exception, ValidationError) as exc:
            log.exception("job %s could not be split", job.job_id)
            record_failure(self.store, claim, error_document(exc), self._give_up_after_s)
            return
        self._guard.release(claim)  # the split drops the lease: no heartbeat may follow it
        ids = self.store.split(job.job_id, claim.lease_token, children, allow_partial=allow_partial)
        if ids is None:
            log.warning("job %s was lost while it split", job.job_id)
            return
        log.info("job %s split into %d jobs", job.job_id, len(ids))
        if self.on_queued is not None:
            # chunks answered by stored results are not queued; with every chunk so
            # answered, the study itself is queued to assemble
            try:
                statuses = self.store.statuses([*ids, job.job_id])
            except StoreUnavailable:  # tell of them all: a claim of a done job finds none
                self.on_queued([*ids, job.job_id])
                return
            queued = [i for i, s in statuses.items() if s is JobStatus.ACCEPTED]
            if queued:
                self.on_queued(queued)

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

    def _child_file(self, job_id: str, name: str) -> bytes | None:
        """A child job's artifact, for its parent's assembly."""
        artifact = self.store.get_artifact(job_id, name)
        return None if artifact is None else artifact.data

    def _run_job(self, claim: Claim, context: StoreProgress) -> tuple[dict[str, Any], Any] | None:
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
            if definition.fan_out is not None and job.phase == "assembling":
                children = self.store.child_results(job.job_id)
                outcome = definition.fan_out.assemble(inputs, children, self._child_file, context)
            else:
                outcome = definition.run(inputs, context)
        except (Exception, ValidationError) as exc:
            log.exception("job %s raised", job.job_id)
            record_failure(self.store, claim, error_document(exc), self._give_up_after_s)
            return None
        result = dict(outcome.result)
        result["notes"] = list(outcome.all_notes)
        result["paper_errata"] = list(outcome.errata)
        build = self.settings.build
        key = job.result_key or result_key(
            job.process_id, definition.keyed_inputs(job.inputs), definition.version, build
        )
        provenance = provenance_block(
            job.process_id, definition.version, build, self.settings.backend_name(), key
        )
        return stamp_outcome(result, outcome.artifacts, provenance)


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
