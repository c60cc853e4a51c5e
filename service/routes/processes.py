"""``/v1/processes``: what the service can run, and submitting jobs."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Header, Request, Response
from fastapi.responses import HTMLResponse, JSONResponse
from pydantic import BaseModel, ConfigDict, Field
from starlette.concurrency import run_in_threadpool

from service.auth import Identity, get_identity
from service.deps import DispatcherDep, RegistryDep, SettingsDep, StoreDep
from service.documents import job_href, status_document
from service.execution import no_cache, submit_job, wait_while_connected
from service.job_watcher import JobWatcher
from service.pages import FormatQuery, PagesDep, views, wants_html
from service.preferences import requested_wait
from service.routes.jobs import finished_document
from service.schemas import RETENTION, REUSE, SHARE
from worker.contract import JobRecord
from worker.errors import NoSuchJob
from worker.store.base import JobStore

__all__ = ["router"]

router = APIRouter(prefix="/v1/processes", tags=["processes"])


class ExecuteRequest(BaseModel):
    """The body of an execution request."""

    model_config = ConfigDict(extra="forbid")

    inputs: dict[str, Any] = Field(..., description="The process inputs (see its schema).")
    retention_s: float | None = RETENTION
    reuse: bool = REUSE
    share: bool = SHARE


# The process list and descriptions need no store and take no threadpool thread for
# JSON: they answer at once even while every thread waits on a store in trouble.
# (A page reads templates and method files: it runs in the threadpool.)


@router.get("", summary="List the processes", response_model=None)
async def list_processes(
    request: Request,
    response: Response,
    registry: RegistryDep,
    pages: PagesDep,
    f: FormatQuery = None,
) -> dict[str, Any] | HTMLResponse:
    response.headers["Vary"] = "Accept"
    if wants_html(request):
        return await run_in_threadpool(views.process_list_page, request, pages, registry)
    return {
        "processes": [
            {
                **d.summary(),
                "links": [
                    {"href": f"/v1/processes/{d.id}", "rel": "self", "type": "application/json"}
                ],
            }
            for d in registry
        ],
        "links": [{"href": "/v1/processes", "rel": "self", "type": "application/json"}],
    }


@router.get(
    "/{process_id}",
    summary="Describe a process: inputs schema, examples, limits",
    response_model=None,
)
async def describe_process(
    process_id: str,
    request: Request,
    response: Response,
    registry: RegistryDep,
    pages: PagesDep,
    f: FormatQuery = None,
) -> dict[str, Any] | HTMLResponse:
    definition = registry.require(process_id)
    response.headers["Vary"] = "Accept"
    if wants_html(request):
        return await run_in_threadpool(views.process_page, request, pages, registry, definition)
    doc = definition.describe()
    doc["links"] = [
        {
            "href": f"/v1/processes/{process_id}/execution",
            "rel": "http://www.opengis.net/def/rel/ogc/1.0/execute",
            "type": "application/json",
            "title": "POST to run it",
        },
    ]
    if definition.method_doc:
        doc["links"].append(
            {
                "href": f"/methods/{definition.method_doc}",
                "rel": "describedby",
                "type": "text/html",
                "title": "The method, its equations and the paper's errata",
            }
        )
    return doc


@router.post(
    "/{process_id}/execution",
    status_code=201,
    summary="Submit a job (committed before the response)",
)
async def execute(
    process_id: str,
    body: ExecuteRequest,
    request: Request,
    response: Response,
    store: StoreDep,
    registry: RegistryDep,
    settings: SettingsDep,
    dispatcher: DispatcherDep,
    idempotency_key: Annotated[
        str | None, Header(alias="Idempotency-Key", min_length=1, max_length=255)
    ] = None,
    prefer: Annotated[str | None, Header(max_length=255)] = None,
    cache_control: Annotated[str | None, Header(alias="Cache-Control", max_length=255)] = None,
) -> Any:
    """Queue a job.  With ``Prefer: wait=N`` and a request within the process's
    ``sync_cost_limit``, answer ``200`` with the result document if the job finishes
    within N seconds (``Preference-Applied: wait=N``); otherwise ``201`` as usual.

    The wait holds no thread: the app's job watcher wakes the request when the job is
    done."""
    wait = requested_wait(prefer)
    identity = get_identity(request)
    job, created, synchronous = await run_in_threadpool(
        submit_job,
        store,
        registry,
        settings,
        process_id,
        body.inputs,
        idempotency_key,
        dispatcher,
        wait is not None,
        identity.name,
        body.retention_s,
        body.reuse and not no_cache(cache_control),
        body.share,
    )
    response.headers["Location"] = job_href(job.job_id)
    if not created:
        response.headers["Idempotent-Replayed"] = "true"
    if wait is not None and synchronous:
        watcher: JobWatcher = request.app.state.watcher
        # a job answered by a stored result is finished already: no wait at all
        if job.reused_from is not None or await wait_while_connected(
            request, watcher, job.job_id, wait
        ):
            document = await run_in_threadpool(
                _finished_document, store, job.job_id, identity.admin
            )
            headers = {
                "Location": response.headers["Location"],
                "Preference-Applied": f"wait={wait:g}",
            }
            return JSONResponse(document, status_code=200, headers=headers)
    return _status(job, identity)


def _status(job: JobRecord, identity: Identity) -> dict[str, Any]:
    return status_document(
        job, worker=identity.sees_workers, owner=identity.sees_owners, admin=identity.admin
    )


def _finished_document(store: JobStore, job_id: str, admin: bool = False) -> dict[str, Any]:
    job = store.get_job(job_id)
    if job is None:  # pragma: no cover - jobs are only deleted by retention, later
        raise NoSuchJob(f"No job {job_id!r}.")
    return finished_document(store, job, admin)
