"""``/ogc/``: the landing page, conformance, processes and execution of the façade."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Query, Request
from starlette.concurrency import run_in_threadpool
from starlette.responses import Response

from service.deps import ApiDep, RegistryDep, SettingsDep
from service.execution import no_cache, wait_while_connected
from service.job_watcher import JobWatcher
from service.ogc import pages as ogc_pages
from service.ogc.execute_request import OgcExecuteRequest
from service.ogc.execution import (
    definition_of,
    job_results,
    submit_execute,
)
from service.ogc.execution_mode import execution_mode, parse_prefer
from service.ogc.jobs.documents import status_info
from service.ogc.landing import conformance_document, landing_document
from service.ogc.process_documents import process_description, process_list
from service.ogc.schemas import (
    ARTIFACT_CONTENT,
    RESULTS_SCHEMA,
    OgcConfClasses,
    OgcLandingPage,
    OgcProcess,
    OgcProcessList,
    OgcStatusInfo,
)
from service.ogc.urls import public_urls
from service.ogc.vocabulary import JSON, OGC_PREFIX, TAG
from service.pages import FormatQuery
from service.parameters import CacheControlHeader, IdempotencyKey, PreferHeader
from worker.contract import JobRecord
from worker.store.base import JobStore

__all__ = ["ProcessListLimit", "ProcessListOffset", "router"]

router = APIRouter(prefix=OGC_PREFIX, tags=[TAG])

# The pages at these URLs (?f=html, Accept: text/html): service.ogc.page_routes.


@router.get(
    "/",
    summary="Landing page",
    response_model=OgcLandingPage,
    response_description="The landing page.",
    response_model_exclude_unset=True,
)
def landing(request: Request, response: Response, f: FormatQuery = None) -> OgcLandingPage:
    response.headers.update(ogc_pages.NEGOTIATED)
    return landing_document(public_urls(request), request.app.openapi_version)


@router.get(
    "",
    include_in_schema=False,
    response_model=OgcLandingPage,
    response_model_exclude_unset=True,
)
def landing_without_slash(
    request: Request, response: Response, f: FormatQuery = None
) -> OgcLandingPage:
    return landing(request, response)


@router.get(
    "/conformance",
    summary="The conformance classes this server meets",
    response_model=OgcConfClasses,
    response_description="The conformance declaration.",
    response_model_exclude_unset=True,
)
def conformance(
    request: Request, response: Response, settings: SettingsDep, f: FormatQuery = None
) -> OgcConfClasses:
    response.headers.update(ogc_pages.NEGOTIATED)
    return conformance_document(settings, request.app.openapi_version)


ProcessListLimit = Annotated[int, Query(ge=1, le=10000, description="Most summaries per page.")]
ProcessListOffset = Annotated[
    int, Query(ge=0, le=1_000_000, description="Summaries to skip (next links).")
]


@router.get(
    "/processes",
    summary="The processes",
    response_model=OgcProcessList,
    response_description="Process summaries.",
    response_model_exclude_unset=True,
)
def list_processes(
    request: Request,
    response: Response,
    registry: RegistryDep,
    limit: ProcessListLimit = 10,
    offset: ProcessListOffset = 0,
    f: FormatQuery = None,
) -> OgcProcessList:
    _, document = process_list(list(registry), public_urls(request), limit, offset)
    response.headers.update(ogc_pages.NEGOTIATED)
    return document


@router.get(
    "/processes/{processID}",
    summary="A process: its inputs and outputs",
    response_model=OgcProcess,
    response_description="The OGC process description.",
    response_model_exclude_unset=True,
)
def describe_process(
    processID: str,
    request: Request,
    response: Response,
    registry: RegistryDep,
    f: FormatQuery = None,
) -> OgcProcess:
    definition = definition_of(registry, processID)
    response.headers.update(ogc_pages.NEGOTIATED)
    return process_description(definition, public_urls(request))


_EXECUTE_RESPONSES: dict[int | str, dict[str, Any]] = {
    200: {
        "description": "Run synchronously: the results, as `response` asked (a results "
        "document, one output in its own media type, or multipart/related).  "
        "`Link: <job>; rel=monitor` names the job.",
        "content": {JSON: {"schema": RESULTS_SCHEMA}, **ARTIFACT_CONTENT},
    },
    201: {"description": "Run asynchronously: the job's status; `Location` is the job."},
    204: {
        "description": "Run synchronously, `response=raw`, every output by reference: "
        "one `Link` header per output."
    },
}


@router.post(
    "/processes/{processID}/execution",
    summary="Execute a process (synchronously or not, as the standard negotiates)",
    responses=_EXECUTE_RESPONSES,
    response_model=OgcStatusInfo,
    response_model_exclude_unset=True,
    status_code=201,
)
async def execute(
    processID: str,
    body: OgcExecuteRequest,
    request: Request,
    response: Response,
    api: ApiDep,
    idempotency_key: IdempotencyKey = None,
    prefer: PreferHeader = None,
    cache_control: CacheControlHeader = None,
) -> OgcStatusInfo | Response:
    """Create a job.  With no `Prefer`, a process that can run synchronously (its
    `sync-execute`, within its `sync_cost_limit`) answers with the results (waiting at
    most 60 s); `Prefer: respond-async` answers 201 at once; `respond-sync` and
    `wait=N` are honoured where the process allows (`Preference-Applied`)."""
    preferences = parse_prefer(prefer)
    urls = public_urls(request)
    submitted = await run_in_threadpool(
        submit_execute,
        api.store,
        api.registry,
        api.settings,
        api.dispatcher,
        processID,
        body,
        idempotency_key,
        not preferences.respond_async,
        urls.root,
        api.identity.name,
        no_cache(cache_control),
    )
    mode = execution_mode(preferences, submitted.can_run_sync)
    job_id = submitted.job.job_id
    headers = {"Location": urls.job(job_id)}
    if not submitted.created:
        headers["Idempotent-Replayed"] = "true"
    watcher: JobWatcher = request.app.state.watcher
    reused = submitted.job.reused_from is not None  # finished already: no wait at all
    if mode.synchronous and (
        reused or await wait_while_connected(request, watcher, job_id, mode.wait_s)
    ):
        headers["Link"] = f'<{urls.job(job_id)}>; rel="monitor"; type="{JSON}"'
        if mode.applied_if_sync:
            headers["Preference-Applied"] = mode.applied_if_sync
        return await run_in_threadpool(
            job_results, api.store, api.registry, job_id, urls, submitted.presentation, headers
        )
    if mode.applied_if_async:
        headers["Preference-Applied"] = mode.applied_if_async
    job = submitted.job
    if mode.synchronous:  # waited in vain: the status as it is now
        job = await run_in_threadpool(_current, api.store, job)
    response.headers.update(headers)
    return status_info(job, urls, admin=api.identity.admin)


def _current(store: JobStore, job: JobRecord) -> JobRecord:
    return store.get_job(job.job_id) or job
