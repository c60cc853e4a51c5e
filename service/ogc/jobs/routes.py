"""``/ogc/jobs``: the job list, a job's status, its results, dismissal.

A caller sees its own jobs (an admin key every owner's, ``owner`` selecting one);
another owner's job is ``no-such-job``.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from fastapi import APIRouter, Query, Request
from fastapi.responses import JSONResponse
from pydantic import AfterValidator, StringConstraints
from starlette.responses import Response, StreamingResponse

from service.auth import Identity, IdentityDep
from service.deps import RegistryDep, StoreDep
from service.documents import artifact_headers
from service.job_lookup import find_job, missing_job
from service.ogc import pages as ogc_pages
from service.ogc.execute_request import Presentation
from service.ogc.execution import finished_job, job_results
from service.ogc.jobs.documents import job_list, status_info
from service.ogc.jobs.query import MAX_PAGE, listing_filter, page_query, parse_datetime_interval
from service.ogc.outputs import process_outputs
from service.ogc.results import select_outputs
from service.ogc.schemas import ARTIFACT_CONTENT, RESULTS_SCHEMA, OgcJobList, OgcStatusInfo
from service.ogc.urls import public_urls
from service.ogc.vocabulary import JSON, OGC_PREFIX, TAG
from service.pages import FormatQuery, Pages, PagesDep, wants_html
from service.parameters import CursorQuery
from service.problems import parameter_error
from worker.contract import JobStatus
from worker.errors import NoSuchArtifact, NoSuchJob, NoSuchProcess, StorageError
from worker.processes import ProcessRegistry
from worker.store.base import JobStore

__all__ = ["router"]

router = APIRouter(prefix=f"{OGC_PREFIX}/jobs", tags=[TAG])


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


@router.get(
    "",
    summary="The jobs, newest first",
    responses={200: {"model": OgcJobList, "description": "A page of jobs."}},
    response_model=None,
)
def list_jobs(
    request: Request,
    store: StoreDep,
    registry: RegistryDep,
    pages: PagesDep,
    identity: IdentityDep,
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
    f: FormatQuery = None,
) -> Response:
    scope = identity.owner_filter(owner)
    unknown = sorted(set(processID or ()) - set(registry.ids()))
    if unknown:  # the API definition lists the IDs: a bad value, like any other
        unknown_id = NoSuchProcess.named(unknown[0], registry.ids())
        raise parameter_error("query", "processID", unknown_id.detail)
    where = listing_filter(
        processID,
        status,
        job_type,
        None if datetime is None else parse_datetime_interval(datetime),
        minDuration,
        maxDuration,
    )
    page = store.list_jobs(limit=min(limit, MAX_PAGE), cursor=cursor, where=where, owner=scope)
    urls = public_urls(request)
    params = [(k, v) for k, v in request.query_params.multi_items() if k != "f"]
    self_href = f"{urls.ogc}/jobs" + (f"?{page_query(params, cursor)}" if params else "")
    next_href = (
        None
        if page.next_cursor is None
        else f"{urls.ogc}/jobs?{page_query(params, page.next_cursor)}"
    )
    document = job_list(page.jobs, urls, self_href, next_href)
    if wants_html(request):
        return ogc_pages.job_list_page(request, pages, registry, urls, document, limit)
    return JSONResponse(document, headers=ogc_pages.NEGOTIATED)


_STATUS: dict[int | str, dict[str, Any]] = {
    200: {"model": OgcStatusInfo, "description": "The job's status information."}
}


@router.get("/{jobID}", summary="A job's status", responses=_STATUS, response_model=None)
def get_job(
    jobID: str,
    request: Request,
    store: StoreDep,
    registry: RegistryDep,
    pages: PagesDep,
    identity: IdentityDep,
    f: FormatQuery = None,
) -> Response:
    job = find_job(store, jobID, identity.owner_scope)
    urls = public_urls(request)
    document = status_info(job, urls)
    if wants_html(request):
        result = store.get_result(jobID) if job.status is JobStatus.SUCCESSFUL else None
        return ogc_pages.job_page(request, pages, registry, urls, job, result, document)
    return JSONResponse(document, headers=ogc_pages.NEGOTIATED)


@router.delete(
    "/{jobID}",
    summary="Dismiss a job (a queued job never runs, a running one is stopped, a "
    "finished one's results are deleted)",
    responses=_STATUS,
    response_model=None,
)
def dismiss_job(
    jobID: str, request: Request, store: StoreDep, identity: IdentityDep
) -> JSONResponse:
    job = store.dismiss(jobID, owner=identity.owner_scope)
    if job is None:
        raise missing_job(store, jobID, identity.owner_scope)
    return JSONResponse(status_info(job, public_urls(request)))


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
    response_model=None,
)
def get_results(
    jobID: str,
    request: Request,
    store: StoreDep,
    registry: RegistryDep,
    pages: PagesDep,
    identity: IdentityDep,
    f: FormatQuery = None,
) -> Response:
    urls = public_urls(request)
    owner = identity.owner_scope
    if not wants_html(request):
        return job_results(store, registry, jobID, urls, headers=ogc_pages.NEGOTIATED, owner=owner)
    # A page: the job's, with the outputs its request selected (or why there are none).
    job, result = finished_job(store, jobID, owner)
    presentation = Presentation.from_json(store.request_options(jobID)[0])
    definition = registry.get(job.process_id)
    outputs = process_outputs(definition) if definition is not None else {}
    selected = select_outputs(job, result, outputs, presentation, store)
    document = status_info(job, urls)
    return ogc_pages.results_page(
        request, pages, registry, urls, job, result, document, selected, presentation.response
    )


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
    response_model=None,
)
def get_output(
    jobID: str,
    outputID: str,
    request: Request,
    store: StoreDep,
    registry: RegistryDep,
    pages: PagesDep,
    identity: IdentityDep,
    f: FormatQuery = None,
) -> Response:
    return _output(jobID, outputID, request, store, registry, pages, identity, content=True)


@router.head("/{jobID}/results/{outputID}", include_in_schema=False, response_model=None)
def head_output(
    jobID: str,
    outputID: str,
    request: Request,
    store: StoreDep,
    registry: RegistryDep,
    pages: PagesDep,
    identity: IdentityDep,
    f: FormatQuery = None,
) -> Response:
    """What GET answers, without the content (a file's bytes are not read)."""
    return _output(jobID, outputID, request, store, registry, pages, identity, content=False)


def _headers_only(response: Response) -> Response:
    """``response``'s status and headers (its ``Content-Length`` too), without a body."""
    return Response(status_code=response.status_code, headers=dict(response.headers))


def _output(
    jobID: str,
    outputID: str,
    request: Request,
    store: JobStore,
    registry: ProcessRegistry,
    pages: Pages,
    identity: Identity,
    *,
    content: bool,
) -> Response:
    """One output (``content``: with its content; else only the status and headers)."""
    job, result = finished_job(store, jobID, identity.owner_scope)
    definition = registry.get(job.process_id)
    spec = process_outputs(definition).get(outputID) if definition is not None else None
    page = wants_html(request)
    answer: Response
    if spec is not None and not spec.artifact and outputID in result:
        if page:
            urls = public_urls(request)
            answer = ogc_pages.output_page(request, pages, urls, job, spec, value=result[outputID])
        else:
            answer = JSONResponse(result[outputID], headers=ogc_pages.NEGOTIATED)
        return answer if content else _headers_only(answer)
    stored = store.artifact(jobID, outputID) if spec is not None and spec.artifact else None
    if spec is None or stored is None:
        raise NoSuchArtifact(f"Job {jobID} has no output {outputID!r}.")
    if page:
        urls = public_urls(request)
        answer = ogc_pages.output_page(request, pages, urls, job, spec, stored=stored)
        return answer if content else _headers_only(answer)
    headers = {
        **artifact_headers(stored),
        **ogc_pages.NEGOTIATED,
        "Content-Length": str(stored.info.size),
    }
    if not content:
        return Response(status_code=200, headers=headers, media_type=stored.info.media_type)
    try:
        chunks = store.artifact_chunks(jobID, stored)
    except FileNotFoundError as exc:  # dismissed between the two reads
        raise NoSuchJob(f"Job {jobID} was dismissed; its results were deleted.") from exc
    except OSError as exc:  # the error names the file: logged with the 503, not shown
        raise StorageError(f"The output {outputID!r} of job {jobID} cannot be read.") from exc
    return StreamingResponse(chunks, media_type=stored.info.media_type, headers=headers)
