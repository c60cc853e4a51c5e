"""``/v1/jobs``: status, listing, results, artifacts and dismissal.

Each caller sees its own jobs (an admin key every owner's): another owner's job is
404 ``no-such-job`` on every route, as if it did not exist.  An expired job (its
retention ended) is 410 ``job-expired`` for a while, then 404
(:mod:`service.job_lookup`).
"""

from __future__ import annotations

from typing import Annotated, Any
from urllib.parse import urlencode

from fastapi import APIRouter, Header, Query, Request, Response
from fastapi.responses import HTMLResponse, StreamingResponse

from service.auth import Identity, IdentityDep
from service.deps import RegistryDep, StoreDep
from service.documents import artifact_headers, results_document, status_document
from service.job_lookup import find_job, missing_job
from service.pages import FormatQuery, Pages, PagesDep, views, wants_html
from service.parameters import CursorQuery
from worker.contract import JobRecord, JobStatus
from worker.errors import (
    JobDismissed,
    JobFailed,
    NoSuchArtifact,
    ResultNotReady,
    StorageError,
)
from worker.processes import ProcessRegistry
from worker.store.base import JobFilter, JobStore, StoredArtifact

__all__ = ["router"]

router = APIRouter(prefix="/v1/jobs", tags=["jobs"])


def _job(store: JobStore, job_id: str, owner: str | None = None) -> JobRecord:
    """The job, if it exists and ``owner`` (None: anyone) owns it; else no-such-job
    (or job-expired)."""
    return find_job(store, job_id, owner)


@router.get("", summary="List jobs, newest first", response_model=None)
def list_jobs(
    request: Request,
    response: Response,
    store: StoreDep,
    registry: RegistryDep,
    pages: PagesDep,
    identity: IdentityDep,
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
    f: FormatQuery = None,
) -> dict[str, Any] | HTMLResponse:
    scope = identity.owner_filter(owner)
    where = None if parent is None else JobFilter(parent_id=parent)
    page = store.list_jobs(
        limit=limit, cursor=cursor, status=status, process_id=process_id, owner=scope,
        where=where,
    )  # fmt: skip
    response.headers["Vary"] = "Accept"
    if wants_html(request):
        return views.job_list_page(
            request, pages, registry, page, limit=limit, status=status, process_id=process_id,
            owner=owner,
        )  # fmt: skip
    links = [{"href": "/v1/jobs", "rel": "self", "type": "application/json"}]
    if page.next_cursor:
        query = f"limit={limit}&cursor={page.next_cursor}"
        if status is not None:
            query += f"&status={status.value}"
        if process_id is not None:
            query += f"&processID={process_id}"
        if owner is not None:
            query += f"&{urlencode({'owner': owner})}"
        if parent is not None:
            query += f"&{urlencode({'parent': parent})}"
        links.append({"href": f"/v1/jobs?{query}", "rel": "next", "type": "application/json"})
    return {
        "jobs": [_status(j, identity) for j in page.jobs],
        "next_cursor": page.next_cursor,
        "links": links,
    }


@router.get("/{job_id}", summary="A job's status", response_model=None)
def get_job(
    job_id: str,
    request: Request,
    response: Response,
    store: StoreDep,
    registry: RegistryDep,
    pages: PagesDep,
    identity: IdentityDep,
    f: FormatQuery = None,
) -> dict[str, Any] | HTMLResponse:
    job = _job(store, job_id, identity.owner_scope)
    response.headers["Vary"] = "Accept"
    if wants_html(request):
        return _job_page(request, store, registry, pages, job)
    return _status(job, identity)


def _status(job: JobRecord, identity: Identity) -> dict[str, Any]:
    """The status document as this caller may see it (``worker_id``, ``owner``)."""
    return status_document(
        job, worker=identity.sees_workers, owner=identity.sees_owners, admin=identity.admin
    )


def _job_page(
    request: Request, store: JobStore, registry: ProcessRegistry, pages: Pages, job: JobRecord
) -> HTMLResponse:
    result = store.get_result(job.job_id) if job.status is JobStatus.SUCCESSFUL else None
    return views.job_page(request, pages, registry, job, result)


@router.delete("/{job_id}", summary="Dismiss a job (stops a running attempt's process)")
def dismiss_job(job_id: str, store: StoreDep, identity: IdentityDep) -> dict[str, Any]:
    job = store.dismiss(job_id, owner=identity.owner_scope)
    if job is None:
        raise missing_job(store, job_id, identity.owner_scope)
    return _status(job, identity)


def _finished(store: JobStore, job_id: str, owner: str | None = None) -> JobRecord:
    """The job if it succeeded; otherwise the problem that says why it has no results."""
    job = _job(store, job_id, owner)
    if job.status is JobStatus.FAILED:
        raise JobFailed(jobID=job.job_id, error=dict(job.error or {}))
    if job.status is JobStatus.DISMISSED:
        raise JobDismissed(f"Job {job_id} was dismissed; it has no results.")
    if job.status is not JobStatus.SUCCESSFUL:
        raise ResultNotReady(
            f"Job {job_id} is {job.status.value} ({round(job.progress)}%); poll /v1/jobs/{job_id}."
        )
    return job


def finished_document(store: JobStore, job: JobRecord, admin: bool = False) -> dict[str, Any]:
    """The result document of a finished job, or the problem that says why there is none."""
    job = _finished(store, job.job_id)
    result = store.get_result(job.job_id)
    if result is None:  # dismissed between the two reads
        raise JobDismissed(f"Job {job.job_id} was dismissed; it has no results.")
    return results_document(job, result, admin=admin)


@router.get(
    "/{job_id}/results",
    summary="The result document with links to every artifact",
    response_model=None,
)
def get_results(
    job_id: str,
    request: Request,
    response: Response,
    store: StoreDep,
    registry: RegistryDep,
    pages: PagesDep,
    identity: IdentityDep,
    f: FormatQuery = None,
) -> dict[str, Any] | HTMLResponse:
    job = _job(store, job_id, identity.owner_scope)
    response.headers["Vary"] = "Accept"
    if wants_html(request):  # the job's page shows its results (or why there are none)
        return _job_page(request, store, registry, pages, job)
    return finished_document(store, job, identity.admin)


#: The artifact's validator; over-long values are 422 before anything is looked up.
IfNoneMatch = Annotated[str | None, Header(max_length=1000)]


def _artifact(
    store: JobStore, job_id: str, name: str, owner: str | None
) -> tuple[StoredArtifact, dict[str, str]]:
    """The artifact of a successful job, and the headers of its download."""
    job = _finished(store, job_id, owner)
    stored = store.artifact(job_id, name)
    if stored is None:
        names = ", ".join(a.name for a in job.artifacts)
        raise NoSuchArtifact(f"Job {job_id} has no artifact {name!r}; it has: {names}.")
    return stored, artifact_headers(stored)


@router.get(
    "/{job_id}/results/{name}",
    summary="Download one artifact (PNG, SVG, CSV, NPZ)",
    description="`HEAD` answers the same status and headers (`Content-Length`, `ETag`, "
    "the media type) without the bytes.",
)
def get_artifact(
    job_id: str,
    name: str,
    store: StoreDep,
    identity: IdentityDep,
    if_none_match: IfNoneMatch = None,
) -> Response:
    stored, headers = _artifact(store, job_id, name, identity.owner_scope)
    if if_none_match is not None and _etag_matches(if_none_match, headers["ETag"]):
        return Response(status_code=304, headers=headers)
    try:
        chunks = store.artifact_chunks(job_id, stored)
    except FileNotFoundError as exc:  # dismissed between the two reads
        raise JobDismissed(f"Job {job_id} was dismissed; it has no results.") from exc
    except OSError as exc:  # the error names the file: logged with the 503, not shown
        raise StorageError(f"The artifact {name!r} of job {job_id} cannot be read.") from exc
    headers["Content-Length"] = str(stored.info.size)
    return StreamingResponse(chunks, media_type=stored.info.media_type, headers=headers)


@router.head("/{job_id}/results/{name}", include_in_schema=False)
def head_artifact(
    job_id: str,
    name: str,
    store: StoreDep,
    identity: IdentityDep,
    if_none_match: IfNoneMatch = None,
) -> Response:
    """What GET answers, without the bytes (none is read)."""
    stored, headers = _artifact(store, job_id, name, identity.owner_scope)
    if if_none_match is not None and _etag_matches(if_none_match, headers["ETag"]):
        return Response(status_code=304, headers=headers)
    headers["Content-Length"] = str(stored.info.size)
    return Response(status_code=200, headers=headers, media_type=stored.info.media_type)


def _etag_matches(if_none_match: str, etag: str) -> bool:
    tags = {t.strip().removeprefix("W/") for t in if_none_match.split(",")}
    return "*" in tags or etag in tags
