"""Waiting for jobs without holding a thread or a store query per waiter.

One :class:`JobWatcher` per API process polls the store for every job someone waits
on, in one query per tick, and wakes the waiters whose job reached a terminal status.
A request held open by ``Prefer: wait=N`` is then an awaiting coroutine: it holds no
threadpool thread, so waiting requests never slow the rest of the API down.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections import defaultdict

from starlette.concurrency import run_in_threadpool

from worker.contract import TERMINAL_STATUSES, JobStatus
from worker.store.base import JobsPort

__all__ = ["JobWatcher"]

log = logging.getLogger("dexlab.service")

#: Job IDs per status query.
_BATCH = 500


class JobWatcher:
    """Wakes coroutines waiting for jobs to finish (start it in the app's lifespan)."""

    def __init__(self, store: JobsPort, interval_s: float = 0.1) -> None:
        self._store = store
        self._interval_s = interval_s
        self._waiters: defaultdict[str, set[asyncio.Future[None]]] = defaultdict(set)
        self._wake = asyncio.Event()
        self._task: asyncio.Task[None] | None = None

    def start(self) -> None:
        self._task = asyncio.get_running_loop().create_task(self._run(), name="job-watcher")

    async def stop(self) -> None:
        if self._task is not None:
            self._task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._task
        for futures in self._waiters.values():
            for future in futures:
                future.cancel()
        self._waiters.clear()

    @property
    def waiting(self) -> int:
        """How many waits are open."""
        return sum(len(f) for f in self._waiters.values())

    async def wait(self, job_id: str, timeout_s: float) -> bool:
        """True once the job is terminal, False after ``timeout_s``."""
        future: asyncio.Future[None] = asyncio.get_running_loop().create_future()
        self._waiters[job_id].add(future)
        self._wake.set()
        try:
            await asyncio.wait_for(future, timeout_s)
            return True
        except TimeoutError:
            return False
        finally:
            futures = self._waiters.get(job_id)
            if futures is not None:
                futures.discard(future)
                if not futures:
                    del self._waiters[job_id]

    async def _run(self) -> None:
        while True:
            if not self._waiters:
                self._wake.clear()
                await self._wake.wait()
            await asyncio.sleep(self._interval_s)
            job_ids = list(self._waiters)
            if not job_ids:
                continue
            statuses: dict[str, JobStatus] = {}
            try:
                for i in range(0, len(job_ids), _BATCH):
                    batch = job_ids[i : i + _BATCH]
                    statuses.update(await run_in_threadpool(self._store.statuses, batch))
            except Exception as exc:  # store trouble: the waiters time out or a later tick
                log.warning("job watcher: the store did not answer (%s)", exc)
                continue
            for job_id, status in statuses.items():
                if status in TERMINAL_STATUSES:
                    for future in self._waiters.get(job_id, ()):
                        if not future.done():
                            future.set_result(None)
