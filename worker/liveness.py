"""Signs of life of worker processes, and the watch that kills a frozen one.

A supervisor (the local pool's, or ``dexlab worker``'s Celery main process) makes a
:class:`LivenessBoard` before its worker processes start: shared memory with a place
per slot of the pool.  Each worker process beats in its place from a thread of its
own, twice a second, whatever its job does (:meth:`LivenessBoard.start_beating`).

The supervisor's :class:`FrozenWatch` counts as a sign of life a beat, or CPU time the
process used (``/proc/PID/stat``, where there is one) since its last look.  A job busy
in numerical code that holds the GIL for long stops the beats but uses CPU time, so it
is left alone; a frozen process (SIGSTOPped, or stuck without running at all) shows
neither, and after ``frozen_after_s`` (a lease, at least 2 s: the guard thread's lease
renewals stopped as long ago) it is SIGKILLed.  Its pool then starts a new process in
its place (the local pool's supervisor, or billiard under Celery, whose message goes
back to the queue), and the job it held is retried, its lease having lapsed.

Only silence the watch saw counts: a look that comes more than half the threshold
after the previous one (the supervisor itself was stopped or starved, e.g. a whole
machine paused and resumed with its processes) starts counting afresh, so a machine
that resumes does not kill its processes before they could beat.
"""

from __future__ import annotations

import ctypes
import logging
import multiprocessing
import os
import signal
import threading
import time
from contextlib import suppress
from dataclasses import dataclass
from multiprocessing.context import BaseContext
from pathlib import Path

from worker.settings import WorkerSettings

__all__ = ["BEAT_INTERVAL_S", "FrozenWatch", "LivenessBoard", "Watchdog", "frozen_after_s"]

log = logging.getLogger("dexlab.pool")

#: How often a worker process beats (seconds).
BEAT_INTERVAL_S = 0.5
#: How often :class:`Watchdog` looks at every process (seconds).
LOOK_INTERVAL_S = 0.25


def frozen_after_s(settings: WorkerSettings) -> float:
    """How long a worker process may show no sign of life before it is killed: a
    lease (its lease renewals stopped as long), at least 2 s (four beats)."""
    return max(settings.lease_seconds, 2.0)


class LivenessBoard:
    """Per slot, the process in it (its pid) and its count of beats, in shared memory.

    Made by the supervisor before its processes start (handed to a spawned process as
    an argument; a forked one inherits it).  A process :meth:`enters <enter>` its slot
    (the local pool's supervisor enters a process it started at once, so that one
    frozen before its first beat is watched too); then only that process writes there.
    """

    def __init__(self, slots: int, context: BaseContext | None = None) -> None:
        ctx = context if context is not None else multiprocessing.get_context()
        self._cells = ctx.RawArray(ctypes.c_double, 2 * slots)
        self.slots = slots

    def enter(self, slot: int, pid: int) -> None:
        """``pid`` is the process in ``slot`` from now on."""
        self._cells[2 * slot] = float(pid)

    def read(self, slot: int) -> tuple[int, float]:
        """``(pid, beats)`` of ``slot`` (pid 0: nobody entered it yet)."""
        return int(self._cells[2 * slot]), float(self._cells[2 * slot + 1])

    def start_beating(self, slot: int) -> None:
        """In a worker process: enter ``slot`` and beat in it every
        :data:`BEAT_INTERVAL_S` from a thread of its own (for the process's life)."""
        self.enter(slot, os.getpid())
        threading.Thread(
            target=self._beat_forever, args=(slot,), name="liveness", daemon=True
        ).start()

    def _beat_forever(self, slot: int) -> None:
        pid = float(os.getpid())
        while True:
            self._cells[2 * slot] = pid
            self._cells[2 * slot + 1] += 1.0
            time.sleep(BEAT_INTERVAL_S)


def _stat(pid: int) -> tuple[str, int] | None:
    """``(state letter, CPU clock ticks used)`` of a process from ``/proc/PID/stat``;
    None when it is gone."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            fields = f.read().rsplit(b")", 1)[1].split()
    except (FileNotFoundError, ProcessLookupError, IndexError):
        return None
    # Fields 3 (state), 14 and 15 (utime, stime) of proc(5), counted after the name.
    return fields[0].decode(), int(fields[11]) + int(fields[12])


@dataclass
class _Seen:
    """What the watch saw of a slot's process, and when it last showed life."""

    pid: int
    beats: float
    cpu_ticks: int | None
    since: float
    looked: float


class FrozenWatch:
    """A supervisor's look at its processes: how long each has shown no sign of life,
    and the kill of a frozen one.  One thread uses it."""

    def __init__(self, board: LivenessBoard, frozen_after_s: float) -> None:
        self.board = board
        self.frozen_after_s = frozen_after_s
        self._seen: dict[int, _Seen] = {}
        self._killed: set[int] = set()
        self._has_proc = Path("/proc/self/stat").exists()

    def silence(self, slot: int) -> tuple[int, float] | None:
        """``(pid, seconds without a sign of life)`` of the process in ``slot``; None
        when the slot is empty or its process is gone (or killed by this watch)."""
        pid, beats = self.board.read(slot)
        if pid <= 0 or pid in self._killed:
            return None
        cpu_ticks = None
        if self._has_proc:
            stat = _stat(pid)
            if stat is None or stat[0] in ("Z", "X"):  # gone, or dead awaiting its wait()
                return None
            cpu_ticks = stat[1]
        now = time.monotonic()
        seen = self._seen.get(slot)
        if (
            seen is None
            or seen.pid != pid
            or seen.beats != beats
            or (cpu_ticks is not None and cpu_ticks != seen.cpu_ticks)
            or now - seen.looked > self.frozen_after_s / 2  # the watch was not looking
        ):
            self._seen[slot] = _Seen(pid, beats, cpu_ticks, since=now, looked=now)
            return pid, 0.0
        seen.looked = now
        return pid, now - seen.since

    def kill_if_frozen(self, slot: int) -> int | None:
        """SIGKILL the process in ``slot`` if it showed no sign of life for
        ``frozen_after_s``; its pid if it did."""
        silence = self.silence(slot)
        if silence is None or silence[1] <= self.frozen_after_s:
            return None
        pid, silent_s = silence
        log.error(
            "worker process %s in slot %d showed no sign of life (no beat, no CPU time) "
            "for %.1f s (frozen?); killing it",
            pid,
            slot,
            silent_s,
        )
        with suppress(ProcessLookupError):
            os.kill(pid, signal.SIGKILL)
        self._killed = {p for p in self._killed if p in self._pids()} | {pid}
        self._seen.pop(slot, None)
        return pid

    def _pids(self) -> set[int]:
        return {self.board.read(slot)[0] for slot in range(self.board.slots)}


class Watchdog(threading.Thread):
    """Kills the frozen processes of a board, looking every :data:`LOOK_INTERVAL_S`
    (for a pool that replaces its dead processes itself: Celery's prefork pool)."""

    def __init__(self, board: LivenessBoard, frozen_after_s: float) -> None:
        super().__init__(name="dexlab-watchdog", daemon=True)
        self._watch = FrozenWatch(board, frozen_after_s)
        self._stopping = threading.Event()

    def run(self) -> None:
        while not self._stopping.wait(LOOK_INTERVAL_S):
            for slot in range(self._watch.board.slots):
                try:
                    self._watch.kill_if_frozen(slot)
                except Exception:  # keep watching the other processes
                    log.exception("could not look at the worker process in slot %d", slot)

    def stop(self) -> None:
        self._stopping.set()
        self.join(timeout=5.0)
