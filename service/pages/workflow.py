"""Pages about jobs, beside their status pages (``/pages/``, not in the OpenAPI
document; no JavaScript needed):

- ``GET /pages/jobs/{jobID}/edit``: "Edit and run again": the job's process page with
  a first form holding the job's inputs; it posts to ``/pages/processes/{id}/run``.
- ``GET /pages/jobs/{jobID}/dismiss``: the question before a job is dismissed, whose
  button posts ``/pages/jobs/{jobID}/dismiss`` (:mod:`service.pages.actions`).
  A job that can no longer be dismissed goes back to its page (303).
- ``GET /pages/compare?jobs=A&jobs=B...``: two to six jobs of one process side by side
  (the jobs list's check boxes submit it); jobs of different processes are a 422
  naming ``query.jobs``.

A job is the caller's: another owner's job is 404, an expired one 410, as on
``/v1/jobs/{jobID}``.
"""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Query, Request
from fastapi.responses import RedirectResponse, Response

from service.deps import ApiDep
from service.documents import job_href
from service.job_lookup import find_job
from service.pages.comparison import comparison_context
from service.pages.job_forms import dismiss_question_page, rerun_page
from service.problems import parameter_error
from worker.contract import JobStatus

__all__ = ["router"]

router = APIRouter(prefix="/pages", include_in_schema=False)


@router.get("/jobs/{job_id}/edit")
def edit_and_run_again(job_id: str, request: Request, api: ApiDep) -> Response:
    job = find_job(api.store, job_id, api.identity.owner_scope)
    definition = api.registry.require(job.process_id)
    return rerun_page(request, api.pages, api.registry, definition, job)


@router.get("/jobs/{job_id}/dismiss")
def confirm_dismissal(job_id: str, request: Request, api: ApiDep) -> Response:
    job = find_job(api.store, job_id, api.identity.owner_scope)
    if job.status is JobStatus.DISMISSED:
        return RedirectResponse(job_href(job_id), status_code=303)
    return dismiss_question_page(request, api.pages, api.registry, job)


#: Jobs compared at most.
MAX_COMPARED = 6


@router.get("/compare")
def compare_jobs(
    request: Request,
    api: ApiDep,
    jobs: Annotated[list[str], Query(min_length=2, max_length=MAX_COMPARED)],
) -> Response:
    store = api.store
    found = [find_job(store, job_id, api.identity.owner_scope) for job_id in dict.fromkeys(jobs)]
    if len(found) < 2:
        raise parameter_error("query", "jobs", "name at least two different jobs")
    processes = sorted({j.process_id for j in found})
    if len(processes) > 1:
        raise parameter_error("query", "jobs", f"jobs of one process only, not of {processes}")
    results = [
        store.get_result(j.job_id) if j.status is JobStatus.SUCCESSFUL else None for j in found
    ]
    return api.pages.render(request, "compare.html", comparison_context(found, results))
