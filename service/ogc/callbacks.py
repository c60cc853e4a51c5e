"""Sending the callbacks OGC execute requests subscribed to (conformance class
``callback``).

One :class:`CallbackSender` runs in every API process while callbacks are on (the
``outbound_allow_hosts`` setting names hosts).  Each tick it asks the store for due
callbacks; the store hands each to one sender at a time across replicas (a claim
under a lease), so a callback is sent once, and again only if that send failed or
its sender died mid-send.  It POSTs:

- ``inProgressUri``: the job's status information, once, when the job is seen running;
- ``successUri``: the results document (the outputs the request asked for; files by
  reference);
- ``failedUri``: the failure as a problem document.

No redirect is followed, each request times out after ``outbound_timeout_s``, the
allow-list is checked again before each send, and a failed send is retried with
growing pauses, up to ``callback_max_attempts`` tries.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
from dataclasses import replace
from typing import Any

import httpx
from starlette.concurrency import run_in_threadpool

from service.documents import as_json
from service.ogc.execute_request import Presentation
from service.ogc.jobs.documents import status_info
from service.ogc.outbound import OutboundPolicy
from service.ogc.outputs import process_outputs
from service.ogc.results import document_bytes, select_outputs
from service.ogc.urls import PublicUrls
from service.ogc.vocabulary import EXCEPTION_TYPES, JSON
from service.problems import PROBLEM_TYPES, problem_document, problem_type_uri
from worker.contract import JobStatus
from worker.processes import ProcessRegistry
from worker.store.base import CallbackClaim, JobStore

__all__ = ["CallbackSender"]

log = logging.getLogger("dexlab.service")

#: Callbacks claimed per tick.
_BATCH = 20


class CallbackSender:
    """Claims due callbacks and sends them (start it in the app's lifespan)."""

    def __init__(
        self,
        store: JobStore,
        registry: ProcessRegistry,
        policy: OutboundPolicy,
        max_attempts: int,
        interval_s: float = 0.5,
    ) -> None:
        self._store = store
        self._registry = registry
        self._policy = policy
        self._max_attempts = max_attempts
        self._interval_s = interval_s
        # A sender that dies mid-send holds its claim this long; then another retries.
        self._lease_s = 4 * policy.timeout_s + 10.0
        self._task: asyncio.Task[None] | None = None

    def start(self) -> None:
        self._task = asyncio.get_running_loop().create_task(self._run(), name="ogc-callbacks")

    async def stop(self) -> None:
        if self._task is not None:
            self._task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._task

    async def _run(self) -> None:
        async with httpx.AsyncClient(follow_redirects=False) as client:
            while True:
                try:
                    claims = await run_in_threadpool(
                        self._store.claim_callbacks, self._lease_s, self._max_attempts, _BATCH
                    )
                    for claim in claims:
                        await self._send(client, claim)
                except Exception as exc:  # store trouble: the next tick tries again
                    log.warning("callbacks: %s: %s", type(exc).__name__, exc)
                await asyncio.sleep(self._interval_s)

    async def _send(self, client: httpx.AsyncClient, claim: CallbackClaim) -> None:
        body = await run_in_threadpool(self._document, claim)
        delivered = body is not None and await self._policy.post(
            client, claim.uri, body[0], body[1]
        )
        retry_after = min(300.0, 2.0**claim.attempt)
        if not delivered:
            log.info(
                "callback %s of job %s to %s failed (try %d)",
                claim.event,
                claim.job_id,
                claim.uri,
                claim.attempt,
            )
        await run_in_threadpool(
            self._store.finish_callback, claim, delivered, retry_after, self._max_attempts
        )

    def _document(self, claim: CallbackClaim) -> tuple[bytes, str] | None:
        """The body and media type of the callback (None: nothing left to send)."""
        job = self._store.get_job(claim.job_id)
        stored, _ = self._store.request_options(claim.job_id)
        if job is None or stored is None:
            return None
        urls = PublicUrls(str(stored.get("base", "")))
        if claim.event == "in-progress":
            return _json(as_json(status_info(job, urls))), JSON
        if claim.event == "failed":
            return _json(_failure(job.error or {}, urls, job.job_id)), "application/problem+json"
        result = self._store.get_result(job.job_id)
        definition = self._registry.get(job.process_id)
        if job.status is not JobStatus.SUCCESSFUL or result is None or definition is None:
            return None
        presentation = Presentation.from_json(stored)
        # A callback carries files by reference (no file is held in memory to send it).
        outputs = process_outputs(definition)
        selected = [
            replace(o, mode="reference") if o.spec.artifact else o
            for o in select_outputs(job, result, outputs, presentation, self._store)
        ]
        return document_bytes(selected, urls, job.job_id, self._store), JSON


def _json(document: dict[str, Any]) -> bytes:
    return json.dumps(document, allow_nan=False).encode()


def _failure(error: Any, urls: PublicUrls, job_id: str) -> dict[str, Any]:
    slug = str(error.get("type", "job-failed"))
    slug = slug if slug in PROBLEM_TYPES else "job-failed"
    return problem_document(
        slug,
        detail=str(error.get("detail", "The job failed.")),
        title=str(error.get("title") or PROBLEM_TYPES[slug][1]),
        instance=urls.job(job_id),
        type_uri=EXCEPTION_TYPES.get(slug) or f"{urls.root}{problem_type_uri(slug)}",
        jobID=job_id,
    )
