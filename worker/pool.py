"""The local worker pool: N spawned worker processes, watched and replaced when they die.

When a process dies (killed, crashed, or stopped itself after a dismissal or a time
limit) the supervisor expires the leases it held, so its job is retried at once by the
next claim rather than after the lease runs out, and starts a new process in its slot.
A process that shows no sign of life for a lease (no beat, no CPU time: frozen, e.g.
SIGSTOPped, perhaps holding SQLite's write lock; :mod:`worker.liveness`) is killed.
A process that keeps dying at start-up (a broken store) is restarted after growing
pauses (capped), and the log says why.

The supervisor binds the pool's wake-up socket, which its idle processes sleep on
(:mod:`worker.dispatch.wake_ups`), and wakes the pools when a dead process's jobs are
queued for a retry.

The process in slot 0 prefers cheap jobs (:mod:`worker.store.scheduling`), so small
jobs are not starved by expensive ones; every process runs at a lower scheduling
priority than the supervisor and the API (``DEXLAB_WORKER_NICE``).  The supervisor also
runs the retention sweeper (:mod:`worker.retention`).
"""

from __future__ import annotations

import logging
import multiprocessing
import os
import threading
import time
from dataclasses import dataclass, field
from multiprocessing.process import BaseProcess

from worker.dispatch.wake_ups import PoolWakeUps, WakeUpSender, wake_up_dir
from worker.errors import StoreUnavailable
from worker.liveness import FrozenWatch, LivenessBoard, frozen_after_s
from worker.logs import current_log_format
from worker.pool_process import EXIT_STARTUP, worker_main
from worker.retention import RetentionSweeper
from worker.runner import worker_id_for
from worker.settings import WorkerSettings
from worker.store.base import JobStore

__all__ = ["WorkerPool"]

log = logging.getLogger("dexlab.pool")

#: A process that dies sooner than this after its start died "at start-up".
EARLY_DEATH_S = 10.0
#: Restart pauses after repeated early deaths: 0.5 s, 1 s, 2 s, ... at most 30 s.
FIRST_BACKOFF_S = 0.5
MAX_BACKOFF_S = 30.0


@dataclass
class _Slot:
    """One place in the pool: its process, when it started, its restarts."""

    proc: BaseProcess | None = None
    started: float = 0.0
    early_deaths: int = 0
    next_start: float = 0.0
    restarts: int = 0
    unreleased: list[str] = field(default_factory=list)


class WorkerPool:
    """Supervises ``settings.workers`` worker processes (spawn start method)."""

    def __init__(self, settings: WorkerSettings, store: JobStore) -> None:
        self.settings = settings
        self.store = store
        self._ctx = multiprocessing.get_context("spawn")
        self._slots = [_Slot() for _ in range(settings.workers)]
        self._board = LivenessBoard(settings.workers, self._ctx)
        self._frozen = FrozenWatch(self._board, frozen_after_s(settings))
        self._lock = threading.Lock()
        self._stopping = threading.Event()
        self._monitor: threading.Thread | None = None
        self._retention: RetentionSweeper | None = None
        self._wake_dir = wake_up_dir(settings.resolved_store_url())
        self._wake_ups: PoolWakeUps | None = None
        self._waker = WakeUpSender(self._wake_dir)

    # -- lifecycle ------------------------------------------------------------------
    def start(self) -> None:
        self._wake_ups = PoolWakeUps.bind(self._wake_dir)
        with self._lock:
            for index in range(len(self._slots)):
                self._spawn(index)
        self._monitor = threading.Thread(target=self._watch, name="dexlab-pool", daemon=True)
        self._monitor.start()
        self._retention = RetentionSweeper(self.settings, self.store)
        self._retention.start()
        log.info(
            "worker pool started with %d process(es); idle, they wake on %s or look for work "
            "every %g s",
            len(self._slots),
            "nothing" if self._wake_ups is None else self._wake_ups.path,
            self.settings.poll_seconds,
        )

    def stop(self, grace_s: float = 5.0) -> None:
        self._stopping.set()
        if self._retention is not None:
            self._retention.stop()
        if self._monitor is not None:
            self._monitor.join(timeout=5.0)
        with self._lock:
            procs = [s.proc for s in self._slots if s.proc is not None]
            for proc in procs:
                if proc.is_alive():
                    proc.terminate()  # SIGTERM: finish the current job, then exit
            deadline = time.monotonic() + grace_s
            for proc in procs:
                proc.join(timeout=max(0.0, deadline - time.monotonic()))
                if proc.is_alive():
                    proc.kill()
                    proc.join(timeout=5.0)
                self._release(worker_id_for(proc.pid) if proc.pid else None)
            for slot in self._slots:
                slot.proc = None
        if self._wake_ups is not None:
            self._wake_ups.close()
            self._wake_ups = None
        self._waker.close()
        log.info("worker pool stopped")

    # -- state ----------------------------------------------------------------------
    def pids(self) -> list[int]:
        with self._lock:
            return [s.proc.pid for s in self._slots if s.proc is not None and s.proc.pid]

    def alive(self) -> int:
        with self._lock:
            return sum(1 for s in self._slots if s.proc is not None and s.proc.is_alive())

    @property
    def size(self) -> int:
        return len(self._slots)

    # -- internals ------------------------------------------------------------------
    def _spawn(self, index: int) -> None:
        slot = self._slots[index]
        proc = self._ctx.Process(
            target=worker_main,
            args=(
                # The worker section only (the tree's other sections hold secrets).
                self.settings.model_dump(mode="json", include=set(WorkerSettings.model_fields)),
                os.getpid(),
                (self._board, index),
                (current_log_format(), logging.getLogger().getEffectiveLevel()),
                index == 0,  # the slot that prefers cheap jobs
                None if self._wake_ups is None else self._wake_ups.sock,
            ),
            name=f"dexlab-worker-{index}",
            daemon=False,
        )
        proc.start()
        assert proc.pid is not None
        self._board.enter(index, proc.pid)  # watched from now, before its first beat
        slot.proc = proc
        slot.started = time.monotonic()
        log.info("started worker process %s in slot %d", proc.pid, index)

    def _release(self, worker_id: str | None) -> bool:
        """Expire the leases a dead process held; False if the store did not answer."""
        if worker_id is None:
            return True
        try:
            expired = self.store.expire_leases_of(worker_id)
            self.store.unregister_worker(worker_id)
        except StoreUnavailable as exc:
            log.warning("could not release the leases of %s yet: %s", worker_id, exc)
            return False
        if expired:
            log.warning(
                "worker %s died holding %d job(s); they will be retried", worker_id, expired
            )
            self._waker.wake(expired)
        return True

    def _on_exit(self, index: int, slot: _Slot) -> None:
        proc = slot.proc
        assert proc is not None
        lived = time.monotonic() - slot.started
        early = lived < EARLY_DEATH_S
        slot.early_deaths = slot.early_deaths + 1 if early else 0
        slot.restarts += 1
        if proc.pid is not None:
            slot.unreleased.append(worker_id_for(proc.pid))
        pause = 0.0
        if slot.early_deaths > 1:
            pause = min(FIRST_BACKOFF_S * 2 ** (slot.early_deaths - 2), MAX_BACKOFF_S)
        why = (
            "could not start (see its log)"
            if proc.exitcode == EXIT_STARTUP
            else (f"exited with code {proc.exitcode} after {lived:.1f} s")
        )
        if pause:
            log.error(
                "worker process %s in slot %d %s; %d early deaths in a row, next start in %.1f s",
                proc.pid,
                index,
                why,
                slot.early_deaths,
                pause,
            )
        else:
            log.warning("worker process %s in slot %d %s", proc.pid, index, why)
        slot.proc = None
        slot.next_start = time.monotonic() + pause

    def _watch(self) -> None:
        while not self._stopping.wait(0.2):
            with self._lock:
                if self._stopping.is_set():
                    return
                for index, slot in enumerate(self._slots):
                    if slot.proc is not None and slot.proc.is_alive():
                        self._frozen.kill_if_frozen(index)
                        continue
                    if slot.proc is not None:
                        self._on_exit(index, slot)
                    slot.unreleased = [w for w in slot.unreleased if not self._release(w)]
                    if slot.proc is None and time.monotonic() >= slot.next_start:
                        self._spawn(index)
