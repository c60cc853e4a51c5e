"""``GET /v1/jobs/{jobID}/events``: a job's progress as Server-Sent Events.

The stream opens with a ``retry:`` hint, then sends a ``progress`` event (JSON
:class:`service.schemas.ProgressEvent`: ``{"status", "progress", "message"}``) at once
and whenever one of them changes, read from the store at most every
``DEXLAB_EVENT_POLL_SECONDS``.  It ends after the event of a terminal status
(``successful``, ``failed``, ``dismissed``), when the client goes away, or after
``DEXLAB_EVENT_STREAM_SECONDS`` (the browser then reconnects).  Between reads it
sleeps as a coroutine, so an open stream holds no threadpool thread; a comment line
every 15 s keeps proxies from closing a quiet stream.  The OpenAPI document describes
each event (:mod:`service.openapi_streams`).
"""

from __future__ import annotations

import logging
import time
from collections.abc import AsyncIterator

import anyio
from fastapi import APIRouter
from fastapi.responses import StreamingResponse
from starlette.concurrency import run_in_threadpool

from service.deps import ApiDep
from service.job_lookup import find_job
from service.schemas import ProgressEvent
from worker.contract import TERMINAL_STATUSES, JobRecord
from worker.errors import StoreUnavailable
from worker.store.base import JobStore

__all__ = ["EVENT_STREAM", "router"]

log = logging.getLogger("dexlab.service")

EVENT_STREAM = "text/event-stream"

#: How long a browser waits before it reconnects to an ended stream (milliseconds).
RETRY_MS = 2000
#: A comment line after this long without an event.
KEEPALIVE_S = 15.0

router = APIRouter(prefix="/v1/jobs", tags=["jobs"])


def _state(job: JobRecord) -> tuple[str, int, str]:
    return job.status.value, round(job.progress), job.message


def _event(state: tuple[str, int, str]) -> str:
    status, progress, message = state
    data = ProgressEvent.model_validate(
        {"status": status, "progress": progress, "message": message}
    ).model_dump_json()
    return f"event: progress\ndata: {data}\n\n"


def _read(store: JobStore, job_id: str) -> JobRecord | None:
    try:
        return store.get_job(job_id)
    except StoreUnavailable as exc:  # a locked or restarting store: try the next tick
        log.warning("progress stream of %s: the store did not answer (%s)", job_id, exc)
        return None


async def _events(
    store: JobStore, job: JobRecord, poll_s: float, lifetime_s: float
) -> AsyncIterator[str]:
    """The stream of one job (the route checks that the job exists first)."""
    yield f"retry: {RETRY_MS}\n\n"
    state = _state(job)
    yield _event(state)
    if job.status in TERMINAL_STATUSES:
        return
    started = last_sent = time.monotonic()
    while time.monotonic() - started < lifetime_s:
        await anyio.sleep(poll_s)
        current = await run_in_threadpool(_read, store, job.job_id)
        if current is not None and _state(current) != state:
            state = _state(current)
            last_sent = time.monotonic()
            yield _event(state)
            if current.status in TERMINAL_STATUSES:
                return
        elif time.monotonic() - last_sent >= KEEPALIVE_S:
            last_sent = time.monotonic()
            yield ": still running\n\n"


@router.get(
    "/{job_id}/events",
    summary="Follow a job's progress (Server-Sent Events)",
    response_class=StreamingResponse,
    responses={
        200: {
            "description": "`progress` events (JSON `{status, progress, message}`) until "
            "the job ends; a `retry:` hint first.",
            "content": {EVENT_STREAM: {"schema": {"type": "string"}}},  # see service.openapi
        }
    },
)
async def job_events(job_id: str, api: ApiDep) -> StreamingResponse:
    """``progress`` events until the job ends (see the module docstring); a browser's
    EventSource sends its session cookie."""
    job = await run_in_threadpool(find_job, api.store, job_id, api.identity.owner_scope)
    settings = api.pages.settings
    return StreamingResponse(
        _events(api.store, job, settings.event_poll_seconds, settings.event_stream_seconds),
        media_type=EVENT_STREAM,
        headers={"Cache-Control": "no-cache", "X-Accel-Buffering": "no"},
    )
