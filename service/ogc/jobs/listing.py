"""``GET /ogc/jobs``: its query parameters (one dependency, which the JSON route and
the page route share) and the page of jobs they select."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Literal

from fastapi import Depends, Query, Request
from pydantic import AfterValidator, StringConstraints

from service.deps import Api
from service.ogc.jobs.documents import job_list
from service.ogc.jobs.query import MAX_PAGE, listing_filter, page_query, parse_datetime_interval
from service.ogc.schemas import OgcJobList
from service.ogc.urls import public_urls
from service.parameters import CursorQuery
from service.problems import parameter_error
from worker.contract import JobStatus
from worker.errors import NoSuchProcess

__all__ = ["JobListQuery", "JobListQueryDep", "job_list_document"]


def _interval(value: str | None) -> str | None:
    if value is not None:
        parse_datetime_interval(value)  # ValueError says what is wrong
    return value


ProcessIDs = list[Annotated[str, StringConstraints(min_length=1, max_length=200)]]
Interval = Annotated[
    str | None,
    Query(
        max_length=100,
        description="A date-time, or an interval start/end ('..' or "
        "empty: open), RFC 3339; selects jobs by their `created` time.",
    ),
    AfterValidator(_interval),
]


@dataclass(frozen=True, slots=True)
class JobListQuery:
    """The job list's parameters, validated."""

    process_ids: list[str] | None
    statuses: list[JobStatus] | None
    types: list[str] | None
    datetime: str | None
    min_duration: int | None
    max_duration: int | None
    limit: int
    cursor: str | None
    owner: str | None


async def job_list_query(
    processID: Annotated[
        ProcessIDs | None, Query(description="Only these processes' jobs.")
    ] = None,
    status: Annotated[
        list[JobStatus] | None, Query(description="Only jobs in these states.")
    ] = None,
    job_type: Annotated[
        list[Literal["process"]] | None,
        Query(alias="type", description="Only jobs of these types (every job is `process`)."),
    ] = None,
    datetime: Interval = None,
    minDuration: Annotated[
        int | None, Query(ge=0, le=10**9, description="Only jobs that ran at least this long (s).")
    ] = None,
    maxDuration: Annotated[
        int | None, Query(ge=0, le=10**9, description="Only jobs that ran at most this long (s).")
    ] = None,
    limit: Annotated[
        int, Query(ge=1, le=10000, description=f"Most jobs per page (at most {MAX_PAGE} sent).")
    ] = 10,
    cursor: CursorQuery = None,
    owner: Annotated[
        str | None,
        Query(max_length=64, description="Admin keys only: this key's jobs ('' = anonymous)."),
    ] = None,
) -> JobListQuery:
    return JobListQuery(
        processID, status, list(job_type) if job_type else None, datetime, minDuration,
        maxDuration, limit, cursor, owner,
    )  # fmt: skip


JobListQueryDep = Annotated[JobListQuery, Depends(job_list_query)]


def job_list_document(request: Request, api: Api, query: JobListQuery) -> OgcJobList:
    """jobList.yaml: the page of the caller's jobs (an admin's: ``owner``'s) the query
    selects, with ``self`` and ``next`` links that repeat its parameters."""
    scope = api.identity.owner_filter(query.owner)
    unknown = sorted(set(query.process_ids or ()) - set(api.registry.ids()))
    if unknown:  # the API definition lists the IDs: a bad value, like any other
        unknown_id = NoSuchProcess.named(unknown[0], api.registry.ids())
        raise parameter_error("query", "processID", unknown_id.detail)
    where = listing_filter(
        query.process_ids,
        query.statuses,
        query.types,
        None if query.datetime is None else parse_datetime_interval(query.datetime),
        query.min_duration,
        query.max_duration,
    )
    page = api.store.list_jobs(
        limit=min(query.limit, MAX_PAGE), cursor=query.cursor, where=where, owner=scope
    )
    urls = public_urls(request)
    params = [(k, v) for k, v in request.query_params.multi_items() if k != "f"]
    self_href = f"{urls.ogc}/jobs" + (f"?{page_query(params, query.cursor)}" if params else "")
    next_href = (
        None
        if page.next_cursor is None
        else f"{urls.ogc}/jobs?{page_query(params, page.next_cursor)}"
    )
    return job_list(page.jobs, urls, self_href, next_href, admin=api.identity.admin)
