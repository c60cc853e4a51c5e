"""The job store interface: the single source of truth for jobs, results and artifacts.

Every write a worker makes on behalf of a running attempt carries the attempt's lease
token; the store applies it only while that token is current and the job still
running, so a stale or duplicate worker can never overwrite a newer attempt.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from datetime import datetime
from typing import Any, Protocol

from worker.contract import Artifact, ChildEnd, JobRecord, JobStatus
from worker.store.records import ApiKey, CallbackClaim, JobTally, StoredArtifact, WorkerInfo

__all__ = [
    "ApiKey",
    "CallbackClaim",
    "Claim",
    "ClaimAttempt",
    "HeartbeatAck",
    "JobFilter",
    "JobPage",
    "JobStore",
    "JobTally",
    "NewJob",
    "QueueLimits",
    "StoredArtifact",
    "WorkerInfo",
]


#: A finished job's retention when nothing else is said (seconds; 7 days).
DEFAULT_RETENTION_S = 604800.0


@dataclass(frozen=True)
class QueueLimits:
    """The quotas a new job must fit, checked in the transaction that inserts it (None:
    no such limit).  See :mod:`worker.store.quotas`."""

    #: Jobs waiting in the whole queue.
    max_queued: int | None = None
    #: Jobs the owner may have waiting.
    max_queued_per_owner: int | None = None
    #: Submissions the owner may make per minute (a token bucket of this size).
    submit_rate_per_min: int | None = None


@dataclass(frozen=True)
class NewJob:
    """A job to create."""

    process_id: str
    inputs: Mapping[str, Any]
    time_limit_s: float
    max_attempts: int
    idempotency_key: str | None = None
    request_hash: str | None = None
    #: The API key name submitting it ('' = anonymous); idempotency keys are per owner.
    owner: str = ""
    #: Whether it costs at most its process's ``sync_cost_limit`` (a cheap job, which
    #: one worker slot prefers).
    cheap: bool = False
    #: Seconds the job and its files are kept once it has finished.
    retention_s: float = DEFAULT_RETENTION_S
    #: The quotas to check (none by default: the submission path sets them).
    limits: QueueLimits = QueueLimits()
    #: The job that created this one for itself (None: a client's job).  Such work
    #: counts as its parent: quotas count only jobs without a parent.
    parent_id: str | None = None


@dataclass(frozen=True)
class Claim:
    """A job a worker claimed, with the token that fences its writes."""

    job: JobRecord
    lease_token: str


@dataclass(frozen=True)
class ClaimAttempt:
    """The outcome of claiming one named job (a broker delivered its ID).

    ``claim`` is set when this worker now runs it.  Otherwise ``status`` says why not
    (None: no such job): finished or dismissed (drop the message); running under
    another worker's live lease, which ends in ``retry_after_s`` seconds unless renewed;
    or accepted but its owner runs as many jobs as it may (try again in
    ``retry_after_s``).
    """

    claim: Claim | None
    status: JobStatus | None
    retry_after_s: float | None


@dataclass(frozen=True)
class HeartbeatAck:
    """What a heartbeat learned: whether the attempt still owns the job."""

    owner: bool
    status: JobStatus | None


@dataclass(frozen=True)
class JobPage:
    """One page of a job listing, newest first."""

    jobs: Sequence[JobRecord]
    next_cursor: str | None


@dataclass(frozen=True)
class JobFilter:
    """Which jobs a listing selects; every criterion given must hold (None: any).

    ``created_from`` and ``created_to`` bound the creation time, both inclusive, at the
    microsecond the documents show.  A duration is ``finished - started``, or ``now -
    started`` while running; a duration bound selects only jobs that have started and
    are not back in the queue (accepted jobs have no duration)."""

    statuses: frozenset[JobStatus] | None = None
    process_ids: frozenset[str] | None = None
    created_from: datetime | None = None
    created_to: datetime | None = None
    min_duration_s: float | None = None
    max_duration_s: float | None = None
    #: The children of this job (a study's chunks); None: jobs that are nobody's child.
    parent_id: str | None = None


class JobStore(Protocol):
    """Persistent jobs.  Implementations: :class:`worker.store.sqlite.SqliteJobStore`."""

    def initialise(self) -> None:
        """Create or migrate the schema."""

    def ping(self) -> None:
        """Raise :class:`worker.errors.StoreUnavailable` unless the store answers."""

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

    def set_request_options(
        self, job_id: str, presentation: Mapping[str, Any], subscriber: Mapping[str, Any] | None
    ) -> None:
        """Keep how the client asked for the job's results (``presentation``) and where
        to send callbacks (``subscriber``), with the job."""

    def request_options(
        self, job_id: str
    ) -> tuple[Mapping[str, Any] | None, Mapping[str, Any] | None]:
        """``(presentation, subscriber)`` kept with the job (None: none kept)."""

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

    def child_results(self, job_id: str) -> Iterator[tuple[ChildEnd, Mapping[str, Any] | None]]:
        """Each child with its result document (None unless successful), in order."""

    def mark_dispatched(self, job_id: str) -> None:
        """Record that the job's ID was handed to the broker now."""

    def undispatched(self, older_than_s: float, limit: int = 100) -> list[str]:
        """Accepted jobs not dispatched within ``older_than_s`` (lost messages)."""

    def take_overdue(self, job_ids: Sequence[str], older_than_s: float) -> list[str]:
        """Those of these jobs still undispatched within ``older_than_s``, each marked
        dispatched now (so that of several sweepers, one re-sends each)."""

    def accepted_count(self, bound: int) -> int:
        """Accepted jobs (chunks included), counted up to ``bound``."""

    def schema_version(self) -> int: ...

    def close(self) -> None: ...

    def heartbeat(self, job_id: str, lease_token: str, lease_s: float) -> HeartbeatAck:
        """Extend the lease if the attempt still owns the job."""

    def report_progress(
        self, job_id: str, lease_token: str, percent: float, message: str
    ) -> bool: ...

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

    def fail(self, job_id: str, lease_token: str, error: Mapping[str, Any]) -> bool: ...

    def expire_leases_of(self, worker_id: str) -> int:
        """Expire the leases a (dead) worker holds so the jobs are retried at once."""

    def dismiss(self, job_id: str, *, owner: str | None = None) -> JobRecord | None:
        """Dismiss a job (a finished job's results are deleted); None if unknown, or
        when ``owner`` is given and owns it not (then nothing changes)."""

    def get_result(self, job_id: str) -> Mapping[str, Any] | None: ...

    def artifact(self, job_id: str, name: str) -> StoredArtifact | None:
        """A successful job's artifact metadata, by name."""

    def artifact_chunks(self, job_id: str, stored: StoredArtifact) -> Iterator[bytes]:
        """The artifact's bytes, about 1 MiB at a time."""

    def get_artifact(self, job_id: str, name: str) -> Artifact | None:
        """The whole artifact in memory (small files and tests; the API streams)."""

    def check_storage(self) -> None:
        """Raise :class:`worker.errors.StoreUnavailable` (or ``StorageFull``) unless the
        store can take a write now: one try, no retry window (a readiness probe)."""

    def register_worker(self, worker_id: str, host: str, pid: int) -> None: ...

    def worker_heartbeat(self, worker_id: str) -> None: ...

    def unregister_worker(self, worker_id: str) -> None: ...

    def live_workers(self, within_s: float) -> list[WorkerInfo]: ...

    def job_tallies(self) -> list[JobTally]:
        """Every running count of job events (:mod:`worker.store.tallies`), in one query."""

    def queue_depth(self) -> dict[tuple[str, JobStatus], int]:
        """How many jobs are accepted and running, by process, in one query."""

    def expire_jobs(self, limit: int) -> list[str]:
        """Delete up to ``limit`` jobs whose retention ended, and their files, leaving a
        tombstone of each (:mod:`worker.store.retention`); the deleted IDs."""

    def forget_expired(self, limit: int) -> int:
        """Delete up to ``limit`` tombstones past their grace period; how many."""

    def expired_at(self, job_id: str, *, owner: str | None = None) -> datetime | None:
        """When the job expired, if it did and its tombstone is kept (None otherwise, or
        when ``owner`` is given and owned it not)."""

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
