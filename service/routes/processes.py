"""``/v1/processes``: what the service can run, and submitting jobs."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request, Response
from fastapi.responses import JSONResponse
from pydantic import BaseModel, ConfigDict, Field
from starlette.concurrency import run_in_threadpool

from service.deps import Api, ApiDep, RegistryDep
from service.documents import as_json, job_href, status_document
from service.execution import no_cache, submit_job, wait_while_connected
from service.job_watcher import JobWatcher
from service.pages import FormatQuery
from service.parameters import CacheControlHeader, IdempotencyKey, PreferHeader
from service.preferences import requested_wait
from service.routes.jobs import finished_document
from service.schemas import (
    RETENTION,
    REUSE,
    SHARE,
    Link,
    ProcessDescription,
    ProcessList,
    ProcessSummary,
    ResultsDocument,
    StatusDocument,
)
from worker.contract import JobRecord
from worker.errors import NoSuchJob
from worker.store.base import JobStore

__all__ = [
    "EXECUTE_RESPONSES",
    "ExecuteRequest",
    "execute",
    "router",
]

router = APIRouter(prefix="/v1/processes", tags=["processes"])

JSON = "application/json"


class ExecuteRequest(BaseModel):
    """The body of an execution request."""

    model_config = ConfigDict(extra="forbid")

    inputs: dict[str, Any] = Field(..., description="The process inputs (see its schema).")
    retention_s: float | None = RETENTION
    reuse: bool = REUSE
    share: bool = SHARE


# The process list and descriptions need no store and take no threadpool thread: they
# answer at once even while every thread waits on a store in trouble.  Their pages are
# service.pages.routes.


@router.get(
    "",
    summary="List the processes",
    response_model=ProcessList,
    response_model_exclude_unset=True,
)
async def list_processes(
    response: Response, registry: RegistryDep, f: FormatQuery = None
) -> ProcessList:
    response.headers["Vary"] = "Accept"
    return ProcessList(
        processes=[
            ProcessSummary(
                **d.summary(), links=[Link(href=f"/v1/processes/{d.id}", rel="self", type=JSON)]
            )
            for d in registry
        ],
        links=[Link(href="/v1/processes", rel="self", type=JSON)],
    )


@router.get(
    "/{process_id}",
    summary="Describe a process: inputs schema, examples, limits",
    response_model=ProcessDescription,
    response_model_exclude_unset=True,
)
async def describe_process(
    process_id: str, response: Response, registry: RegistryDep, f: FormatQuery = None
) -> ProcessDescription:
    definition = registry.require(process_id)
    response.headers["Vary"] = "Accept"
    links = [
        Link(href=f"/v1/processes/{process_id}/execution",
             rel="http://www.opengis.net/def/rel/ogc/1.0/execute", type=JSON,
             title="POST to run it"),
    ]  # fmt: skip
    if definition.method_doc:
        links.append(
            Link(href=f"/methods/{definition.method_doc}", rel="describedby", type="text/html",
                 title="The method, its equations and the paper's errata")
        )  # fmt: skip
    return ProcessDescription.model_validate({**definition.describe(), "links": links})


#: The execute routes' other success: the result document of a job that finished
#: within the ``Prefer: wait=N`` asked for (their 201 is the status document).
EXECUTE_RESPONSES: dict[int | str, dict[str, Any]] = {
    200: {
        "model": ResultsDocument,
        "description": "The result document: the job finished within the `Prefer: wait=N` "
        "the request asked for (`Preference-Applied`).",
    }
}


@router.post(
    "/{process_id}/execution",
    status_code=201,
    summary="Submit a job (committed before the response)",
    response_model=StatusDocument,
    response_model_exclude_unset=True,
    responses=EXECUTE_RESPONSES,
)
async def execute(
    process_id: str,
    body: ExecuteRequest,
    request: Request,
    response: Response,
    api: ApiDep,
    idempotency_key: IdempotencyKey = None,
    prefer: PreferHeader = None,
    cache_control: CacheControlHeader = None,
) -> StatusDocument | JSONResponse:
    """Queue a job.  With ``Prefer: wait=N`` and a request within the process's
    ``sync_cost_limit``, answer ``200`` with the result document if the job finishes
    within N seconds (``Preference-Applied: wait=N``); otherwise ``201`` as usual.

    The wait holds no thread: the app's job watcher wakes the request when the job is
    done."""
    wait = requested_wait(prefer)
    job, created, synchronous = await run_in_threadpool(
        submit_job,
        api.store,
        api.registry,
        api.settings,
        process_id,
        body.inputs,
        idempotency_key,
        api.dispatcher,
        wait is not None,
        api.identity.name,
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
                _finished_document, api.store, job.job_id, api.identity.admin
            )
            headers = {
                "Location": response.headers["Location"],
                "Preference-Applied": f"wait={wait:g}",
            }
            return JSONResponse(as_json(document), status_code=200, headers=headers)
    return _status(job, api)


def _status(job: JobRecord, api: Api) -> StatusDocument:
    identity = api.identity
    return status_document(
        job, worker=identity.sees_workers, owner=identity.sees_owners, admin=identity.admin
    )


def _finished_document(store: JobStore, job_id: str, admin: bool = False) -> ResultsDocument:
    job = store.get_job(job_id)
    if job is None:  # pragma: no cover - jobs are only deleted by retention, later
        raise NoSuchJob(f"No job {job_id!r}.")
    return finished_document(store, job, admin)
