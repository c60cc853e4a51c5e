"""One design of a study, as a job of its own (``/pages/``, no JavaScript needed; left
out of the OpenAPI document):

- ``POST /pages/jobs/{jobID}/designs/{index}/run``: "Open as a job": the study's
  process on that design (its ``fixed`` inputs with the design's varied values, plots
  on) is submitted like any run from a page, and the browser goes to the new job's
  page (303); a refusal (a design the process refuses, a quota) is that process's page
  with the problem and the design's inputs in its first form.
- ``GET /pages/jobs/{jobID}/designs/{index}/edit``: "Edit and run": the process page
  with a first form holding that design's inputs.

The study is the caller's (another owner's is 404); an index past the last design is
a 404 page naming it.
"""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import Response
from starlette.concurrency import run_in_threadpool

from service.deps import Api, ApiDep
from service.job_lookup import find_job
from service.pages.forms import check_csrf, check_form_origin, read_form
from service.pages.json_text import compact_json
from service.pages.page_submission import PageRefusal, submit_from_page
from service.pages.views import example_forms, process_page
from service.study_tables import STUDY_PROCESS
from worker.errors import (
    NoSuchArtifact,
)
from worker.processes import ProcessDefinition
from worker.studies.evaluation import one_design_inputs

__all__ = ["router"]

router = APIRouter(prefix="/pages", include_in_schema=False)


def _design(api: Api, job_id: str, index: int) -> tuple[ProcessDefinition, dict[str, Any]]:
    """The study's process and the inputs of its design ``index``."""
    job = find_job(api.store, job_id, api.identity.owner_scope)
    if job.process_id != STUDY_PROCESS:
        raise NoSuchArtifact(f"Job {job_id} is not a design study: it has no designs.")
    spec = api.registry.require(STUDY_PROCESS).inputs_model.model_validate(job.inputs)
    definition = api.registry.require(spec.process)  # type: ignore[attr-defined]
    try:
        return definition, one_design_inputs(spec, definition, index)  # type: ignore[arg-type]
    except IndexError as exc:
        raise NoSuchArtifact(f"Job {job_id} has no design {index}: {exc}.") from None


def _form(job_id: str, index: int, text: str, problem: Any = None) -> dict[str, Any]:
    return {
        "title": f"Design {index} of study {job_id[:8]}",
        "description": "The study's fixed inputs with this design's varied values (plots "
        "on); change what you like and run it as a job of its own.",
        "text": text,
        "problem": problem,
        "rows": min(max(text.count("\n") + 2, 4), 24),
        "button": "Run this design",
    }


@router.get("/jobs/{job_id}/designs/{index}/edit")
def edit_design(job_id: str, index: int, request: Request, api: ApiDep) -> Response:
    definition, inputs = _design(api, job_id, index)
    form = _form(job_id, index, compact_json(inputs))
    return process_page(request, api.pages, api.registry, definition,
                        examples=[form, *example_forms(definition)])  # fmt: skip


@router.post("/jobs/{job_id}/designs/{index}/run")
async def run_design(job_id: str, index: int, request: Request, api: ApiDep) -> Response:
    check_form_origin(request)
    check_csrf(request, await read_form(request))
    definition, inputs = await run_in_threadpool(_design, api, job_id, index)
    answer = await submit_from_page(request, api, definition.id, inputs)
    if not isinstance(answer, PageRefusal):
        return answer
    form = _form(job_id, index, compact_json(inputs), answer.problem)
    page = await run_in_threadpool(
        lambda: process_page(
            request,
            api.pages,
            api.registry,
            definition,
            examples=[form, *example_forms(definition)],
            status_code=answer.status,
        )
    )
    return answer.answered(page)
