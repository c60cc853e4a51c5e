"""The watch over worker processes, on real processes: a frozen one (SIGSTOPped, or
stuck in a call that holds the GIL) is killed after the threshold and not before; an
idle one, and one busy in code that holds the GIL (it cannot beat, but it uses CPU
time), are left alone."""

from __future__ import annotations

import ctypes
import multiprocessing
import os
import signal
import time
from contextlib import suppress

import pytest

from worker.liveness import FrozenWatch, LivenessBoard, Watchdog, frozen_after_s
from worker.settings import WorkerSettings

pytestmark = pytest.mark.slow

FROZEN_AFTER_S = 1.5
BUSY_S = 4.0
IDLE, STOPPED, STUCK, BUSY = range(4)


def _child(board: LivenessBoard, slot: int) -> None:
    """A worker process that beats, then idles, or holds the GIL (busy, or stuck)."""
    board.start_beating(slot)
    while board.read(slot)[1] < 1:  # the first beat, before the GIL is held
        time.sleep(0.01)
    if slot == BUSY:
        started = time.process_time()  # CPU time: at least as long in wall time
        sum(range(5_000_000))
        rate = 5_000_000 / (time.process_time() - started)
        sum(range(int(rate * BUSY_S)))  # one C call: the GIL is held throughout
    elif slot == STUCK:
        ctypes.PyDLL(None).sleep(60)  # a C call that keeps the GIL, running nothing
    time.sleep(60)


def _stalls(board: LivenessBoard, slot: int, seen: dict[int, tuple[float, float]]) -> float:
    """How long the slot's beat count has stayed as it is (seconds), noting it."""
    beats = board.read(slot)[1]
    now = time.monotonic()
    if slot not in seen or seen[slot][0] != beats:
        seen[slot] = (beats, now)
    return now - seen[slot][1]


def test_frozen_processes_are_killed_and_busy_or_idle_ones_are_not() -> None:
    ctx = multiprocessing.get_context("spawn")
    board = LivenessBoard(4, ctx)
    children = [ctx.Process(target=_child, args=(board, slot), daemon=True) for slot in range(4)]
    for child in children:
        child.start()
    watchdog = Watchdog(board, FROZEN_AFTER_S)
    try:
        deadline = time.monotonic() + 30
        while any(board.read(slot)[1] < 1 for slot in range(4)):  # every child beats
            assert time.monotonic() < deadline, "the children never started beating"
            time.sleep(0.02)
        watchdog.start()
        pid = children[STOPPED].pid
        assert pid is not None
        os.kill(pid, signal.SIGSTOP)
        stopped_at = time.monotonic()
        died_after: dict[int, float] = {}
        seen: dict[int, tuple[float, float]] = {}
        longest_stall = 0.0
        while time.monotonic() - stopped_at < BUSY_S + 1.0:
            for slot, child in enumerate(children):
                if slot not in died_after and not child.is_alive():
                    died_after[slot] = time.monotonic() - stopped_at
            longest_stall = max(longest_stall, _stalls(board, BUSY, seen))
            time.sleep(0.05)
    finally:
        watchdog.stop()
        for child in children:
            with suppress(ProcessLookupError):
                if child.pid is not None:
                    os.kill(child.pid, signal.SIGKILL)
            child.join(5)
    assert set(died_after) == {STOPPED, STUCK}, died_after
    assert FROZEN_AFTER_S <= died_after[STOPPED] < FROZEN_AFTER_S + 1.5, died_after
    assert children[STOPPED].exitcode == children[STUCK].exitcode == -signal.SIGKILL
    # The busy child held the GIL (its beats stopped) longer than the threshold.
    assert longest_stall > FROZEN_AFTER_S + 0.5, longest_stall


def test_silence_the_watch_did_not_see_is_not_counted() -> None:
    """A supervisor that was itself stopped (a whole machine paused, then resumed) does
    not kill a process on its first look after: it counts the silence from there."""
    ctx = multiprocessing.get_context("spawn")
    board = LivenessBoard(1, ctx)
    child = ctx.Process(target=_child, args=(board, IDLE), daemon=True)
    child.start()
    try:
        deadline = time.monotonic() + 30
        while board.read(IDLE)[1] < 1:
            assert time.monotonic() < deadline, "the child never started beating"
            time.sleep(0.02)
        watch = FrozenWatch(board, frozen_after_s=1.0)
        assert child.pid is not None
        os.kill(child.pid, signal.SIGSTOP)
        assert watch.kill_if_frozen(IDLE) is None
        time.sleep(1.5)  # the supervisor is not looking: "paused" with its processes
        resumed_at = time.monotonic()
        while watch.kill_if_frozen(IDLE) is None:
            assert time.monotonic() - resumed_at < 5, "never killed"
            time.sleep(0.05)
        assert time.monotonic() - resumed_at >= 1.0
        child.join(5)
        assert child.exitcode == -signal.SIGKILL
    finally:
        with suppress(ProcessLookupError):
            if child.pid is not None:
                os.kill(child.pid, signal.SIGKILL)
        child.join(5)


def test_frozen_after_is_a_lease_and_at_least_two_seconds() -> None:
    assert frozen_after_s(WorkerSettings(lease_seconds=15)) == 15
    assert frozen_after_s(WorkerSettings(lease_seconds=0.5)) == 2.0
