"""Every exception the dexlab client raises, in one tree.

::

    DexlabError                   base: .problem (the RFC 9457 problem document), .status
    ├── RequestRefused            the service refused the request; nothing was queued
    │   ├── InvalidInputs         422 invalid-inputs / invalid-request: .errors, per field
    │   ├── CostLimitExceeded     422 the work is above the process's cost limit: .cost
    │   ├── IdempotencyConflict   422 an Idempotency-Key reused with another body
    │   ├── Unauthorized          401 no API key, or a wrong or revoked one
    │   └── QuotaExceeded         429 too many jobs or requests: .retry_after (seconds)
    ├── NotFound                  404 nothing at this path
    │   ├── NoSuchProcess         no process has this ID
    │   ├── NoSuchJob             no job has this ID (or it is not yours)
    │   └── NoSuchArtifact        the job has no file of this name
    ├── ResultNotReady            404 the job has not finished yet
    ├── JobDismissed              410 the job was dismissed; its results are gone
    ├── JobFailed                 the job failed: .problem is its failure, .job_id
    ├── ServiceUnavailable        503 / 507 the store or the workers are down: .retry_after
    │   └── ServiceUnreachable    no answer at all (connection refused, DNS, timeouts)
    └── WaitTimeout               wait() or run() gave up (also a TimeoutError)

The server's problem documents map to these by their ``type`` (the last path segment,
so ``/problems/no-such-job`` and OGC's ``.../no-such-job`` both give :class:`NoSuchJob`),
then by HTTP status; anything else is a plain :class:`DexlabError`.  Each class's
docstring is its default title.  Errors raised on the client's side (unreachable
service, timeout) carry a problem document of the same shape, so a caller reads every
error the same way.
"""

from __future__ import annotations

from collections.abc import Mapping
from datetime import UTC, datetime
from email.utils import parsedate_to_datetime
from typing import Any

__all__ = [
    "CostLimitExceeded",
    "DexlabError",
    "IdempotencyConflict",
    "InvalidInputs",
    "JobDismissed",
    "JobFailed",
    "NoSuchArtifact",
    "NoSuchJob",
    "NoSuchProcess",
    "NotFound",
    "QuotaExceeded",
    "RequestRefused",
    "ResultNotReady",
    "ServiceUnavailable",
    "ServiceUnreachable",
    "Unauthorized",
    "WaitTimeout",
    "error_from_problem",
    "retry_after_seconds",
]


class DexlabError(Exception):
    """Something went wrong."""

    def __init__(
        self,
        problem: Mapping[str, Any] | None = None,
        *,
        status: int | None = None,
        retry_after: float | None = None,
    ) -> None:
        doc = dict(problem or {})
        doc.setdefault("title", (type(self).__doc__ or "Error").strip())
        if status is None and isinstance(doc.get("status"), int):
            status = doc["status"]
        self.problem: dict[str, Any] = doc
        self.status = status
        self.retry_after = retry_after
        super().__init__(self.message)

    @property
    def type(self) -> str:
        """The problem type URI (``about:blank`` when it has none)."""
        return str(self.problem.get("type") or "about:blank")

    @property
    def slug(self) -> str:
        """The problem type's last path segment, e.g. ``no-such-job``."""
        return problem_slug(self.problem)

    @property
    def title(self) -> str:
        return str(self.problem["title"])

    @property
    def detail(self) -> str:
        return str(self.problem.get("detail") or "")

    @property
    def message(self) -> str:
        """One line: the title, then the detail when there is one."""
        return f"{self.title}: {self.detail}" if self.detail else self.title


class RequestRefused(DexlabError):
    """The service refused the request."""


class InvalidInputs(RequestRefused):
    """Invalid inputs."""

    @property
    def errors(self) -> list[dict[str, Any]]:
        """One ``{"field", "message", "type"}`` per bad field, as the service names it."""
        found = self.problem.get("errors")
        return [dict(e) for e in found if isinstance(e, Mapping)] if isinstance(found, list) else []


class CostLimitExceeded(RequestRefused):
    """Cost limit exceeded."""

    @property
    def cost(self) -> float | None:
        value = self.problem.get("cost")
        return float(value) if isinstance(value, int | float) else None

    @property
    def cost_limit(self) -> float | None:
        value = self.problem.get("cost_limit")
        return float(value) if isinstance(value, int | float) else None


class IdempotencyConflict(RequestRefused):
    """Idempotency-Key reused."""


class Unauthorized(RequestRefused):
    """Unauthorized: send a valid API key (DEXLAB_API_KEY)."""


class QuotaExceeded(RequestRefused):
    """Quota exceeded."""


class NotFound(DexlabError):
    """Not found."""


class NoSuchProcess(NotFound):
    """No such process."""


class NoSuchJob(NotFound):
    """No such job."""


class NoSuchArtifact(NotFound):
    """No such artifact."""


class ResultNotReady(DexlabError):
    """Result not ready."""


class JobDismissed(DexlabError):
    """Job dismissed."""


class JobFailed(DexlabError):
    """Job failed."""

    @property
    def job_id(self) -> str | None:
        value = self.problem.get("jobID")
        return str(value) if value is not None else None


class ServiceUnavailable(DexlabError):
    """Service unavailable."""


class ServiceUnreachable(ServiceUnavailable):
    """Service unreachable."""


class WaitTimeout(DexlabError, TimeoutError):
    """Gave up waiting for the job."""


#: Problem types (the last segment of ``type``) and the class each raises.
_BY_SLUG: dict[str, type[DexlabError]] = {
    "invalid-inputs": InvalidInputs,
    "invalid-request": InvalidInputs,
    "invalid-parameter-value": InvalidInputs,
    "cost-limit-exceeded": CostLimitExceeded,
    "idempotency-conflict": IdempotencyConflict,
    "unauthorized": Unauthorized,
    "quota-exceeded": QuotaExceeded,
    "rate-limited": QuotaExceeded,
    "too-many-requests": QuotaExceeded,
    "no-such-process": NoSuchProcess,
    "no-such-job": NoSuchJob,
    "no-such-artifact": NoSuchArtifact,
    "not-found": NotFound,
    "result-not-ready": ResultNotReady,
    "job-dismissed": JobDismissed,
    "job-failed": JobFailed,
    "job-error": JobFailed,
    "time-limit-exceeded": JobFailed,
    "worker-lost": JobFailed,
    "store-unavailable": ServiceUnavailable,
    "storage-error": ServiceUnavailable,
    "storage-full": ServiceUnavailable,
    "not-ready": ServiceUnavailable,
}

_BY_STATUS: dict[int, type[DexlabError]] = {
    401: Unauthorized,
    404: NotFound,
    410: JobDismissed,
    429: QuotaExceeded,
    502: ServiceUnavailable,
    503: ServiceUnavailable,
    504: ServiceUnavailable,
    507: ServiceUnavailable,
}


def problem_slug(problem: Mapping[str, Any]) -> str:
    """The last path segment of a problem's ``type``: ``/problems/no-such-job`` ->
    ``no-such-job``."""
    kind = str(problem.get("type") or "")
    return kind.rstrip("/").rsplit("/", 1)[-1]


def retry_after_seconds(
    header: str | None, problem: Mapping[str, Any] | None = None
) -> float | None:
    """Seconds to wait, from a ``Retry-After`` header (seconds or an HTTP date) or a
    problem's ``retry_after`` / ``retry_after_s`` member; None when neither says."""
    if header:
        text = header.strip()
        try:
            return max(0.0, float(text))
        except ValueError:
            try:
                when = parsedate_to_datetime(text)
            except (TypeError, ValueError):
                when = None
            if when is not None:
                if when.tzinfo is None:  # '-0000': UTC, says RFC 5322
                    when = when.replace(tzinfo=UTC)
                return max(0.0, (when - datetime.now(UTC)).total_seconds())
    for key in ("retry_after", "retry_after_s"):
        value = (problem or {}).get(key)
        if isinstance(value, int | float) and not isinstance(value, bool) and value >= 0:
            return float(value)
    return None


def error_from_problem(
    status: int, problem: Mapping[str, Any], *, retry_after: float | None = None
) -> DexlabError:
    """The exception for a problem document the service answered with ``status``.

    A failed job's results (``GET /v1/jobs/{id}/results``) answer with the failure's own
    type and status (500, or 503/507 for a storage failure) and name the job
    (``jobID``): those are :class:`JobFailed`, never a passing outage."""
    slug = problem_slug(problem)
    cls = _BY_SLUG.get(slug) or _BY_STATUS.get(status, DexlabError)
    if "jobID" in problem and status >= 500:
        cls = JobFailed
    if retry_after is None:
        retry_after = retry_after_seconds(None, problem)
    return cls(problem, status=status, retry_after=retry_after)
