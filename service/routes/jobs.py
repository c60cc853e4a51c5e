"""``/v1/jobs``: status, listing, results, artifacts and dismissal.

Each caller sees its own jobs (an admin key every owner's): another owner's job is
404 ``no-such-job`` on every route, as if it did not exist.  An expired job (its
retention ended) is 410 ``job-expired`` for a while, then 404
(:mod:`service.job_lookup`).
"""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Header, Response
from fastapi.responses import StreamingResponse

from service.auth import Identity
from service.deps import ApiDep
from service.documents import artifact_headers, results_document, status_document
from service.job_lookup import find_job, missing_job
from service.job_lookup import list_jobs as find_jobs
from service.pages import FormatQuery
from service.parameters import JobListQueryDep
from service.schemas import JobList, Link, ResultsDocument, StatusDocument
from worker.contract import JobRecord, JobStatus
from worker.errors import (
    JobDismissed,
    JobFailed,
    NoSuchArtifact,
    ResultNotReady,
    StorageError,
)
from worker.store.base import JobStore, StoredArtifact

__all__ = ["finished_document", "finished_job", "router"]

router = APIRouter(prefix="/v1/jobs", tags=["jobs"])

JSON = "application/json"


def _job(store: JobStore, job_id: str, owner: str | None = None) -> JobRecord:
    """The job, if it exists and ``owner`` (None: anyone) owns it; else no-such-job
    (or job-expired)."""
    return find_job(store, job_id, owner)


# The GET routes that have a page (?f=html, Accept: text/html): service.pages.routes.


@router.get(
    "",
    summary="List jobs, newest first",
    response_model=JobList,
    response_model_exclude_unset=True,
)
def list_jobs(
    response: Response, api: ApiDep, query: JobListQueryDep, f: FormatQuery = None
) -> JobList:
    page = find_jobs(api.store, api.identity, query)
    response.headers["Vary"] = "Accept"
    links = [Link(href="/v1/jobs", rel="self", type=JSON)]
    if page.next_cursor:
        links.append(Link(href=query.next_href(page.next_cursor), rel="next", type=JSON))
    return JobList(
        jobs=[_status(j, api.identity) for j in page.jobs],
        next_cursor=page.next_cursor,
        links=links,
    )


@router.get(
    "/{job_id}",
    summary="A job's status",
    response_model=StatusDocument,
    response_model_exclude_unset=True,
)
def get_job(job_id: str, response: Response, api: ApiDep, f: FormatQuery = None) -> StatusDocument:
    job = _job(api.store, job_id, api.identity.owner_scope)
    response.headers["Vary"] = "Accept"
    return _status(job, api.identity)


def _status(job: JobRecord, identity: Identity) -> StatusDocument:
    """The status document as this caller may see it (``worker_id``, ``owner``)."""
    return status_document(
        job, worker=identity.sees_workers, owner=identity.sees_owners, admin=identity.admin
    )


@router.delete(
    "/{job_id}",
    summary="Dismiss a job (stops a running attempt's process)",
    response_model=StatusDocument,
    response_model_exclude_unset=True,
)
def dismiss_job(job_id: str, api: ApiDep) -> StatusDocument:
    job = api.store.dismiss(job_id, owner=api.identity.owner_scope)
    if job is None:
        raise missing_job(api.store, job_id, api.identity.owner_scope)
    return _status(job, api.identity)


def finished_job(store: JobStore, job_id: str, owner: str | None = None) -> JobRecord:
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


def finished_document(store: JobStore, job: JobRecord, admin: bool = False) -> ResultsDocument:
    """The result document of a finished job, or the problem that says why there is none."""
    job = finished_job(store, job.job_id)
    result = store.get_result(job.job_id)
    if result is None:  # dismissed between the two reads
        raise JobDismissed(f"Job {job.job_id} was dismissed; it has no results.")
    return results_document(job, result, admin=admin)


@router.get(
    "/{job_id}/results",
    summary="The result document with links to every artifact",
    response_model=ResultsDocument,
    response_model_exclude_unset=True,
)
def get_results(
    job_id: str, response: Response, api: ApiDep, f: FormatQuery = None
) -> ResultsDocument:
    job = _job(api.store, job_id, api.identity.owner_scope)
    response.headers["Vary"] = "Accept"
    return finished_document(api.store, job, api.identity.admin)


#: The artifact's validator; over-long values are 422 before anything is looked up.
IfNoneMatch = Annotated[str | None, Header(max_length=1000)]


def _artifact(
    store: JobStore, job_id: str, name: str, owner: str | None
) -> tuple[StoredArtifact, dict[str, str]]:
    """The artifact of a successful job, and the headers of its download."""
    job = finished_job(store, job_id, owner)
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
    api: ApiDep,
    if_none_match: IfNoneMatch = None,
) -> Response:
    store = api.store
    stored, headers = _artifact(store, job_id, name, api.identity.owner_scope)
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
    api: ApiDep,
    if_none_match: IfNoneMatch = None,
) -> Response:
    """What GET answers, without the bytes (none is read)."""
    stored, headers = _artifact(api.store, job_id, name, api.identity.owner_scope)
    if if_none_match is not None and _etag_matches(if_none_match, headers["ETag"]):
        return Response(status_code=304, headers=headers)
    headers["Content-Length"] = str(stored.info.size)
    return Response(status_code=200, headers=headers, media_type=stored.info.media_type)


def _etag_matches(if_none_match: str, etag: str) -> bool:
    tags = {t.strip().removeprefix("W/") for t in if_none_match.split(",")}
    return "*" in tags or etag in tags
