"""The asynchronous client: :class:`AsyncClient` and its :class:`AsyncJob` handles, the
twins of :class:`~dexlab.Client` and :class:`~dexlab.Job` (same documents, errors,
retries and waiting), for asyncio and trio code.

::

    async with AsyncClient() as client:
        job = await client.run("spm-design-space", example=1, progress=False)
        job.result["rectangles"]

An :class:`AsyncJob` fetches its result document when ``await job.wait()`` (or
``client.run``) sees it succeed; ``result``, ``notes`` and ``artifacts`` then read it
without a request (``await job.results()`` fetches it for a job found otherwise).
"""

from __future__ import annotations

import os
from collections.abc import AsyncIterator, Mapping
from contextlib import closing, suppress
from pathlib import Path
from types import TracebackType
from typing import Any

import anyio
import httpx

from dexlab.connection import (
    Connection,
    api_path,
    error_from_response,
    new_idempotency_key,
    problem_of,
    read_answer,
    read_bytes,
    unreachable,
)
from dexlab.documents import Artifact, JobStatus, example_inputs, read_csv, read_npz, safe_file_name
from dexlab.events import EventStreamParser, progress_of
from dexlab.job_view import JobView
from dexlab.progress import ProgressDisplay, progress_display
from dexlab.retry import RetryPolicy
from dexlab.waiting import WaitClock, events_unsupported, failure_of

__all__ = ["AsyncClient", "AsyncJob"]


class AsyncClient:
    """A dexlab service, asynchronously (see :class:`~dexlab.Client` for the arguments).
    Close it (``await client.aclose()``, or ``async with``) when done."""

    def __init__(
        self,
        url: str | None = None,
        api_key: str | None = None,
        *,
        timeout: float = 30.0,
        retry: RetryPolicy | None = None,
    ) -> None:
        self.connection = Connection.resolve(url, api_key, timeout, retry)
        self._http = httpx.AsyncClient(
            base_url=self.connection.url,
            headers=self.connection.headers(),
            timeout=self.connection.timeout,
        )

    @property
    def url(self) -> str:
        return self.connection.url

    async def aclose(self) -> None:
        await self._http.aclose()

    async def __aenter__(self) -> AsyncClient:
        return self

    async def __aexit__(self, kind: type[BaseException] | None, value: BaseException | None,
                        traceback: TracebackType | None) -> None:  # fmt: skip
        await self.aclose()

    def __repr__(self) -> str:
        return f"<AsyncClient {self.url}>"

    async def send(self, request: httpx.Request, *, stream: bool = False) -> httpx.Response:
        """As :meth:`dexlab.Client.send`: retried on connection errors and 502/503/504."""
        policy = self.connection.retry
        attempt = 0
        while True:
            attempt += 1
            try:
                response = await self._http.send(request, stream=stream)
            except httpx.TransportError as exc:
                pause = policy.pause(attempt)
                if pause is None:
                    raise unreachable(self.url, exc) from exc
                await anyio.sleep(pause)
                continue
            if stream and response.status_code >= 400:
                await response.aread()
            problem = problem_of(response) if response.status_code >= 400 else None
            if policy.retries_answer(response.status_code, problem):
                pause = policy.pause(attempt, error_from_response(response).retry_after)
                if pause is not None:
                    await response.aclose()
                    await anyio.sleep(pause)
                    continue
            return response

    async def request(self, method: str, path: str, **options: Any) -> httpx.Response:
        return await self.send(self._http.build_request(method, path, **options))

    async def _document(self, method: str, path: str, **options: Any) -> Any:
        return read_answer(await self.request(method, path, **options))

    async def processes(self) -> list[dict[str, Any]]:
        return list((await self._document("GET", api_path("processes")))["processes"])

    async def describe(self, process_id: str) -> dict[str, Any]:
        return dict(await self._document("GET", api_path("processes", process_id)))

    async def examples(self, process_id: str) -> list[dict[str, Any]]:
        return list((await self.describe(process_id)).get("examples") or [])

    async def submit(
        self,
        process_id: str,
        inputs: Mapping[str, Any] | None = None,
        *,
        example: int | None = None,
        idempotency_key: str | None = None,
    ) -> AsyncJob:
        """As :meth:`dexlab.Client.submit`."""
        if (inputs is None) == (example is None):
            raise TypeError("Give either the inputs or example=N (a worked example), not both.")
        if example is not None:
            inputs = example_inputs(process_id, await self.describe(process_id), example)
        key = idempotency_key or new_idempotency_key()
        doc = await self._document(
            "POST", api_path("processes", process_id, "execution"),
            json={"inputs": dict(inputs or {})}, headers={"Idempotency-Key": key},
        )  # fmt: skip
        return AsyncJob(self, JobStatus.from_document(doc))

    async def run(
        self,
        process_id: str,
        inputs: Mapping[str, Any] | None = None,
        *,
        example: int | None = None,
        progress: bool | ProgressDisplay = True,
        timeout: float | None = None,
    ) -> AsyncJob:
        """As :meth:`dexlab.Client.run`."""
        job = await self.submit(process_id, inputs, example=example)
        return await job.wait(timeout, progress=progress)

    async def job(self, job_id: str) -> AsyncJob:
        return AsyncJob(self, JobStatus.from_document(
            await self._document("GET", api_path("jobs", job_id))))  # fmt: skip

    async def jobs(
        self, status: str | None = None, process: str | None = None, *, page_size: int = 100
    ) -> AsyncIterator[AsyncJob]:
        """As :meth:`dexlab.Client.jobs`: ``async for job in client.jobs(...)``."""
        params: dict[str, Any] = {"limit": page_size}
        if status is not None:
            params["status"] = status
        if process is not None:
            params["processID"] = process
        while True:
            page = await self._document("GET", api_path("jobs"), params=params)
            for doc in page.get("jobs") or []:
                yield AsyncJob(self, JobStatus.from_document(doc))
            cursor = page.get("next_cursor")
            if not cursor:
                return
            params["cursor"] = cursor


class AsyncJob(JobView):
    """A job on the service, asynchronously (see :class:`~dexlab.Job`)."""

    def __init__(self, client: AsyncClient, status: JobStatus) -> None:
        super().__init__(client.connection, status)
        self._client = client

    async def status(self) -> JobStatus:
        return self._absorb(await self._client._document("GET", self._path()))

    async def results(self) -> dict[str, Any]:
        """The whole result document; fetched once, then kept."""
        if self._results is None:
            self._keep_results(await self._client._document("GET", self._path("results")))
        return self._results or {}

    @property
    def result(self) -> dict[str, Any]:
        """The result, once ``wait()`` or ``results()`` fetched it."""
        return self._result_of(self._cached_results())

    @property
    def notes(self) -> list[str]:
        return self._notes_of(self._cached_results())

    @property
    def artifacts(self) -> list[Artifact]:
        return self._artifacts_of(self._cached_results())

    async def read(self, name: str) -> bytes:
        artifact = self._artifact_named(await self.results(), name)
        return read_bytes(
            await self._client.request(
                "GET", self._path("results", artifact.name), headers={"Accept": "*/*"}
            )
        )

    async def arrays(self, name: str) -> dict[str, Any]:
        return read_npz(await self.read(name), name)

    async def table(self, name: str) -> list[dict[str, int | float | str]]:
        return read_csv((await self.read(name)).decode("utf-8"))

    async def download(self, directory: str | os.PathLike[str]) -> list[Path]:
        folder = Path(directory)
        folder.mkdir(parents=True, exist_ok=True)
        written = []
        for artifact in self._artifacts_of(await self.results()):
            target = folder / safe_file_name(artifact.name)
            partial = target.with_name(f".{target.name}.part")
            partial.write_bytes(await self.read(artifact.name))
            partial.replace(target)
            written.append(target)
        return written

    async def cancel(self) -> JobStatus:
        return self._absorb(await self._client._document("DELETE", self._path()))

    async def wait(
        self, timeout: float | None = None, *, progress: bool | ProgressDisplay = False
    ) -> AsyncJob:
        """As :meth:`dexlab.Job.wait`."""
        clock = WaitClock(timeout, self.id)
        with closing(progress_display(progress, f"{self.process_id} {self.id[:8]}")) as display:
            status = await self.status()
            display.update(status)
            while not status.done:
                clock.check(status)
                await self._follow(clock, display)
                status = await self.status()
                display.update(status)
        failure = failure_of(status)
        if failure is not None:
            raise failure
        await self.results()
        return self

    async def _follow(self, clock: WaitClock, display: ProgressDisplay) -> None:
        if clock.events:
            before = self._status
            with suppress(httpx.TransportError):  # a broken stream: the status read retries
                await self._stream(clock, display)
            if self._status != before:
                clock.progressed()
                return
        await anyio.sleep(clock.pause())

    async def _stream(self, clock: WaitClock, display: ProgressDisplay) -> None:
        request = self._client._http.build_request(
            "GET", self._path("events"), headers={"Accept": "text/event-stream"},
            timeout=httpx.Timeout(self._client.connection.timeout, read=clock.read_timeout()),
        )  # fmt: skip
        response = await self._client.send(request, stream=True)
        try:
            if events_unsupported(response):
                clock.events = False
                return
            if response.status_code >= 400:
                return
            parser = EventStreamParser()
            async for line in response.aiter_lines():
                event = parser.feed(line)
                payload = progress_of(event) if event is not None else None
                if payload is not None:
                    self._status = self._status.with_event(payload)
                    display.update(self._status)
                    if self._status.done:
                        return
        finally:
            await response.aclose()
