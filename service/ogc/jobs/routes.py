"""``/ogc/jobs``: the job list, a job's status, its results, dismissal (JSON; the pages
at these URLs are :mod:`service.ogc.page_routes`).

A caller sees its own jobs (an admin key every owner's, ``owner`` selecting one);
another owner's job is ``no-such-job``.
"""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import JSONResponse
from starlette.responses import Response, StreamingResponse

from service.deps import Api, ApiDep
from service.documents import artifact_headers
from service.job_lookup import find_job, missing_job
from service.ogc import pages as ogc_pages
from service.ogc.execution import headers_only, job_output, job_results
from service.ogc.jobs.documents import status_info
from service.ogc.jobs.listing import JobListQueryDep, job_list_document
from service.ogc.schemas import ARTIFACT_CONTENT, RESULTS_SCHEMA, OgcJobList, OgcStatusInfo
from service.ogc.urls import public_urls
from service.ogc.vocabulary import JSON, OGC_PREFIX, TAG
from service.pages import FormatQuery
from worker.errors import NoSuchJob, StorageError

__all__ = ["router"]

router = APIRouter(prefix=f"{OGC_PREFIX}/jobs", tags=[TAG])


@router.get(
    "",
    summary="The jobs, newest first",
    response_model=OgcJobList,
    response_description="A page of jobs.",
    response_model_exclude_unset=True,
)
def list_jobs(
    request: Request,
    response: Response,
    api: ApiDep,
    query: JobListQueryDep,
    f: FormatQuery = None,
) -> OgcJobList:
    response.headers.update(ogc_pages.NEGOTIATED)
    return job_list_document(request, api, query)


@router.get(
    "/{jobID}",
    summary="A job's status",
    response_model=OgcStatusInfo,
    response_model_exclude_unset=True,
    response_description="The job's status information.",
)
def get_job(
    jobID: str, request: Request, response: Response, api: ApiDep, f: FormatQuery = None
) -> OgcStatusInfo:
    job = find_job(api.store, jobID, api.identity.owner_scope)
    response.headers.update(ogc_pages.NEGOTIATED)
    return status_info(job, public_urls(request), admin=api.identity.admin)


@router.delete(
    "/{jobID}",
    summary="Dismiss a job (a queued job never runs, a running one is stopped, a "
    "finished one's results are deleted)",
    response_model=OgcStatusInfo,
    response_model_exclude_unset=True,
    response_description="The job's status information.",
)
def dismiss_job(jobID: str, request: Request, api: ApiDep) -> OgcStatusInfo:
    job = api.store.dismiss(jobID, owner=api.identity.owner_scope)
    if job is None:
        raise missing_job(api.store, jobID, api.identity.owner_scope)
    return status_info(job, public_urls(request), admin=api.identity.admin)


# The results and outputs are not one document: the execute request chose their form
# (a results document, one output in its own media type, multipart/related, Link
# headers).  Their responses are described below; the handlers return the Response.

_RESULTS: dict[int | str, dict[str, Any]] = {
    200: {
        "description": "The results, as the execute request asked (`response`, `outputs`): "
        "a results document, one output in its own media type, or multipart/related.  "
        "A job created through /v1 answers a results document of every output.",
        "content": {JSON: {"schema": RESULTS_SCHEMA}, **ARTIFACT_CONTENT},
    },
    204: {"description": "`response=raw` with every output by reference: `Link` headers."},
}


@router.get(
    "/{jobID}/results",
    summary="A finished job's results (its failure, if it failed)",
    responses=_RESULTS,
)
def get_results(jobID: str, request: Request, api: ApiDep, f: FormatQuery = None) -> Response:
    return job_results(
        api.store, api.registry, jobID, public_urls(request), headers=ogc_pages.NEGOTIATED,
        owner=api.identity.owner_scope,
    )  # fmt: skip


_OUTPUT: dict[int | str, dict[str, Any]] = {
    200: {
        "description": "One output: a result member as JSON, or a file's bytes.",
        "content": {JSON: {"schema": {}}, **ARTIFACT_CONTENT},
    },
}


@router.get(
    "/{jobID}/results/{outputID}",
    summary="One output of a finished job (where a by-reference output links to)",
    description="`HEAD` answers the same status and headers without the content.",
    responses=_OUTPUT,
)
def get_output(jobID: str, outputID: str, api: ApiDep, f: FormatQuery = None) -> Response:
    return _output(jobID, outputID, api, content=True)


@router.head("/{jobID}/results/{outputID}", include_in_schema=False)
def head_output(jobID: str, outputID: str, api: ApiDep, f: FormatQuery = None) -> Response:
    """What GET answers, without the content (a file's bytes are not read)."""
    return _output(jobID, outputID, api, content=False)


def _output(jobID: str, outputID: str, api: Api, *, content: bool) -> Response:
    """One output (``content``: with its content; else only the status and headers)."""
    output = job_output(api.store, api.registry, jobID, outputID, api.identity.owner_scope)
    stored = output.stored
    if stored is None:  # a result member
        answer = JSONResponse(output.value, headers=ogc_pages.NEGOTIATED)
        return answer if content else headers_only(answer)
    headers = {
        **artifact_headers(stored),
        **ogc_pages.NEGOTIATED,
        "Content-Length": str(stored.info.size),
    }
    if not content:
        return Response(status_code=200, headers=headers, media_type=stored.info.media_type)
    try:
        chunks = api.store.artifact_chunks(jobID, stored)
    except FileNotFoundError as exc:  # dismissed between the two reads
        raise NoSuchJob(f"Job {jobID} was dismissed; its results were deleted.") from exc
    except OSError as exc:  # the error names the file: logged with the 503, not shown
        raise StorageError(f"The output {outputID!r} of job {jobID} cannot be read.") from exc
    return StreamingResponse(chunks, media_type=stored.info.media_type, headers=headers)
