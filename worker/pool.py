"""The local worker pool: N spawned worker processes, watched and replaced when they die.

When a process dies (killed, crashed, or stopped itself after a dismissal or a time
limit) the supervisor expires the leases it held, so its job is retried at once by the
next claim rather than after the lease runs out, and starts a new process in its slot.
"""

from __future__ import annotations

import logging
import multiprocessing
import os
import threading
import time
from multiprocessing.process import BaseProcess

from worker.runner import worker_id_for, worker_main
from worker.settings import WorkerSettings
from worker.store.base import JobStore

__all__ = ["WorkerPool"]

log = logging.getLogger("dexlab.pool")


class WorkerPool:
    """Supervises ``settings.workers`` worker processes (spawn start method)."""

    def __init__(self, settings: WorkerSettings, store: JobStore) -> None:
        self.settings = settings
        self.store = store
        self._ctx = multiprocessing.get_context("spawn")
        self._slots: list[BaseProcess | None] = [None] * settings.workers
        self._restarts = [0] * settings.workers
        self._lock = threading.Lock()
        self._stopping = threading.Event()
        self._monitor: threading.Thread | None = None

    # -- lifecycle ------------------------------------------------------------------
    def start(self) -> None:
        with self._lock:
            for slot in range(len(self._slots)):
                self._slots[slot] = self._spawn(slot)
        self._monitor = threading.Thread(target=self._watch, name="dexlab-pool", daemon=True)
        self._monitor.start()
        log.info("worker pool started with %d process(es)", len(self._slots))

    def stop(self, grace_s: float = 5.0) -> None:
        self._stopping.set()
        if self._monitor is not None:
            self._monitor.join(timeout=5.0)
        with self._lock:
            procs = [p for p in self._slots if p is not None]
            for proc in procs:
                if proc.is_alive():
                    proc.terminate()  # SIGTERM: finish the current job, then exit
            deadline = time.monotonic() + grace_s
            for proc in procs:
                proc.join(timeout=max(0.0, deadline - time.monotonic()))
                if proc.is_alive():
                    proc.kill()
                    proc.join(timeout=5.0)
                self._forget(proc)
            self._slots = [None] * len(self._slots)
        log.info("worker pool stopped")

    # -- state ----------------------------------------------------------------------
    def pids(self) -> list[int]:
        with self._lock:
            return [p.pid for p in self._slots if p is not None and p.pid is not None]

    def alive(self) -> int:
        with self._lock:
            return sum(1 for p in self._slots if p is not None and p.is_alive())

    @property
    def size(self) -> int:
        return len(self._slots)

    # -- internals ------------------------------------------------------------------
    def _spawn(self, slot: int) -> BaseProcess:
        proc = self._ctx.Process(
            target=worker_main,
            args=(self.settings.model_dump(mode="json"), os.getpid()),
            name=f"dexlab-worker-{slot}",
            daemon=False,
        )
        proc.start()
        log.info("started worker process %s in slot %d", proc.pid, slot)
        return proc

    def _forget(self, proc: BaseProcess) -> None:
        if proc.pid is None:
            return
        worker_id = worker_id_for(proc.pid)
        expired = self.store.expire_leases_of(worker_id)
        self.store.unregister_worker(worker_id)
        if expired:
            log.warning("worker %s died holding %d job(s); they will be retried", worker_id,
                        expired)

    def _watch(self) -> None:
        while not self._stopping.wait(0.2):
            with self._lock:
                if self._stopping.is_set():
                    return
                for slot, proc in enumerate(self._slots):
                    if proc is None or proc.is_alive():
                        continue
                    log.warning(
                        "worker process %s in slot %d exited with code %s",
                        proc.pid, slot, proc.exitcode,
                    )
                    try:
                        self._forget(proc)
                    except Exception:  # the store may be briefly unavailable; retry later
                        log.exception("could not release the leases of process %s", proc.pid)
                        continue
                    self._restarts[slot] += 1
                    self._slots[slot] = self._spawn(slot)
