"""``/ogc/``: the landing page, conformance, processes and execution of the façade."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Header, Query, Request
from fastapi.responses import JSONResponse
from starlette.concurrency import run_in_threadpool
from starlette.responses import Response

from service.auth import IdentityDep
from service.deps import DispatcherDep, RegistryDep, SettingsDep, StoreDep
from service.execution import no_cache, wait_while_connected
from service.job_watcher import JobWatcher
from service.ogc import pages as ogc_pages
from service.ogc.execute_request import OgcExecuteRequest
from service.ogc.execution import (
    definition_of,
    job_results,
    outbound_policy,
    submit_execute,
)
from service.ogc.execution_mode import execution_mode, parse_prefer
from service.ogc.jobs.documents import status_info
from service.ogc.process_documents import process_description, process_summary
from service.ogc.schemas import (
    ARTIFACT_CONTENT,
    RESULTS_SCHEMA,
    OgcConfClasses,
    OgcLandingPage,
    OgcProcess,
    OgcProcessList,
    OgcStatusInfo,
)
from service.ogc.urls import public_urls, self_and_alternate
from service.ogc.vocabulary import (
    JSON,
    OGC_PREFIX,
    REL_CONFORMANCE,
    REL_JOB_LIST,
    REL_PROCESSES,
    TAG,
    conformance_classes,
    openapi_media_type,
)
from service.pages import FormatQuery, PagesDep, wants_html
from worker.contract import JobRecord
from worker.store.base import JobStore

__all__ = ["router"]

router = APIRouter(prefix=OGC_PREFIX, tags=[TAG])


def _landing(request: Request) -> dict[str, Any]:
    urls = public_urls(request)
    version = request.app.openapi_version
    return {
        "title": "dexlab: OGC API - Processes",
        "description": "Manipulator kinematic-design processes (dexterity maps, "
        "conditioning maps, optimum designs) as OGC API - Processes - Part 1: Core.",
        "links": [
            *self_and_alternate(f"{urls.ogc}/", "this document"),
            {
                "href": f"{urls.root}/openapi.json",
                "rel": "service-desc",
                "type": openapi_media_type(version),
                "title": f"the API definition (OpenAPI {version})",
            },
            {
                "href": f"{urls.root}/docs",
                "rel": "service-doc",
                "type": "text/html",
                "title": "the API documentation",
            },
            {
                "href": f"{urls.ogc}/conformance",
                "rel": REL_CONFORMANCE,
                "type": JSON,
                "title": "the conformance classes this server meets",
            },
            {
                "href": f"{urls.ogc}/processes",
                "rel": REL_PROCESSES,
                "type": JSON,
                "title": "the processes",
            },
            {"href": f"{urls.ogc}/jobs", "rel": REL_JOB_LIST, "type": JSON, "title": "the jobs"},
        ],
    }


_LANDING: dict[int | str, dict[str, Any]] = {
    200: {"model": OgcLandingPage, "description": "The landing page."}
}


def _answer_landing(request: Request, pages: PagesDep) -> Response:
    document = _landing(request)
    if wants_html(request):
        return ogc_pages.landing_page(request, pages, public_urls(request), document)
    return JSONResponse(document, headers=ogc_pages.NEGOTIATED)


@router.get("/", summary="Landing page", responses=_LANDING, response_model=None)
def landing(request: Request, pages: PagesDep, f: FormatQuery = None) -> Response:
    return _answer_landing(request, pages)


@router.get("", include_in_schema=False, response_model=None)
def landing_without_slash(request: Request, pages: PagesDep, f: FormatQuery = None) -> Response:
    return _answer_landing(request, pages)


@router.get(
    "/conformance",
    summary="The conformance classes this server meets",
    responses={200: {"model": OgcConfClasses, "description": "The conformance declaration."}},
    response_model=None,
)
def conformance(
    request: Request, settings: SettingsDep, pages: PagesDep, f: FormatQuery = None
) -> Response:
    callbacks = outbound_policy(settings).enabled
    document = {"conformsTo": conformance_classes(callbacks, request.app.openapi_version)}
    if wants_html(request):
        return ogc_pages.conformance_page(request, pages, public_urls(request), document)
    return JSONResponse(document, headers=ogc_pages.NEGOTIATED)


@router.get(
    "/processes",
    summary="The processes",
    responses={200: {"model": OgcProcessList, "description": "Process summaries."}},
    response_model=None,
)
def list_processes(
    request: Request,
    registry: RegistryDep,
    pages: PagesDep,
    limit: Annotated[int, Query(ge=1, le=10000, description="Most summaries per page.")] = 10,
    offset: Annotated[
        int, Query(ge=0, le=1_000_000, description="Summaries to skip (next links).")
    ] = 0,
    f: FormatQuery = None,
) -> Response:
    urls = public_urls(request)
    definitions = list(registry)
    page = definitions[offset : offset + limit]
    links = self_and_alternate(
        f"{urls.ogc}/processes?limit={limit}&offset={offset}", "this page of processes"
    )
    if offset + limit < len(definitions):
        links.append(
            {
                "href": f"{urls.ogc}/processes?limit={limit}&offset={offset + limit}",
                "rel": "next",
                "type": JSON,
                "title": "the next page",
            }
        )
    document = {"processes": [process_summary(d, urls) for d in page], "links": links}
    if wants_html(request):
        return ogc_pages.process_list_page(request, pages, urls, page, document)
    return JSONResponse(document, headers=ogc_pages.NEGOTIATED)


@router.get(
    "/processes/{processID}",
    summary="A process: its inputs and outputs",
    responses={200: {"model": OgcProcess, "description": "The OGC process description."}},
    response_model=None,
)
def describe_process(
    processID: str,
    request: Request,
    registry: RegistryDep,
    pages: PagesDep,
    f: FormatQuery = None,
) -> Response:
    definition = definition_of(registry, processID)
    urls = public_urls(request)
    document = process_description(definition, urls)
    if wants_html(request):
        return ogc_pages.process_page(request, pages, registry, urls, definition, document)
    return JSONResponse(document, headers=ogc_pages.NEGOTIATED)


_EXECUTE_RESPONSES: dict[int | str, dict[str, Any]] = {
    200: {
        "description": "Run synchronously: the results, as `response` asked (a results "
        "document, one output in its own media type, or multipart/related).  "
        "`Link: <job>; rel=monitor` names the job.",
        "content": {JSON: {"schema": RESULTS_SCHEMA}, **ARTIFACT_CONTENT},
    },
    201: {
        "model": OgcStatusInfo,
        "description": "Run asynchronously: the job's status; `Location` is the job.",
    },
    204: {
        "description": "Run synchronously, `response=raw`, every output by reference: "
        "one `Link` header per output."
    },
}


@router.post(
    "/processes/{processID}/execution",
    summary="Execute a process (synchronously or not, as the standard negotiates)",
    responses=_EXECUTE_RESPONSES,
    response_model=None,
    status_code=201,
)
async def execute(
    processID: str,
    body: OgcExecuteRequest,
    request: Request,
    store: StoreDep,
    registry: RegistryDep,
    settings: SettingsDep,
    dispatcher: DispatcherDep,
    identity: IdentityDep,
    idempotency_key: Annotated[
        str | None, Header(alias="Idempotency-Key", min_length=1, max_length=255)
    ] = None,
    prefer: Annotated[str | None, Header(max_length=255)] = None,
    cache_control: Annotated[str | None, Header(alias="Cache-Control", max_length=255)] = None,
) -> Response:
    """Create a job.  With no `Prefer`, a process that can run synchronously (its
    `sync-execute`, within its `sync_cost_limit`) answers with the results (waiting at
    most 60 s); `Prefer: respond-async` answers 201 at once; `respond-sync` and
    `wait=N` are honoured where the process allows (`Preference-Applied`)."""
    preferences = parse_prefer(prefer)
    urls = public_urls(request)
    submitted = await run_in_threadpool(
        submit_execute,
        store,
        registry,
        settings,
        dispatcher,
        processID,
        body,
        idempotency_key,
        not preferences.respond_async,
        urls.root,
        identity.name,
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
            job_results, store, registry, job_id, urls, submitted.presentation, headers
        )
    if mode.applied_if_async:
        headers["Preference-Applied"] = mode.applied_if_async
    job = submitted.job
    if mode.synchronous:  # waited in vain: the status as it is now
        job = await run_in_threadpool(_current, store, job)
    return JSONResponse(status_info(job, urls), status_code=201, headers=headers)


def _current(store: JobStore, job: JobRecord) -> JobRecord:
    return store.get_job(job.job_id) or job
