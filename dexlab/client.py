"""The synchronous client: :class:`Client`, which hands out :class:`~dexlab.Job` handles.

::

    from dexlab import Client

    with Client() as client:                      # DEXLAB_URL, DEXLAB_API_KEY
        job = client.run("fourbar-grashof", example=1)
        job.result["classification"]              # 'crank-rocker'
        job.download("fourbar")                   # every file the job wrote

Every request is retried on connection errors and ``503`` (see :mod:`dexlab.retry`);
waiting follows the job's event stream (see :mod:`dexlab.waiting`).
"""

from __future__ import annotations

import time
from collections.abc import Iterator, Mapping
from types import TracebackType
from typing import Any

import httpx

from dexlab.connection import (
    Connection,
    api_path,
    error_from_response,
    new_idempotency_key,
    problem_of,
    read_answer,
    unreachable,
)
from dexlab.documents import JobStatus, example_inputs
from dexlab.job import Job
from dexlab.progress import ProgressDisplay
from dexlab.retry import RetryPolicy

__all__ = ["Client"]


class Client:
    """A dexlab service (see the module docstring).  ``url`` and ``api_key`` default to
    ``DEXLAB_URL`` and ``DEXLAB_API_KEY``; ``timeout`` bounds each request (seconds);
    ``retry`` says how requests are retried.  Close it (or use ``with``) when done."""

    def __init__(
        self,
        url: str | None = None,
        api_key: str | None = None,
        *,
        timeout: float = 30.0,
        retry: RetryPolicy | None = None,
    ) -> None:
        self.connection = Connection.resolve(url, api_key, timeout, retry)
        self._http = httpx.Client(
            base_url=self.connection.url,
            headers=self.connection.headers(),
            timeout=self.connection.timeout,
        )

    @property
    def url(self) -> str:
        return self.connection.url

    def close(self) -> None:
        self._http.close()

    def __enter__(self) -> Client:
        return self

    def __exit__(self, kind: type[BaseException] | None, value: BaseException | None,
                 traceback: TracebackType | None) -> None:  # fmt: skip
        self.close()

    def __repr__(self) -> str:
        return f"<Client {self.url}>"

    # Requests, retried.

    def send(self, request: httpx.Request, *, stream: bool = False) -> httpx.Response:
        """Send ``request``, trying again on connection errors and 502/503/504 as the
        retry policy allows; the last answer is returned whatever its status."""
        policy = self.connection.retry
        attempt = 0
        while True:
            attempt += 1
            try:
                response = self._http.send(request, stream=stream)
            except httpx.TransportError as exc:
                pause = policy.pause(attempt)
                if pause is None:
                    raise unreachable(self.url, exc) from exc
                time.sleep(pause)
                continue
            if stream and response.status_code >= 400:
                response.read()
            problem = problem_of(response) if response.status_code >= 400 else None
            if policy.retries_answer(response.status_code, problem):
                pause = policy.pause(attempt, error_from_response(response).retry_after)
                if pause is not None:
                    response.close()
                    time.sleep(pause)
                    continue
            return response

    def build_request(self, method: str, path: str, **options: Any) -> httpx.Request:
        """A request to ``path`` on the service (``options`` as httpx takes them)."""
        return self._http.build_request(method, path, **options)

    def request(self, method: str, path: str, **options: Any) -> httpx.Response:
        """A request to ``path`` (e.g. ``/v1/jobs``), retried; any answer is returned."""
        return self.send(self.build_request(method, path, **options))

    def document(self, method: str, path: str, **options: Any) -> Any:
        """The JSON document at ``path``; an error answer raises its exception."""
        return read_answer(self.request(method, path, **options))

    # Processes.

    def processes(self) -> list[dict[str, Any]]:
        """Every process: ``id``, ``title``, ``description``, ``version``."""
        return list(self.document("GET", api_path("processes"))["processes"])

    def describe(self, process_id: str) -> dict[str, Any]:
        """A process's description: its inputs schema, outputs, worked examples, limits."""
        return dict(self.document("GET", api_path("processes", process_id)))

    def examples(self, process_id: str) -> list[dict[str, Any]]:
        """A process's worked examples (``title``, ``description``, ``inputs``), in its
        order: ``submit(process_id, example=N)`` runs number N (from 0)."""
        return list(self.describe(process_id).get("examples") or [])

    # Jobs.

    def _inputs(self, process_id: str, inputs: Mapping[str, Any] | None,
                example: int | None) -> dict[str, Any]:  # fmt: skip
        if (inputs is None) == (example is None):
            raise TypeError("Give either the inputs or example=N (a worked example), not both.")
        if example is not None:
            return example_inputs(process_id, self.describe(process_id), example)
        return dict(inputs or {})

    def submit(
        self,
        process_id: str,
        inputs: Mapping[str, Any] | None = None,
        *,
        example: int | None = None,
        idempotency_key: str | None = None,
        reuse: bool = True,
        share: bool = True,
    ) -> Job:
        """Queue a job with ``inputs``, or with the inputs of worked example ``example``
        (from 0).  The submission carries an ``Idempotency-Key`` (a fresh one unless
        given), the same on every retry, so it never makes two jobs.  A stored result
        of the same inputs may answer it at once (``reuse=False``: compute afresh);
        ``share=False`` keeps its result from other API keys (docs/reuse.md)."""
        body: dict[str, Any] = {"inputs": self._inputs(process_id, inputs, example)}
        if not reuse:
            body["reuse"] = False
        if not share:
            body["share"] = False
        key = idempotency_key or new_idempotency_key()
        doc = self.document("POST", api_path("processes", process_id, "execution"),
                             json=body, headers={"Idempotency-Key": key})  # fmt: skip
        return Job(self, JobStatus.from_document(doc))

    def run(
        self,
        process_id: str,
        inputs: Mapping[str, Any] | None = None,
        *,
        example: int | None = None,
        progress: bool | ProgressDisplay = True,
        timeout: float | None = None,
    ) -> Job:
        """Submit and wait (with a progress bar in a terminal or notebook); the job, its
        results fetched.  Raises :class:`~dexlab.errors.JobFailed` if it fails and
        :class:`~dexlab.errors.WaitTimeout` after ``timeout`` seconds (the job goes on)."""
        job = self.submit(process_id, inputs, example=example)
        return job.wait(timeout, progress=progress)

    def invalidate_reuse(self, process_id: str, key: str | None = None) -> dict[str, Any]:
        """Stop the stored results of ``process_id`` (of result key ``key`` only, when
        given) from answering new jobs, deleting none (an admin key's right):
        ``{"processID", "result_key", "invalidated"}``."""
        params = {} if key is None else {"key": key}
        return dict(self.document("DELETE", api_path("reuse", process_id), params=params))

    def job(self, job_id: str) -> Job:
        """The job with this ID (its status read now)."""
        return Job(self, JobStatus.from_document(self.document("GET", api_path("jobs", job_id))))

    def jobs(
        self, status: str | None = None, process: str | None = None, *, page_size: int = 100
    ) -> Iterator[Job]:
        """Every job, newest first, optionally of one ``status`` and ``process``; pages
        are fetched as the iteration needs them."""
        params: dict[str, Any] = {"limit": page_size}
        if status is not None:
            params["status"] = status
        if process is not None:
            params["processID"] = process
        while True:
            page = self.document("GET", api_path("jobs"), params=params)
            for doc in page.get("jobs") or []:
                yield Job(self, JobStatus.from_document(doc))
            cursor = page.get("next_cursor")
            if not cursor:
                return
            params["cursor"] = cursor
