"""The pages at the JSON API's URLs: ``/``, ``/v1``, ``/v1/processes[/{id}]``,
``/v1/jobs[/{id}[/results]]`` for a client that asks for HTML.

Each is an :class:`~service.pages.html_route.HtmlRoute` on the same path as its JSON
route (:mod:`service.routes`), which answers every other request.  The parameters are
declared as the JSON route declares them, so a bad one is the same problem (as a page).
"""

from __future__ import annotations

from fastapi import Request
from fastapi.responses import HTMLResponse

from service.deps import Api, ApiDep
from service.job_lookup import find_job, list_jobs
from service.pages import views
from service.pages.html_route import page_router
from service.pages.study_page import study_context
from service.parameters import JobListQueryDep
from worker.contract import JobStatus

__all__ = ["router"]

router = page_router()


@router.get("/")
@router.get("/v1")
def landing(request: Request, api: ApiDep) -> HTMLResponse:
    return views.landing_page(request, api.pages, api.registry)


# The process pages read templates and method files: plain ``def``, in the threadpool.


@router.get("/v1/processes")
def process_list(request: Request, api: ApiDep) -> HTMLResponse:
    return views.process_list_page(request, api.pages, api.registry)


@router.get("/v1/processes/{process_id}")
def process(process_id: str, request: Request, api: ApiDep) -> HTMLResponse:
    definition = api.registry.require(process_id)
    return views.process_page(request, api.pages, api.registry, definition)


@router.get("/v1/jobs")
def job_list(request: Request, api: ApiDep, query: JobListQueryDep) -> HTMLResponse:
    page = list_jobs(api.store, api.identity, query)
    return views.job_list_page(
        request, api.pages, api.registry, page, limit=query.limit, status=query.status,
        process_id=query.process_id, owner=query.owner,
    )  # fmt: skip


def _job_page(request: Request, api: Api, job_id: str) -> HTMLResponse:
    job = find_job(api.store, job_id, api.identity.owner_scope)
    result = api.store.get_result(job.job_id) if job.status is JobStatus.SUCCESSFUL else None
    extra = study_context(request, api, job, result)  # a design study's explorer
    return views.job_page(request, api.pages, api.registry, job, result, extra=extra)


@router.get("/v1/jobs/{job_id}")
def job(job_id: str, request: Request, api: ApiDep) -> HTMLResponse:
    return _job_page(request, api, job_id)


@router.get("/v1/jobs/{job_id}/results")
def results(job_id: str, request: Request, api: ApiDep) -> HTMLResponse:
    """The job's page shows its results (or why there are none)."""
    return _job_page(request, api, job_id)
