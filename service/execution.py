"""Submitting a job and waiting for it, shared by the native and the OGC execute routes.

A submit is blocking store work (run it in the threadpool); a synchronous answer then
waits for the job without holding a thread: the app's :class:`JobWatcher` wakes the
request when the job is done, and the wait ends as soon as the client goes away.
"""

from __future__ import annotations

import asyncio
from collections.abc import Mapping
from typing import Any

from fastapi import Request

from service.job_watcher import JobWatcher
from service.ogc.execute_request import InvalidRequest
from worker.contract import JobRecord
from worker.dispatch import Dispatcher
from worker.processes import ProcessRegistry
from worker.settings import WorkerSettings
from worker.store.base import JobStore
from worker.submission import submit_request

__all__ = [
    "RETENTION_FIELD",
    "check_retention",
    "no_cache",
    "submit_job",
    "wait_while_connected",
]

#: The execute body's member (beside ``inputs``, in /v1 and OGC bodies) that asks for a
#: shorter retention than the service's.
RETENTION_FIELD = "retention_s"


def no_cache(cache_control: str | None) -> bool:
    """Whether a ``Cache-Control`` request header says ``no-cache`` (as ``"reuse":
    false`` does: compute afresh)."""
    if not cache_control:
        return False
    directives = (part.strip().split("=", 1)[0].lower() for part in cache_control.split(","))
    return "no-cache" in directives


def check_retention(settings: WorkerSettings, retention_s: float | None) -> None:
    """A requested retention must not exceed the service's (``DEXLAB_RESULT_TTL_S``);
    the models already refuse one that is not a positive number."""
    if retention_s is not None and retention_s > settings.result_ttl_s:
        raise InvalidRequest(
            [
                {
                    "field": RETENTION_FIELD,
                    "message": f"Input should be at most {settings.result_ttl_s:g}, the "
                    "longest this service keeps a finished job (DEXLAB_RESULT_TTL_S)",
                    "type": "less_than_equal",
                }
            ]
        )


def submit_job(
    store: JobStore,
    registry: ProcessRegistry,
    settings: WorkerSettings,
    process_id: str,
    inputs: Mapping[str, Any],
    idempotency_key: str | None,
    dispatcher: Dispatcher,
    wants_sync: bool,
    owner: str = "",
    retention_s: float | None = None,
    reuse: bool = True,
    share: bool = True,
) -> tuple[JobRecord, bool, bool]:
    """Submit a job owned by ``owner``, kept ``retention_s`` once finished (None: the
    service's retention) (blocking store work, run in the threadpool); ``(job, created,
    sync)``: ``sync`` when the client asked for a synchronous answer and the process
    allows one for these inputs (its ``sync_cost_limit``, as the submission priced
    them: the inputs are validated and priced once), or the job was answered at once by
    a stored result (whatever its cost: ``reuse``, ``share``: worker.submission)."""
    check_retention(settings, retention_s)
    submission = submit_request(
        store, registry, settings, process_id, inputs, idempotency_key, dispatcher, owner,
        retention_s, reuse=reuse, share=share,
    )  # fmt: skip
    return (
        submission.job,
        submission.created,
        wants_sync and (submission.cheap or submission.reused),
    )


async def wait_while_connected(
    request: Request, watcher: JobWatcher, job_id: str, wait_s: float
) -> bool:
    """Wait for the job as the watcher does, but stop as soon as the client goes away
    (an abandoned wait must not keep the request, nor the server's shutdown, open).
    True once the job is finished."""
    finished = asyncio.ensure_future(watcher.wait(job_id, wait_s))
    gone = asyncio.ensure_future(_disconnected(request))
    try:
        await asyncio.wait({finished, gone}, return_when=asyncio.FIRST_COMPLETED)
    finally:
        for task in (finished, gone):
            task.cancel()
        await asyncio.gather(finished, gone, return_exceptions=True)
    return finished.done() and not finished.cancelled() and finished.result()


async def _disconnected(request: Request) -> None:
    """Return once the client has closed the connection (the body is already read)."""
    while (await request.receive())["type"] != "http.disconnect":
        pass
