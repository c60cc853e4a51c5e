"""The pages' form actions (no JavaScript needed), under ``/pages/``.

- ``POST /pages/processes/{processID}/run``: the (edited) JSON of a worked example,
  as the form field ``inputs`` (with the "Your own arm" form, the other inputs, and the
  arm pasted as a DH table or a URDF: :mod:`service.pages.own_arm`); a job is queued
  and the browser is sent to its page (303).  JSON that does not parse, or inputs that
  do not validate, re-render the process page with the problem and the user's text kept
  (in the form it came from: "Edit and run again" when the field ``from`` names the job
  it came from).
- ``POST /pages/processes/design-study/build``: the study builder's choices
  (:mod:`service.pages.builder_form`) as the inputs of a ``design-study``, submitted
  like the JSON form's; a refusal comes back on the builder with its fields.
- ``POST /pages/jobs/{jobID}/dismiss``: cancel a queued or running job, or delete a
  finished one's results, then back to the job's page (303).

Both refuse a form posted from another site, or (signed in with a session cookie)
without the session's CSRF token (403, :mod:`service.pages.forms`); a job is the
caller's (another owner's job is 404).  They are page actions, not API operations:
the API has ``POST .../execution`` and ``DELETE /v1/jobs/{jobID}``; these are left
out of the OpenAPI document.
"""

from __future__ import annotations

import json
from functools import partial
from typing import Any

from fastapi import APIRouter, Request, Response
from fastapi.responses import RedirectResponse
from starlette.concurrency import run_in_threadpool

from service.deps import ApiDep
from service.documents import job_href
from service.job_lookup import missing_job
from service.pages import views
from service.pages.builder_form import (
    BUILD_ACTION,
    MAX_BUILDER_FIELDS,
    STUDY_PROCESS,
    chosen_study,
    study_builder_page,
)
from service.pages.forms import check_csrf, check_form_origin, read_form
from service.pages.job_forms import rerun_form
from service.pages.own_arm import own_arm_form, robot_from_form
from service.pages.page_submission import PageRefusal, submit_from_page
from service.problems import problem_document
from service.request_guard import json_depth

__all__ = ["router"]

router = APIRouter(prefix="/pages", include_in_schema=False)


class _BadText(Exception):
    """The form's JSON text is not a JSON object; the message says why."""


def _refuse_constant(name: str) -> Any:
    raise _BadText(f"{name} is not a JSON number")


def _parse_inputs(text: str, max_depth: int) -> dict[str, Any]:
    try:
        value = json.loads(text, parse_constant=_refuse_constant)
    except json.JSONDecodeError as exc:
        raise _BadText(f"{exc.msg} at line {exc.lineno} column {exc.colno}") from None
    except RecursionError:
        raise _BadText(f"they nest deeper than {max_depth} levels") from None
    if not isinstance(value, dict):
        raise _BadText('they must be a JSON object: {"name": value, ...}')
    if json_depth(value) > max_depth:
        raise _BadText(f"they nest deeper than {max_depth} levels")
    return value


def _example_index(value: str, count: int) -> int:
    """Which example's form was posted (the first, if the field is not one)."""
    try:
        index = int(value)
    except ValueError:
        return 0
    return index if 0 <= index < count else 0


@router.post("/processes/{process_id}/run")
async def run_process(process_id: str, request: Request, api: ApiDep) -> Response:
    check_form_origin(request)
    registry, settings = api.registry, api.settings
    definition = registry.require(process_id)
    form = await read_form(request)
    check_csrf(request, form)
    text = form.get("inputs", "")
    examples = views.example_forms(definition)
    index = _example_index(form.get("example", ""), len(examples))
    source_job = form.get("from", "")[:64]
    if source_job:  # "Edit and run again": a refused run comes back in that form
        examples.insert(0, rerun_form(source_job, text))
        index = 0
    own_arm = "robot_kind" in form  # the "Your own arm" form: a pasted DH table or URDF
    try:
        inputs = _parse_inputs(text, settings.max_json_depth)
    except _BadText as exc:
        detail = f"The inputs are not valid JSON: {exc}."
        refusal = PageRefusal(problem_document("malformed-request", detail=detail))
    else:
        if own_arm:
            inputs["robot"] = robot_from_form(form)
        answer = await submit_from_page(request, api, process_id, inputs)
        if not isinstance(answer, PageRefusal):
            return answer
        refusal = answer
    problem = refusal.problem
    extra = {}
    if own_arm:  # the problem goes back to the form it came from
        extra["own_arm"] = own_arm_form(definition, form, problem)
    else:
        examples[index].update(text=text, problem=problem, rows=max(examples[index]["rows"], 8))
    if process_id == STUDY_PROCESS:  # the study's page keeps its builder
        draw = partial(study_builder_page, params={}, examples=examples,
                       status_code=problem["status"])  # fmt: skip
    else:
        draw = partial(views.process_page, examples=examples, status_code=problem["status"],
                       extra=extra)  # fmt: skip
    page = await run_in_threadpool(draw, request, api.pages, registry, definition)
    return refusal.answered(page)


@router.post(BUILD_ACTION.removeprefix(router.prefix))
async def build_study(request: Request, api: ApiDep) -> Response:
    check_form_origin(request)
    definition = api.registry.require(STUDY_PROCESS)
    form = await read_form(request, max_fields=MAX_BUILDER_FIELDS)
    check_csrf(request, form)
    inputs = chosen_study(api.registry, form)
    if inputs is None:
        refusal = PageRefusal(problem_document(
            "invalid-inputs",
            detail="Choose a process a study can run and one of its worked examples first.",
            errors=[{"field": "process", "type": "value_error",
                     "message": "not a process and worked example the builder offers"}],
        ))  # fmt: skip
    else:
        answer = await submit_from_page(request, api, STUDY_PROCESS, inputs)
        if not isinstance(answer, PageRefusal):
            return answer
        refusal = answer
    page = await run_in_threadpool(
        partial(study_builder_page, problem=refusal.problem),
        request, api.pages, api.registry, definition, form,
    )  # fmt: skip
    return refusal.answered(page)


@router.post("/jobs/{job_id}/dismiss")
async def dismiss_job(job_id: str, request: Request, api: ApiDep) -> RedirectResponse:
    store, identity = api.store, api.identity
    check_form_origin(request)
    check_csrf(request, await read_form(request))
    job = await run_in_threadpool(partial(store.dismiss, job_id, owner=identity.owner_scope))
    if job is None:
        raise await run_in_threadpool(missing_job, store, job_id, identity.owner_scope)
    return RedirectResponse(job_href(job_id), status_code=303)
