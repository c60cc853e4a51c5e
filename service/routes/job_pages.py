"""Pages about one job, beside its status page (``/pages/``, not in the OpenAPI
document; no JavaScript needed):

- ``GET /pages/jobs/{jobID}/edit``: "Edit and run again": the job's process page with
  a first form holding the job's inputs; it posts to ``/pages/processes/{id}/run``.
- ``GET /pages/jobs/{jobID}/dismiss``: the question before a job is dismissed, whose
  button posts ``/pages/jobs/{jobID}/dismiss`` (:mod:`service.routes.page_actions`).
  A job that can no longer be dismissed goes back to its page (303).

A job is the caller's: another owner's job is 404, an expired one 410, as on
``/v1/jobs/{jobID}``.
"""

from __future__ import annotations

from fastapi import APIRouter, Request
from fastapi.responses import HTMLResponse, RedirectResponse

from service.auth import IdentityDep
from service.deps import RegistryDep, StoreDep
from service.documents import job_href
from service.job_lookup import find_job
from service.pages import PagesDep
from service.pages.job_forms import dismiss_question_page, rerun_page
from worker.contract import JobStatus

__all__ = ["router"]

router = APIRouter(prefix="/pages/jobs", include_in_schema=False)


@router.get("/{job_id}/edit", response_model=None)
def edit_and_run_again(
    job_id: str,
    request: Request,
    store: StoreDep,
    registry: RegistryDep,
    pages: PagesDep,
    identity: IdentityDep,
) -> HTMLResponse:
    job = find_job(store, job_id, identity.owner_scope)
    definition = registry.require(job.process_id)
    return rerun_page(request, pages, registry, definition, job)


@router.get("/{job_id}/dismiss", response_model=None)
def confirm_dismissal(
    job_id: str,
    request: Request,
    store: StoreDep,
    registry: RegistryDep,
    pages: PagesDep,
    identity: IdentityDep,
) -> HTMLResponse | RedirectResponse:
    job = find_job(store, job_id, identity.owner_scope)
    if job.status is JobStatus.DISMISSED:
        return RedirectResponse(job_href(job_id), status_code=303)
    return dismiss_question_page(request, pages, registry, job)
