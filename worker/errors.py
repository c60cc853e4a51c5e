"""Every exception dexlab raises on purpose, in one tree.

::

    DexlabError                     base; never raised itself
    ├── InvalidInputs               inputs fail validation (names each field)
    ├── CostLimitExceeded           the requested work exceeds the process's cost limit
    ├── IdempotencyConflict         an Idempotency-Key reused with another request body
    ├── NoSuchProcess               unknown process ID
    │   └── NoPreview               a process without a preview (the live explorer's)
    ├── NoSuchJob                   unknown job ID
    ├── NoSuchArtifact              unknown artifact name for a job
    ├── ResultNotReady              the job has not finished yet
    ├── JobFailed                   the job finished without a result
    ├── JobDismissed                the job was dismissed (cancelled)
    ├── JobExpired                  the job's retention ended: it and its results are gone
    ├── QuotaExceeded               an API key has as many jobs queued as it may
    │   └── RateLimited             an API key submitted as many jobs this minute as it may
    ├── QueueFull                   the whole queue holds as many jobs as it may
    └── StoreUnavailable            the job store cannot be reached (or stays locked)
        ├── StorageFull             the store's disk is full
        └── StorageError            the store cannot read or write its files (corrupt,
                                    read-only, I/O error)

Each class's docstring is its default message.  The HTTP layer maps each class to a
status code and an RFC 9457 problem type in exactly one place (``service.errors``).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any

__all__ = [
    "CostLimitExceeded",
    "DexlabError",
    "FieldError",
    "IdempotencyConflict",
    "InvalidInputs",
    "JobDismissed",
    "JobExpired",
    "JobFailed",
    "NoPreview",
    "NoSuchArtifact",
    "NoSuchJob",
    "NoSuchProcess",
    "QueueFull",
    "QuotaExceeded",
    "RateLimited",
    "ResultNotReady",
    "StorageError",
    "StorageFull",
    "StoreUnavailable",
]

FieldError = Mapping[str, Any]


class DexlabError(Exception):
    """Something went wrong in dexlab."""

    def __init__(self, detail: str | None = None, **extra: Any) -> None:
        self.detail = detail or (self.__doc__ or "").strip()
        self.extra = extra
        super().__init__(self.detail)


class InvalidInputs(DexlabError):
    """The inputs are not valid for this process."""

    def __init__(self, errors: Sequence[FieldError], detail: str | None = None) -> None:
        self.errors = list(errors)
        if detail is None and self.errors:
            first = self.errors[0]
            detail = f"Invalid value for '{first['field']}': {first['message']}"
            if len(self.errors) > 1:
                detail += f" (and {len(self.errors) - 1} more problem(s))"
        super().__init__(detail)


class CostLimitExceeded(DexlabError):
    """The requested work exceeds the process's documented cost limit."""


class IdempotencyConflict(DexlabError):
    """This Idempotency-Key was already used with a different request body."""


class NoSuchProcess(DexlabError):
    """No process with this ID."""

    @classmethod
    def named(cls, process_id: str, available: Iterable[str]) -> NoSuchProcess:
        """The error for ``process_id``, listing the IDs there are (the one wording)."""
        return cls(f"No process {process_id!r}; available: {', '.join(available)}.")


class NoSuchJob(DexlabError):
    """No job with this ID."""


class NoSuchArtifact(DexlabError):
    """This job has no artifact with this name."""


class ResultNotReady(DexlabError):
    """The job has not finished yet; poll its status."""


class JobFailed(DexlabError):
    """The job failed."""


class JobDismissed(DexlabError):
    """The job was dismissed; it has no results."""


class JobExpired(DexlabError):
    """The job's retention ended: the job and its results were deleted."""


# A quota's ``extra`` names the limit (``limit``: its setting, ``allowed``: its value)
# and when to retry (``retry_after_s``); the same for QueueFull.
class QuotaExceeded(DexlabError):
    """This API key has as many jobs queued as it may; retry when one has started."""


class RateLimited(QuotaExceeded):
    """This API key submitted as many jobs this minute as it may."""


class QueueFull(DexlabError):
    """The queue holds as many jobs as the service takes; retry later."""


class StoreUnavailable(DexlabError):
    """The job store cannot be reached."""


class StorageFull(StoreUnavailable):
    """The job store's disk is full; nothing more can be written."""


class StorageError(StoreUnavailable):
    """The job store cannot read or write its files (corrupt, read-only, I/O error)."""


class NoPreview(NoSuchProcess):
    """This process has no preview; run it as a job."""
