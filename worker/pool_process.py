"""The entry point of a local pool's worker process, and the lower scheduling priority
every worker process runs at.

Worker processes run at a lower scheduling priority than the API
(:func:`lower_priority`), so requests stay quick while every core runs jobs.  A pool
process beats in its slot of the supervisor's liveness board twice a second from a
thread of its own, whatever the job does, so a frozen (e.g. SIGSTOPped) process is
found and killed (:mod:`worker.liveness`).  Idle, it sleeps on its pool's wake-up
socket, and it wakes the local pools itself when it queues jobs (a study's chunks, a
study to assemble; :mod:`worker.dispatch.wake_ups`).
"""

from __future__ import annotations

import logging
import os
import signal
import socket
import sys
from typing import Any

from worker.dispatch.wake_ups import WakeUpListener, WakeUpSender, wake_up_dir
from worker.liveness import LivenessBoard
from worker.logs import LogFormat, configure_logging
from worker.registry import worker_registry
from worker.runner import WorkerLoop
from worker.settings import WorkerSettings
from worker.store import open_store

__all__ = ["EXIT_STARTUP", "lower_priority", "worker_main"]

log = logging.getLogger("dexlab.worker")


#: Exit code of a worker process that could not start (e.g. the store cannot be opened).
EXIT_STARTUP = 6


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
    liveness: tuple[LivenessBoard, int] | None = None,
    log_as: tuple[LogFormat, int] = ("text", logging.INFO),
    prefer_cheap: bool = False,
    wake_up_socket: socket.socket | None = None,
) -> None:
    """Entry point of a pool process (spawned): beat in its ``(board, slot)``, lower
    its priority, build resources, then loop (taking cheap jobs first with
    ``prefer_cheap``; idle, sleeping on the pool's ``wake_up_socket``).  It logs as its
    supervisor does: ``log_as`` is the supervisor's ``(format, level)``.  It reads no
    environment: ``settings_data`` is the supervisor's worker settings."""
    log_format, log_level = log_as
    configure_logging(log_format, level=log_level)
    if liveness is not None:
        board, slot = liveness
        board.start_beating(slot)
    settings = WorkerSettings.model_validate(settings_data)
    lower_priority(settings.worker_nice, f"worker process {os.getpid()}")
    try:
        store = open_store(settings.resolved_store_url(), retry_s=settings.store_retry_seconds)
    except Exception as exc:  # the supervisor backs off and says why
        log.error("worker process %d cannot open the job store: %s", os.getpid(), exc)
        sys.exit(EXIT_STARTUP)
    sender = WakeUpSender(wake_up_dir(settings.resolved_store_url()))
    loop = WorkerLoop(
        settings,
        store,
        worker_registry(),
        prefer_cheap=prefer_cheap,
        on_queued=sender.wake_for,
        wake_ups=None if wake_up_socket is None else WakeUpListener(wake_up_socket),
    )
    signal.signal(signal.SIGTERM, lambda *_: loop.request_stop())
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the supervisor decides when we stop
    loop.run(parent_pid=parent_pid)
