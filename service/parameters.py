"""Parameters declared once: the query and header parameters both surfaces share, and
the ``/v1`` job list's (its JSON route and its page take the same), validated where
FastAPI validates parameters (so a bad value is answered like any other:
:func:`service.problems.parameter_problem`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated
from urllib.parse import urlencode

from fastapi import Depends, Header, Query
from pydantic import AfterValidator

from worker.contract import JobStatus
from worker.store.sql import decode_cursor

__all__ = [
    "CacheControlHeader",
    "CursorQuery",
    "IdempotencyKey",
    "JobListQuery",
    "JobListQueryDep",
    "PreferHeader",
]


def _cursor(value: str | None) -> str | None:
    if value is not None:
        decode_cursor(value)  # ValueError names the parameter
    return value


#: The execute requests' ``Idempotency-Key`` and ``Prefer`` headers (both surfaces).
IdempotencyKey = Annotated[
    str | None, Header(alias="Idempotency-Key", min_length=1, max_length=255)
]
PreferHeader = Annotated[str | None, Header(max_length=255)]
#: ``Cache-Control`` of an execute request: ``no-cache`` computes afresh (``reuse: false``).
CacheControlHeader = Annotated[str | None, Header(alias="Cache-Control", max_length=255)]

#: ``cursor``: where a ``next`` link continues; only a cursor this service issued.
CursorQuery = Annotated[
    str | None,
    Query(max_length=200, description="Where a `next` link continues."),
    AfterValidator(_cursor),
]


@dataclass(frozen=True, slots=True)
class JobListQuery:
    """``GET /v1/jobs``'s parameters, validated (the JSON route and its page share them)."""

    limit: int
    cursor: str | None
    status: JobStatus | None
    process_id: str | None
    owner: str | None
    parent: str | None

    def next_href(self, cursor: str) -> str:
        """The next page's URL: this query from ``cursor``."""
        href = f"/v1/jobs?limit={self.limit}&cursor={cursor}"
        if self.status is not None:
            href += f"&status={self.status.value}"
        if self.process_id is not None:
            href += f"&processID={self.process_id}"
        if self.owner is not None:
            href += f"&{urlencode({'owner': self.owner})}"
        if self.parent is not None:
            href += f"&{urlencode({'parent': self.parent})}"
        return href


async def job_list_query(
    limit: Annotated[int, Query(ge=1, le=1000)] = 20,
    cursor: CursorQuery = None,
    status: Annotated[JobStatus | None, Query()] = None,
    process_id: Annotated[str | None, Query(alias="processID", max_length=200)] = None,
    owner: Annotated[
        str | None,
        Query(max_length=64, description="Admin keys only: this key's jobs ('' = anonymous)."),
    ] = None,
    parent: Annotated[
        str | None,
        Query(max_length=64, description="A design study's jobID: list its chunk jobs."),
    ] = None,
) -> JobListQuery:
    return JobListQuery(limit, cursor, status, process_id, owner, parent)


JobListQueryDep = Annotated[JobListQuery, Depends(job_list_query)]
