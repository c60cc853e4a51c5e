"""The job store's port: the single source of truth for jobs, results and artifacts,
as small protocols grouped by role.

Every write a worker makes on behalf of a running attempt carries the attempt's lease
token; the store applies it only while that token is current and the job still
running, so a stale or duplicate worker can never overwrite a newer attempt.

The roles, and the methods each holds:

- :class:`LifecyclePort`: initialise, schema_version, ping, check_storage, close.
- :class:`JobsPort`: create_job (quotas: :class:`QueueLimits`), get_job, statuses,
  list_jobs, dismiss, set_request_options, request_options.
- :class:`QueuePort`: claim_next, claim_job, reap_expired, heartbeat, report_progress,
  fail, expire_leases_of, split, children, mark_dispatched, undispatched,
  take_overdue, accepted_count.
- :class:`ResultsPort`: complete, get_result, child_results, artifact,
  artifact_chunks, get_artifact, reusable, invalidate_reuse.
- :class:`KeysPort`: create_key, seed_key, revoke_key, api_keys, record_key_use,
  shared_secret.
- :class:`RetentionPort`: expire_jobs, forget_expired, expired_at.
- :class:`CallbacksPort`: claim_callbacks, callback_log, finish_callback.
- :class:`WorkersPort`: register_worker, worker_heartbeat, unregister_worker,
  live_workers.
- :class:`MetricsPort`: job_tallies, queue_depth.

:class:`JobStore` is all of them: what :func:`worker.store.open_store` returns and
what the app, the pool and the dispatchers hold; a component that needs one role may
ask for that role alone.  The values crossing the port live in
:mod:`worker.store.records` (re-exported here).

Behind the port, :class:`worker.store.sql.SqlJobStore` writes the logic once in
portable SQL, one topic module a concern, each built on
:class:`worker.store.connector.SqlConnector` (connections, transactions, statement
helpers and the dialect hooks, declared once); the dialects
(:class:`worker.store.sqlite.SqliteJobStore`,
:class:`worker.store.postgres.PostgresJobStore`) override the hooks only.
``tests/test_architecture_store.py`` checks that the roles together are the whole of
what the store offers and what ``service/`` and ``worker/`` call, and that no topic
module restates the connector.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping, Sequence
from datetime import datetime
from typing import Any, Protocol

from worker.contract import Artifact, ChildEnd, JobRecord, JobStatus
from worker.store.records import (
    ApiKey,
    CallbackClaim,
    Claim,
    ClaimAttempt,
    HeartbeatAck,
    JobFilter,
    JobPage,
    JobTally,
    NewJob,
    QueueLimits,
    StoredArtifact,
    WorkerInfo,
)

__all__ = [
    "ApiKey",
    "CallbackClaim",
    "CallbacksPort",
    "Claim",
    "ClaimAttempt",
    "HeartbeatAck",
    "JobFilter",
    "JobPage",
    "JobStore",
    "JobTally",
    "JobsPort",
    "KeysPort",
    "LifecyclePort",
    "MetricsPort",
    "NewJob",
    "QueueLimits",
    "QueuePort",
    "ResultsPort",
    "RetentionPort",
    "StoredArtifact",
    "WorkerInfo",
    "WorkersPort",
]


class LifecyclePort(Protocol):
    """The store itself: its schema, its health and its connections."""

    def initialise(self) -> None:
        """Create or migrate the schema."""

    def schema_version(self) -> int: ...

    def ping(self) -> None:
        """Raise :class:`worker.errors.StoreUnavailable` unless the store answers."""

    def check_storage(self) -> None:
        """Raise :class:`worker.errors.StoreUnavailable` (or ``StorageFull``) unless the
        store can take a write now: one try, no retry window (a readiness probe)."""

    def close(self) -> None: ...


class JobsPort(Protocol):
    """Jobs as a client sees them: submit (quotas checked with the insert), read,
    list, dismiss, and how the client asked for the results."""

    def create_job(self, new: NewJob) -> tuple[JobRecord, bool]:
        """Commit a new job; ``(job, created)``.  A known idempotency key (of the same
        owner) with the same request hash returns the existing job with
        ``created=False`` (a replay: no quota is checked); with another hash it raises
        :class:`worker.errors.IdempotencyConflict`.  A new job must fit ``new.limits``,
        checked atomically with the insert, else :class:`worker.errors.QuotaExceeded`,
        :class:`worker.errors.RateLimited` or :class:`worker.errors.QueueFull`."""

    def get_job(self, job_id: str, *, owner: str | None = None) -> JobRecord | None:
        """The job; None if unknown, or when ``owner`` is given and owns it not."""

    def statuses(self, job_ids: Sequence[str]) -> dict[str, JobStatus]:
        """The status of each known job among ``job_ids``, in one query."""

    def list_jobs(
        self,
        *,
        limit: int,
        cursor: str | None = None,
        status: JobStatus | None = None,
        process_id: str | None = None,
        where: JobFilter | None = None,
        owner: str | None = None,
    ) -> JobPage:
        """Jobs, newest first, ``limit`` at a time (``next_cursor`` continues); ``status``,
        ``process_id``, ``where`` and ``owner`` (one owner's jobs) narrow the selection."""

    def dismiss(self, job_id: str, *, owner: str | None = None) -> JobRecord | None:
        """Dismiss a job (a finished job's results are deleted); None if unknown, or
        when ``owner`` is given and owns it not (then nothing changes)."""

    def set_request_options(
        self, job_id: str, presentation: Mapping[str, Any], subscriber: Mapping[str, Any] | None
    ) -> None:
        """Keep how the client asked for the job's results (``presentation``) and where
        to send callbacks (``subscriber``), with the job."""

    def request_options(
        self, job_id: str
    ) -> tuple[Mapping[str, Any] | None, Mapping[str, Any] | None]:
        """``(presentation, subscriber)`` kept with the job (None: none kept)."""


class QueuePort(Protocol):
    """The queue as workers and the dispatcher see it: claims, leases and the writes
    an attempt fences with its token, fan-out, and the broker's bookkeeping."""

    def claim_next(
        self,
        worker_id: str,
        lease_s: float,
        *,
        prefer_cheap: bool = False,
        max_running_per_owner: int | None = None,
        reap: bool = True,
    ) -> Claim | None:
        """Requeue or fail jobs whose lease expired (unless ``reap`` is false: a worker
        loop reaps every few seconds, not before each claim), then claim the next
        accepted job in fair order (:mod:`worker.store.scheduling`): the owner whose last
        claim is oldest, then its oldest job; with ``prefer_cheap``, a cheap job if one
        is queued; an owner with ``max_running_per_owner`` jobs running is skipped."""

    def claim_job(
        self,
        job_id: str,
        worker_id: str,
        lease_s: float,
        *,
        max_running_per_owner: int | None = None,
    ) -> ClaimAttempt:
        """Claim this job if it is accepted (and its owner runs fewer than
        ``max_running_per_owner`` jobs), or running under an expired lease."""

    def reap_expired(self) -> list[str]:
        """Requeue (or fail, when out of attempts) running jobs whose lease expired;
        returns the requeued job IDs."""

    def heartbeat(self, job_id: str, lease_token: str, lease_s: float) -> HeartbeatAck:
        """Extend the lease if the attempt still owns the job."""

    def report_progress(
        self, job_id: str, lease_token: str, percent: float, message: str
    ) -> bool: ...

    def fail(self, job_id: str, lease_token: str, error: Mapping[str, Any]) -> bool: ...

    def expire_leases_of(self, worker_id: str) -> int:
        """Expire the leases a (dead) worker holds so the jobs are retried at once."""

    def split(
        self,
        job_id: str,
        lease_token: str,
        children: Sequence[NewJob],
        *,
        allow_partial: bool = False,
    ) -> list[str] | None:
        """Queue ``children`` of the running job (its owner, retention, ``parent_id``)
        and park it without a lease until they end; their IDs, or None if the attempt
        lost the job (:mod:`worker.store.fan_out`)."""

    def children(self, job_id: str) -> list[ChildEnd]:
        """The job's children in the order they were made."""

    def mark_dispatched(self, job_id: str) -> None:
        """Record that the job's ID was handed to the broker now."""

    def undispatched(self, older_than_s: float, limit: int = 100) -> list[str]:
        """Accepted jobs not dispatched within ``older_than_s`` (lost messages)."""

    def take_overdue(self, job_ids: Sequence[str], older_than_s: float) -> list[str]:
        """Those of these jobs still undispatched within ``older_than_s``, each marked
        dispatched now (so that of several sweepers, one re-sends each)."""

    def accepted_count(self, bound: int) -> int:
        """Accepted jobs (chunks included), counted up to ``bound``."""


class ResultsPort(Protocol):
    """Results and artifacts: committed by a successful attempt, read by clients and parent jobs."""

    def complete(
        self,
        job_id: str,
        lease_token: str,
        result: Mapping[str, Any],
        artifacts: Sequence[Artifact],
    ) -> bool:
        """Store the artifacts' bytes (outside any transaction, per attempt), then the
        result and the status in one short fenced transaction.  False (and nothing
        committed) if the attempt lost the job."""

    def get_result(self, job_id: str) -> Mapping[str, Any] | None: ...

    def child_results(self, job_id: str) -> Iterator[tuple[ChildEnd, Mapping[str, Any] | None]]:
        """Each child with its result document (None unless successful), in order."""

    def artifact(self, job_id: str, name: str) -> StoredArtifact | None:
        """A successful job's artifact metadata, by name."""

    def artifact_chunks(self, job_id: str, stored: StoredArtifact) -> Iterator[bytes]:
        """The artifact's bytes, about 1 MiB at a time."""

    def get_artifact(self, job_id: str, name: str) -> Artifact | None:
        """The whole artifact in memory (small files and tests; the API streams)."""

    def reusable(self, new: NewJob) -> bool:
        """Whether a stored result would answer ``new`` now."""

    def invalidate_reuse(self, process_id: str, result_key: str | None = None) -> int:
        """Stop the stored results of ``process_id`` (of ``result_key`` only, if given)
        from being reused, deleting no job; how many were reusable."""


class KeysPort(Protocol):
    """API keys (the owners that quotas count) and the service-wide shared secrets."""

    def create_key(self, name: str, secret_hash: str, admin: bool) -> ApiKey | None:
        """Store a new key; None if the name is taken (revoked keys keep their names)."""

    def seed_key(self, name: str, secret_hash: str, admin: bool) -> str:
        """Make the key ``name`` have this secret: ``"created"``, ``"replaced"`` (another
        secret was stored: it and its sessions stop working; the key is live again) or
        ``"unchanged"`` (the same secret: a revoked key stays revoked)."""

    def revoke_key(self, name: str) -> ApiKey | None:
        """Revoke the key (at once, for every replica within a second); None if unknown."""

    def api_keys(self) -> list[ApiKey]:
        """Every key, revoked ones too, oldest first."""

    def record_key_use(self, key_ids: Sequence[str], when: float) -> None:
        """Set ``last_used`` of these keys."""

    def shared_secret(self, name: str, generate: Callable[[], str]) -> str:
        """The service-wide secret ``name``, made with ``generate`` by the first caller
        (every replica then reads the same)."""


class RetentionPort(Protocol):
    """Retention: finished jobs deleted when their time is up, a tombstone kept a while."""

    def expire_jobs(self, limit: int) -> list[str]:
        """Delete up to ``limit`` jobs whose retention ended, and their files, leaving a
        tombstone of each (:mod:`worker.store.retention`); the deleted IDs."""

    def forget_expired(self, limit: int) -> int:
        """Delete up to ``limit`` tombstones past their grace period; how many."""

    def expired_at(self, job_id: str, *, owner: str | None = None) -> datetime | None:
        """When the job expired, if it did and its tombstone is kept (None otherwise, or
        when ``owner`` is given and owned it not)."""


class CallbacksPort(Protocol):
    """The callbacks a job's subscriber asked for: claimed, sent and recorded."""

    def claim_callbacks(self, lease_s: float, max_attempts: int, limit: int) -> list[CallbackClaim]:
        """Record the callbacks that became due (the job started, succeeded or failed) and
        claim up to ``limit`` of those not yet delivered, not claimed by another sender
        under a live lease, and tried fewer than ``max_attempts`` times."""

    def callback_log(self, job_id: str) -> list[dict[str, Any]]:
        """The job's due callbacks: event, uri, attempts, delivered / gave_up (epoch s)."""

    def finish_callback(
        self, claim: CallbackClaim, delivered: bool, retry_after_s: float, max_attempts: int
    ) -> bool:
        """Record a send's outcome: delivered, or retry after ``retry_after_s`` (after
        ``max_attempts`` tries, given up).  False if the claim was lost meanwhile."""


class WorkersPort(Protocol):
    """The workers that run jobs, as they register and beat."""

    def register_worker(self, worker_id: str, host: str, pid: int) -> None: ...

    def worker_heartbeat(self, worker_id: str) -> None: ...

    def unregister_worker(self, worker_id: str) -> None: ...

    def live_workers(self, within_s: float) -> list[WorkerInfo]: ...


class MetricsPort(Protocol):
    """Counts for the metrics endpoint, each in one query."""

    def job_tallies(self) -> list[JobTally]:
        """Every running count of job events (:mod:`worker.store.tallies`), in one query."""

    def queue_depth(self) -> dict[tuple[str, JobStatus], int]:
        """How many jobs are accepted and running, by process, in one query."""


class JobStore(
    LifecyclePort,
    JobsPort,
    QueuePort,
    ResultsPort,
    KeysPort,
    RetentionPort,
    CallbacksPort,
    WorkersPort,
    MetricsPort,
    Protocol,
):
    """The whole port: every role above.  Implementations:
    :class:`worker.store.sqlite.SqliteJobStore`, :class:`worker.store.postgres.PostgresJobStore`."""
