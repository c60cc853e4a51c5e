"""How the clients wait for a job (shared by :class:`~dexlab.Job` and
:class:`~dexlab.AsyncJob`).

Waiting follows the job's Server-Sent Events (``GET /v1/jobs/{jobID}/events``): the
service pushes every change of status, progress and message as it happens, so a
progress bar moves without polling and a finished job is seen at once.  Around the
stream the client reads the status document (with the usual retries): before the first
stream, after each stream ends (the service closes a stream after its lifetime) and
after a stream breaks.  Where the events route is missing (an older service, a proxy
that refuses streams) the client polls the status instead, with pauses growing from
0.25 s to 2 s.  A ``timeout`` bounds the whole wait: :class:`~dexlab.errors.WaitTimeout`.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from typing import Any

import httpx

from dexlab.connection import problem_of
from dexlab.documents import JobStatus
from dexlab.errors import DexlabError, JobDismissed, JobFailed, WaitTimeout, problem_slug

__all__ = ["EVENT_READ_TIMEOUT_S", "WaitClock", "events_unsupported", "failure_of"]

#: The longest silence accepted on an event stream (the service sends a comment line
#: every 15 s on a quiet stream).
EVENT_READ_TIMEOUT_S = 30.0
FIRST_POLL_S = 0.25
LONGEST_POLL_S = 2.0


class WaitClock:
    """The deadline of one wait, its poll pauses, and whether events are available."""

    def __init__(self, timeout: float | None, job_id: str) -> None:
        if timeout is not None and not timeout >= 0:
            raise ValueError(f"The 'timeout' must be >= 0 seconds or None. Got {timeout!r}.")
        self.job_id = job_id
        self.timeout = timeout
        self.deadline = None if timeout is None else time.monotonic() + timeout
        self.events = True
        self._poll = FIRST_POLL_S

    def remaining(self) -> float | None:
        return None if self.deadline is None else self.deadline - time.monotonic()

    def check(self, last: JobStatus) -> None:
        """Raise :class:`WaitTimeout` once the deadline has passed."""
        left = self.remaining()
        if left is not None and left <= 0:
            raise WaitTimeout(
                {"title": "Gave up waiting for the job",
                 "detail": f"Job {self.job_id} is still {last} after {self.timeout:g} s; it "
                 "goes on (wait again, or cancel it).", "jobID": self.job_id},
            )  # fmt: skip

    def read_timeout(self) -> float:
        """The read timeout of an event stream: the silence allowed, within the deadline."""
        left = self.remaining()
        return EVENT_READ_TIMEOUT_S if left is None else max(0.05, min(EVENT_READ_TIMEOUT_S, left))

    def pause(self) -> float:
        """The next pause between status reads (growing), within the deadline."""
        pause, self._poll = self._poll, min(LONGEST_POLL_S, self._poll * 1.6)
        left = self.remaining()
        return pause if left is None else max(0.0, min(pause, left))

    def progressed(self) -> None:
        """Something changed: the next poll comes quickly again."""
        self._poll = FIRST_POLL_S


def events_unsupported(response: httpx.Response) -> bool:
    """Whether an answer to ``GET .../events`` says the service has no event stream
    (as opposed to an error about the job, which the status read then reports)."""
    if response.status_code == 200:
        return not response.headers.get("content-type", "").startswith("text/event-stream")
    if response.status_code in (405, 406, 501):
        return True
    return response.status_code == 404 and problem_slug(problem_of(response) or {}) in (
        "not-found",
        "",
    )


def _problem(error: Mapping[str, Any] | None, job_id: str, default_title: str) -> dict[str, Any]:
    error = dict(error or {})
    kind = str(error.get("type") or "job-failed")
    return {
        "type": kind if "/" in kind or ":" in kind else f"/problems/{kind}",
        "title": str(error.get("title") or default_title),
        "detail": str(error.get("detail") or ""),
        "jobID": job_id,
    }


def failure_of(status: JobStatus) -> DexlabError | None:
    """The exception for a job that ended without results; None if it succeeded or
    has not ended."""
    if status.status == "failed":
        return JobFailed(_problem(status.error, status.job_id, "Job failed"))
    if status.status == "dismissed":
        return JobDismissed(
            {"type": "/problems/job-dismissed", "title": "Job dismissed",
             "detail": f"Job {status.job_id} was dismissed; it has no results.",
             "jobID": status.job_id},
        )  # fmt: skip
    return None
