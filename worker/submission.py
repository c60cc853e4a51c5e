"""Turning a client's request into a committed job: validate, price, store.

Nothing is queued unless the inputs validate, the work fits the process's documented
cost limit, and the queue has room: the store checks the quotas in the transaction
that inserts the job (:mod:`worker.store.quotas`).  Per-key quotas apply to API keys;
the anonymous owner of a service without keys (its operator) meets only the cap on the
whole queue.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from worker.contract import JobRecord, JobStatus
from worker.dispatch import Dispatcher
from worker.errors import CostLimitExceeded, InvalidInputs
from worker.input_validation import field_errors, field_path, validate_inputs
from worker.processes import ProcessRegistry
from worker.provenance.build import result_key
from worker.request_hash import request_hash
from worker.settings import WorkerSettings
from worker.store.base import JobStore, NewJob, QueueLimits

__all__ = [
    "Submission",
    "field_errors",
    "field_path",
    "queue_limits",
    "request_hash",
    "submit",
    "submit_request",
    "validate_inputs",
]


@dataclass(frozen=True)
class Submission:
    """A committed job, whether this request created it (not an idempotent replay), and
    whether it is cheap: it costs at most its process's ``sync_cost_limit``, so the
    request may be answered synchronously (priced once, with the job's validation).
    A job answered by a stored result is finished already (:attr:`reused`)."""

    job: JobRecord
    created: bool
    cheap: bool

    @property
    def reused(self) -> bool:
        """Whether a stored result answered this job (it is successful already)."""
        return self.job.reused_from is not None


def queue_limits(settings: WorkerSettings, owner: str) -> QueueLimits:
    """The quotas a submission of ``owner`` must fit: an API key's (``owner`` is its
    name) and the whole queue's; the anonymous owner ('') only the whole queue's."""
    if owner == "":
        return QueueLimits(max_queued=settings.max_queued)
    return QueueLimits(
        max_queued=settings.max_queued,
        max_queued_per_owner=settings.max_queued_per_key,
        submit_rate_per_min=settings.submit_rate_per_min or None,
    )


def submit(
    store: JobStore,
    registry: ProcessRegistry,
    settings: WorkerSettings,
    process_id: str,
    raw_inputs: Mapping[str, Any],
    idempotency_key: str | None = None,
    dispatcher: Dispatcher | None = None,
    owner: str = "",
    retention_s: float | None = None,
    reuse: bool = True,
    share: bool = True,
) -> tuple[JobRecord, bool]:
    """:func:`submit_request`, answering ``(job, created)``."""
    submission = submit_request(
        store, registry, settings, process_id, raw_inputs, idempotency_key, dispatcher, owner,
        retention_s, reuse=reuse, share=share,
    )  # fmt: skip
    return submission.job, submission.created


def submit_request(
    store: JobStore,
    registry: ProcessRegistry,
    settings: WorkerSettings,
    process_id: str,
    raw_inputs: Mapping[str, Any],
    idempotency_key: str | None = None,
    dispatcher: Dispatcher | None = None,
    owner: str = "",
    retention_s: float | None = None,
    *,
    reuse: bool = True,
    share: bool = True,
) -> Submission:
    """Validate, check the cost limit, commit a job owned by ``owner`` (an API key's
    name; '' = anonymous) within its quotas, then dispatch it; the inputs are validated
    and priced once, here, whatever the request's way of answering.  The finished job
    is kept ``retention_s`` seconds (at most, and by default, ``settings.result_ttl_s``;
    the caller checks a requested value).

    The job is committed before it is dispatched, so a broker outage loses nothing (the
    sweeper sends it later); a replayed idempotent request is not dispatched again.  An
    idempotency key is the owner's own: another owner's same key makes another job.

    With ``reuse`` (and ``settings.reuse`` not ``off``) a successful stored result of
    the same result key, within the scope ``settings.reuse`` allows, answers the job at
    once (:mod:`worker.store.reuse`); ``share=False`` keeps this job's result from other
    owners.  The cost limit, quotas and submit rate apply all the same.
    """
    definition = registry.require(process_id)
    inputs = validate_inputs(definition, raw_inputs)
    cost = definition.cost(inputs)
    if cost > definition.cost_limit:
        raise CostLimitExceeded(
            f"This request costs {cost:,} {definition.cost_unit}, above the limit of "
            f"{definition.cost_limit:,} for {process_id}; use a coarser grid or a larger "
            "orientation step.",
            cost=cost,
            cost_limit=definition.cost_limit,
            cost_unit=definition.cost_unit,
        )
    stored_inputs = inputs.model_dump(mode="json")
    cheap = definition.sync_cost_limit > 0 and cost <= definition.sync_cost_limit
    new = NewJob(
        process_id=process_id,
        inputs=stored_inputs,
        time_limit_s=settings.time_limit_for(definition.time_limit_for(inputs)),
        max_attempts=settings.max_attempts,
        idempotency_key=idempotency_key,
        request_hash=request_hash(process_id, stored_inputs) if idempotency_key else None,
        owner=owner,
        cheap=cheap,
        retention_s=min(retention_s or settings.result_ttl_s, settings.result_ttl_s),
        limits=queue_limits(settings, owner),
        result_key=result_key(
            process_id, definition.keyed_inputs(stored_inputs), definition.version, settings.build
        ),
        reuse=settings.reuse if reuse and settings.reuse != "off" else None,
        share=share,
    )
    # A stored result of this key means these inputs passed the precheck once already
    # (a design study's checks its designs: ~100 ms a reused answer need not pay).
    if definition.precheck is not None and not (new.reuse and store.reusable(new)):
        problems = definition.precheck(inputs)
        if problems:
            raise InvalidInputs(problems)
    job, created = store.create_job(new)
    if created and dispatcher is not None and job.status is JobStatus.ACCEPTED:
        dispatcher.dispatch(job.job_id, job.time_limit_s)
    return Submission(job, created, cheap)
