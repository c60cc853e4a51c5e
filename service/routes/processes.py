"""``/v1/processes``: what the service can run, and submitting jobs."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Header, Response
from fastapi.responses import JSONResponse
from pydantic import BaseModel, ConfigDict, Field

from service.deps import DispatcherDep, RegistryDep, SettingsDep, StoreDep
from service.documents import job_href, status_document
from service.preferences import requested_wait
from service.routes.jobs import finished_document, wait_for_job
from worker.errors import NoSuchProcess
from worker.submission import submit, synchronous_allowed

__all__ = ["router"]

router = APIRouter(prefix="/v1/processes", tags=["processes"])


class ExecuteRequest(BaseModel):
    """The body of an execution request."""

    model_config = ConfigDict(extra="forbid")

    inputs: dict[str, Any] = Field(..., description="The process inputs (see its schema).")


@router.get("", summary="List the processes")
def list_processes(registry: RegistryDep) -> dict[str, Any]:
    return {
        "processes": [
            {**d.summary(), "links": [{"href": f"/v1/processes/{d.id}", "rel": "self",
                                       "type": "application/json"}]}
            for d in registry
        ],
        "links": [{"href": "/v1/processes", "rel": "self", "type": "application/json"}],
    }


@router.get("/{process_id}", summary="Describe a process: inputs schema, examples, limits")
def describe_process(process_id: str, registry: RegistryDep) -> dict[str, Any]:
    definition = registry.get(process_id)
    if definition is None:
        raise NoSuchProcess(f"No process {process_id!r}; available: {', '.join(registry.ids())}.")
    doc = definition.describe()
    doc["links"] = [
        {"href": f"/v1/processes/{process_id}/execution", "rel": "http://www.opengis.net/def/"
         "rel/ogc/1.0/execute", "type": "application/json", "title": "POST to run it"},
    ]
    return doc


@router.post(
    "/{process_id}/execution",
    status_code=201,
    summary="Submit a job (committed before the response)",
)
def execute(
    process_id: str,
    body: ExecuteRequest,
    response: Response,
    store: StoreDep,
    registry: RegistryDep,
    settings: SettingsDep,
    dispatcher: DispatcherDep,
    idempotency_key: Annotated[
        str | None, Header(alias="Idempotency-Key", min_length=1, max_length=255)
    ] = None,
    prefer: Annotated[str | None, Header(max_length=255)] = None,
) -> Any:
    """Queue a job.  With ``Prefer: wait=N`` and a request within the process's
    ``sync_cost_limit``, answer ``200`` with the result document if the job finishes
    within N seconds (``Preference-Applied: wait=N``); otherwise ``201`` as usual."""
    job, created = submit(
        store, registry, settings, process_id, body.inputs, idempotency_key, dispatcher
    )
    response.headers["Location"] = job_href(job.job_id)
    if not created:
        response.headers["Idempotent-Replayed"] = "true"
    wait = requested_wait(prefer)
    if wait is not None and synchronous_allowed(registry, process_id, body.inputs):
        finished = wait_for_job(store, job.job_id, wait)
        if finished is not None:
            headers = {"Location": response.headers["Location"],
                       "Preference-Applied": f"wait={wait:g}"}
            return JSONResponse(finished_document(store, finished), status_code=200,
                                headers=headers)
    return status_document(job)
