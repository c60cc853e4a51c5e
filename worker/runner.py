"""One worker process: claim a job, run it under a lease, store the outcome, repeat.

While a job runs, a guard thread renews the lease.  It stops the whole process
(``os._exit``) when the job is dismissed, when another attempt took the job over, or
when the job's time limit passes (after recording the failure); the pool then starts
a fresh process in its place.
"""

from __future__ import annotations

import logging
import os
import signal
import socket
import threading
import time
import traceback
from typing import Any

from pydantic import ValidationError

from worker.contract import JobStatus
from worker.processes import ProcessRegistry, default_registry
from worker.progress import StoreProgress
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.store.base import Claim, JobStore

__all__ = ["AttemptGuard", "WorkerLoop", "worker_id_for", "worker_main"]

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
        job = self._claim.job
        interval = self._settings.heartbeat_seconds
        while not self._done.wait(max(0.05, min(interval, self._deadline - time.time()))):
            if time.time() >= self._deadline:
                self._store.fail(
                    job.job_id,
                    self._claim.lease_token,
                    {
                        "type": "time-limit-exceeded",
                        "title": "Time limit exceeded",
                        "detail": (
                            f"Attempt {job.attempts} exceeded the job's time limit of "
                            f"{job.time_limit_s:g} s and was stopped."
                        ),
                    },
                )
                log.warning("job %s exceeded its time limit; stopping", job.job_id)
                os._exit(EXIT_TIME_LIMIT)
            ack = self._store.heartbeat(
                job.job_id, self._claim.lease_token, self._settings.lease_seconds
            )
            self._store.worker_heartbeat(self._worker_id)
            if not ack.owner:
                dismissed = ack.status is JobStatus.DISMISSED
                log.warning(
                    "job %s %s; stopping this process",
                    job.job_id,
                    "was dismissed" if dismissed else "is no longer ours",
                )
                os._exit(EXIT_DISMISSED if dismissed else EXIT_LEASE_LOST)


class WorkerLoop:
    """Claims and runs jobs until told to stop or orphaned by its parent."""

    def __init__(
        self, settings: WorkerSettings, store: JobStore, registry: ProcessRegistry
    ) -> None:
        self.settings = settings
        self.store = store
        self.registry = registry
        self.worker_id = worker_id_for(os.getpid())
        self._stop = threading.Event()

    def request_stop(self) -> None:
        self._stop.set()

    def run(self, parent_pid: int | None = None) -> None:
        self.store.register_worker(self.worker_id, socket.gethostname(), os.getpid())
        last_beat = time.monotonic()
        try:
            while not self._stop.is_set():
                if parent_pid is not None and os.getppid() != parent_pid:
                    log.warning("parent process went away; worker %s exits", self.worker_id)
                    return
                if time.monotonic() - last_beat >= self.settings.heartbeat_seconds:
                    self.store.worker_heartbeat(self.worker_id)
                    last_beat = time.monotonic()
                claim = self.store.claim_next(self.worker_id, self.settings.lease_seconds)
                if claim is None:
                    self._stop.wait(self.settings.poll_seconds)
                    continue
                self.execute(claim)
        finally:
            self.store.unregister_worker(self.worker_id)

    def execute(self, claim: Claim) -> None:
        job = claim.job
        token = claim.lease_token
        log.info("worker %s runs job %s (attempt %d)", self.worker_id, job.job_id, job.attempts)
        deadline = time.time() + job.time_limit_s
        guard = AttemptGuard(self.store, claim, self.settings, self.worker_id, deadline)
        guard.start()
        try:
            outcome = self._run_job(claim)
        finally:
            guard.stop()
        if outcome is None:
            return
        result, artifacts = outcome
        try:
            stored = self.store.complete(job.job_id, token, result, artifacts)
        except (TypeError, ValueError) as exc:  # e.g. a NaN in the result document
            log.exception("job %s produced an unstorable result", job.job_id)
            self.store.fail(job.job_id, token, _error_document(exc))
            return
        if not stored:
            log.warning("job %s: result discarded, the attempt no longer owns it", job.job_id)

    def _run_job(self, claim: Claim) -> tuple[dict[str, Any], Any] | None:
        job = claim.job
        definition = self.registry.get(job.process_id)
        if definition is None:
            self.store.fail(
                job.job_id,
                claim.lease_token,
                {
                    "type": "no-such-process",
                    "title": "Unknown process",
                    "detail": f"This worker does not know the process {job.process_id!r}.",
                },
            )
            return None
        try:
            inputs = definition.inputs_model.model_validate(job.inputs)
            context = StoreProgress(self.store, job.job_id, claim.lease_token)
            context.report_progress(0.0, "started")
            outcome = definition.run(inputs, context)
        except (Exception, ValidationError) as exc:
            log.exception("job %s raised", job.job_id)
            self.store.fail(job.job_id, claim.lease_token, _error_document(exc))
            return None
        result = dict(outcome.result)
        result["notes"] = list(outcome.notes)
        return result, list(outcome.artifacts)


def _error_document(exc: BaseException) -> dict[str, Any]:
    return {
        "type": "job-error",
        "title": "The job raised an error",
        "detail": f"{type(exc).__name__}: {exc}",
        "traceback": traceback.format_exception(exc)[-5:],
    }


def worker_main(settings_data: dict[str, Any], parent_pid: int | None = None) -> None:
    """Entry point of a pool process (spawned): build resources, then loop."""
    logging.basicConfig(
        level=logging.INFO, format="%(asctime)s %(process)d %(name)s %(levelname)s %(message)s"
    )
    settings = WorkerSettings.model_validate(settings_data)
    store = open_store(settings.resolved_store_url())
    loop = WorkerLoop(settings, store, default_registry())
    signal.signal(signal.SIGTERM, lambda *_: loop.request_stop())
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the supervisor decides when we stop
    loop.run(parent_pid=parent_pid)
