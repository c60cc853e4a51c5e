"""``POST /v1/processes/{processID}/preview``: a design's maps and indices, at once.

The live explorer's evaluation (:mod:`worker.previews`): the body of an execution,
validated as a submission is (the same 422 naming each field), under the caller's API
key and submit rate limit (:mod:`service.preview_rate`), refused above the process's
preview cost limit (no higher than what it publishes), and computed in a thread of the
request (not the job pool); no job is made and nothing is stored.  A process without a
preview answers 404 ``no-such-process``.

The explorer page in a browser session posts the same request to
``/pages/processes/{processID}/preview`` with its CSRF token in the ``X-CSRF-Token``
header (a session may not write through the JSON API: :mod:`service.auth.gate`).
"""

from __future__ import annotations

from fastapi import APIRouter, Request
from starlette.concurrency import run_in_threadpool

from service.auth.sessions import CSRF_FIELD
from service.deps import Api, ApiDep
from service.pages.forms import check_csrf, check_form_origin
from service.preview_rate import PreviewRate
from service.preview_schemas import PreviewDocument
from service.routes.processes import ExecuteRequest
from worker.preview_run import preview, preview_definition

__all__ = ["CSRF_HEADER", "page_router", "router"]

router = APIRouter(prefix="/v1/processes", tags=["processes"])
page_router = APIRouter(prefix="/pages/processes", include_in_schema=False)

#: The header the explorer page sends its session's CSRF token in.
CSRF_HEADER = "X-CSRF-Token"


def _preview(api: Api, rate: PreviewRate, process_id: str, body: ExecuteRequest) -> PreviewDocument:
    preview_definition(api.registry, process_id)  # an unknown process: 404 before the rate
    rate.take(api.identity.name)
    answer = preview(api.registry, process_id, body.inputs)
    # FastAPI serialises the model with pydantic-core in one go (its fast path for a
    # route model): the ~10^4 map values never pass through jsonable_encoder (~20 ms).
    return PreviewDocument.model_validate({**answer, "process_id": process_id})


@router.post(
    "/{process_id}/preview",
    summary="Preview a design: its maps and indices, computed at once, nothing stored",
    response_model=PreviewDocument,
)
async def preview_process(
    process_id: str, body: ExecuteRequest, request: Request, api: ApiDep
) -> PreviewDocument:
    """The inputs of an execution (`retention_s`, `reuse` and `share` are ignored),
    validated as a submission's and counted against the API key's submit rate; a
    preview costing more than the process's preview limit is refused (422
    `cost-limit-exceeded`, naming the cost and the limit); a process without a preview
    is 404.  Answers the grid axes, the map values (null: no value) and the indices
    summary that the live explorer draws (`/pages/processes/{processID}/explore`)."""
    rate: PreviewRate = request.app.state.preview_rate
    return await run_in_threadpool(_preview, api, rate, process_id, body)


@page_router.post("/{process_id}/preview", response_model=PreviewDocument)
async def preview_from_page(
    process_id: str, body: ExecuteRequest, request: Request, api: ApiDep
) -> PreviewDocument:
    """The same, for the explorer page in a browser session (CSRF token in a header)."""
    check_form_origin(request)
    check_csrf(request, {CSRF_FIELD: request.headers.get(CSRF_HEADER, "")})
    rate: PreviewRate = request.app.state.preview_rate
    return await run_in_threadpool(_preview, api, rate, process_id, body)
