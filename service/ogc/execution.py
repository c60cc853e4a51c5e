"""Running an OGC execute request: submit, keep its options, answer in the negotiated
mode; and reading a finished job's results the way its request asked."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from starlette.responses import Response

from service.config import ServiceSettings
from service.execution import check_retention, submit_job
from service.job_lookup import find_job
from service.ogc.execute_request import (
    OgcExecuteRequest,
    Presentation,
    presentation_of,
    resolve_inputs,
    subscriber_of,
)
from service.ogc.outbound import OutboundPolicy
from service.ogc.outputs import OutputSpec, process_outputs
from service.ogc.results import results_response, select_outputs
from service.ogc.urls import PublicUrls
from worker.contract import JobRecord, JobStatus
from worker.dispatch import Dispatcher
from worker.errors import JobFailed, NoSuchArtifact, NoSuchJob, ResultNotReady
from worker.processes import ProcessDefinition, ProcessRegistry
from worker.store.base import JobStore, StoredArtifact

__all__ = [
    "JobOutput",
    "Submitted",
    "definition_of",
    "finished_job",
    "headers_only",
    "job_output",
    "job_results",
    "outbound_policy",
    "submit_execute",
]


def outbound_policy(settings: ServiceSettings) -> OutboundPolicy:
    return OutboundPolicy.from_setting(settings.outbound_allow_hosts, settings.outbound_timeout_s)


def definition_of(registry: ProcessRegistry, process_id: str) -> ProcessDefinition:
    return registry.require(process_id)


@dataclass(frozen=True)
class Submitted:
    """A submitted execute request: the job, whether it is new, whether it may be
    answered synchronously, and how its results are presented."""

    job: JobRecord
    created: bool
    can_run_sync: bool
    presentation: Presentation


def submit_execute(
    store: JobStore,
    registry: ProcessRegistry,
    settings: ServiceSettings,
    dispatcher: Dispatcher,
    process_id: str,
    body: OgcExecuteRequest,
    idempotency_key: str | None,
    wants_sync: bool,
    base_url: str,
    owner: str = "",
    no_cache: bool = False,
) -> Submitted:
    """Check the request, commit the job (owned by ``owner``), keep its options
    (blocking: threadpool); ``base_url`` is where callbacks' links point.

    A synchronous answer is possible when the process allows it for these inputs and
    a worker is up to run the job (else the wait could only time out)."""
    definition = definition_of(registry, process_id)
    check_retention(settings, body.retention_s)
    presentation = presentation_of(body, process_outputs(definition))
    policy = outbound_policy(settings)
    subscriber = subscriber_of(body, policy)
    inputs = resolve_inputs(
        body.inputs, lambda href: policy.fetch_json(href, settings.max_body_bytes)
    )
    job, created, sync = submit_job(
        store, registry, settings, process_id, inputs, idempotency_key, dispatcher, wants_sync,
        owner, body.retention_s, body.reuse and not no_cache, body.share,
    )  # fmt: skip
    if created:
        options = {**presentation.to_json(), "base": base_url}
        store.set_request_options(job.job_id, options, subscriber)
    if sync and job.reused_from is None:  # a stored result needs no worker
        sync = bool(store.live_workers(within_s=3 * settings.heartbeat_seconds + 1.0))
    return Submitted(job, created, sync, presentation)


def finished_job(
    store: JobStore, job_id: str, owner: str | None = None
) -> tuple[JobRecord, Mapping[str, Any]]:
    """A successful job (of ``owner``; None: anyone's) and its result; otherwise the
    exception that says why there are none (failed: the failure; dismissed or
    another owner's: no such job; else not ready)."""
    job = find_job(store, job_id, owner)
    if job.status is JobStatus.FAILED:
        raise JobFailed(jobID=job.job_id, error=dict(job.error or {}))
    if job.status is not JobStatus.DISMISSED and job.status is not JobStatus.SUCCESSFUL:
        raise ResultNotReady(
            f"Job {job_id} is {job.status.value} ({round(job.progress)}%); its results are "
            "not ready."
        )
    result = store.get_result(job_id) if job.status is JobStatus.SUCCESSFUL else None
    if result is None:
        raise NoSuchJob(f"Job {job_id} was dismissed; its results were deleted.")
    return job, result


def job_results(
    store: JobStore,
    registry: ProcessRegistry,
    job_id: str,
    urls: PublicUrls,
    presentation: Presentation | None = None,
    headers: Mapping[str, str] | None = None,
    owner: str | None = None,
) -> Response:
    """A finished job's results (of ``owner``; None: anyone's), presented as
    ``presentation`` says (default: as the request that created the job asked)."""
    job, result = finished_job(store, job_id, owner)
    if presentation is None:
        presentation = Presentation.from_json(store.request_options(job_id)[0])
    definition = registry.get(job.process_id)
    outputs = process_outputs(definition) if definition is not None else {}
    selected = select_outputs(job, result, outputs, presentation, store)
    return results_response(job, selected, presentation, urls, store, headers)


@dataclass(frozen=True)
class JobOutput:
    """One output of a finished job: a result member (``value``) or a file (``stored``)."""

    job: JobRecord
    spec: OutputSpec
    value: Any = None
    stored: StoredArtifact | None = None


def job_output(
    store: JobStore, registry: ProcessRegistry, job_id: str, output_id: str, owner: str | None
) -> JobOutput:
    """The output ``output_id`` of ``owner``'s finished job (None: anyone's); otherwise
    the exception that says why there is none."""
    job, result = finished_job(store, job_id, owner)
    definition = registry.get(job.process_id)
    spec = process_outputs(definition).get(output_id) if definition is not None else None
    if spec is not None and not spec.artifact and output_id in result:
        return JobOutput(job, spec, value=result[output_id])
    stored = store.artifact(job_id, output_id) if spec is not None and spec.artifact else None
    if spec is None or stored is None:
        raise NoSuchArtifact(f"Job {job_id} has no output {output_id!r}.")
    return JobOutput(job, spec, stored=stored)


def headers_only(response: Response) -> Response:
    """``response``'s status and headers (its ``Content-Length`` too), without a body."""
    return Response(status_code=response.status_code, headers=dict(response.headers))
