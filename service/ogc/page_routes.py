"""The façade's pages: ``/ogc/...`` for a client that asks for HTML.

Each is an :class:`~service.pages.html_route.HtmlRoute` on the same path as its JSON
route (:mod:`service.ogc.routes`, :mod:`service.ogc.jobs.routes`), which answers any
other request; the parameters are the JSON route's, so a bad one is the same problem
(a page).  Each draws the document its JSON route answers
(:mod:`service.ogc.pages`).
"""

from __future__ import annotations

from fastapi import Request
from fastapi.responses import HTMLResponse
from starlette.responses import Response

from service.deps import Api, ApiDep
from service.documents import as_json
from service.job_lookup import find_job
from service.ogc import pages as ogc_pages
from service.ogc.execute_request import Presentation
from service.ogc.execution import definition_of, finished_job, headers_only, job_output
from service.ogc.jobs.documents import status_info
from service.ogc.jobs.listing import JobListQueryDep, job_list_document
from service.ogc.landing import conformance_document, landing_document
from service.ogc.outputs import process_outputs
from service.ogc.process_documents import process_description, process_list
from service.ogc.results import select_outputs
from service.ogc.routes import ProcessListLimit, ProcessListOffset
from service.ogc.urls import public_urls
from service.ogc.vocabulary import OGC_PREFIX
from service.pages.html_route import page_router
from service.pages.renderer import PagesDep
from worker.contract import JobStatus

__all__ = ["router"]

router = page_router(prefix=OGC_PREFIX)


@router.get("/")
@router.get("")
def landing(request: Request, pages: PagesDep) -> HTMLResponse:
    urls = public_urls(request)
    document = as_json(landing_document(urls, request.app.openapi_version))
    return ogc_pages.landing_page(request, pages, urls, document)


@router.get("/conformance")
def conformance(request: Request, api: ApiDep) -> HTMLResponse:
    document = as_json(conformance_document(api.settings, request.app.openapi_version))
    return ogc_pages.conformance_page(request, api.pages, public_urls(request), document)


@router.get("/processes")
def process_list_page(
    request: Request,
    api: ApiDep,
    limit: ProcessListLimit = 10,
    offset: ProcessListOffset = 0,
) -> HTMLResponse:
    urls = public_urls(request)
    page, document = process_list(list(api.registry), urls, limit, offset)
    return ogc_pages.process_list_page(request, api.pages, urls, page, as_json(document))


@router.get("/processes/{processID}")
def process_page(processID: str, request: Request, api: ApiDep) -> HTMLResponse:
    definition = definition_of(api.registry, processID)
    urls = public_urls(request)
    document = as_json(process_description(definition, urls))
    return ogc_pages.process_page(request, api.pages, api.registry, urls, definition, document)


@router.get("/jobs")
def job_list_page(request: Request, api: ApiDep, query: JobListQueryDep) -> HTMLResponse:
    document = as_json(job_list_document(request, api, query))
    return ogc_pages.job_list_page(
        request, api.pages, api.registry, public_urls(request), document, query.limit
    )


@router.get("/jobs/{jobID}")
def job_page(jobID: str, request: Request, api: ApiDep) -> HTMLResponse:
    job = find_job(api.store, jobID, api.identity.owner_scope)
    urls = public_urls(request)
    result = api.store.get_result(jobID) if job.status is JobStatus.SUCCESSFUL else None
    return ogc_pages.job_page(
        request,
        api.pages,
        api.registry,
        urls,
        job,
        result,
        as_json(status_info(job, urls, admin=api.identity.admin)),
    )


@router.get("/jobs/{jobID}/results")
def results_page(jobID: str, request: Request, api: ApiDep) -> HTMLResponse:
    """The job's page, with the outputs its request selected (or why there are none)."""
    urls = public_urls(request)
    job, result = finished_job(api.store, jobID, api.identity.owner_scope)
    presentation = Presentation.from_json(api.store.request_options(jobID)[0])
    definition = api.registry.get(job.process_id)
    outputs = process_outputs(definition) if definition is not None else {}
    selected = select_outputs(job, result, outputs, presentation, api.store)
    document = as_json(status_info(job, urls, admin=api.identity.admin))
    return ogc_pages.results_page(
        request, api.pages, api.registry, urls, job, result, document, selected,
        presentation.response,
    )  # fmt: skip


def _output_page(request: Request, api: Api, jobID: str, outputID: str) -> HTMLResponse:
    output = job_output(api.store, api.registry, jobID, outputID, api.identity.owner_scope)
    urls = public_urls(request)
    return ogc_pages.output_page(
        request, api.pages, urls, output.job, output.spec, value=output.value,
        stored=output.stored,
    )  # fmt: skip


@router.get("/jobs/{jobID}/results/{outputID}")
def output_page(jobID: str, outputID: str, request: Request, api: ApiDep) -> HTMLResponse:
    return _output_page(request, api, jobID, outputID)


@router.head("/jobs/{jobID}/results/{outputID}")
def output_page_head(jobID: str, outputID: str, request: Request, api: ApiDep) -> Response:
    """What GET answers, without the page."""
    return headers_only(_output_page(request, api, jobID, outputID))
