"""The values that cross the job store's port: what a caller hands in (a new job, its
queue limits, a listing filter) and what the store hands out (a claim, a heartbeat's
answer, a page of jobs, a claimed callback, a committed artifact's index entry, an API
key, a running tally and a registered worker).  (:mod:`worker.store.base` re-exports
them with the store's interface.)"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from datetime import datetime
from typing import Any, Literal

from worker.contract import ArtifactInfo, JobRecord, JobStatus

__all__ = [
    "DEFAULT_RETENTION_S",
    "ApiKey",
    "CallbackClaim",
    "Claim",
    "ClaimAttempt",
    "HeartbeatAck",
    "JobFilter",
    "JobPage",
    "JobTally",
    "NewJob",
    "QueueLimits",
    "StoredArtifact",
    "WorkerInfo",
]


@dataclass(frozen=True)
class CallbackClaim:
    """A callback one sender now owns: POST ``event``'s document to ``uri``, then
    report the outcome with ``token``.  ``attempt`` counts from 1."""

    job_id: str
    event: str
    uri: str
    token: str
    attempt: int


@dataclass(frozen=True)
class StoredArtifact:
    """A committed artifact: its metadata, the attempt whose bytes it is, and the
    SHA-256 of those bytes (hex; the HTTP ETag)."""

    info: ArtifactInfo
    attempt: int
    etag: str
    #: The job whose stored bytes these are (another job's, for a job made by reuse).
    holder: str = ""


@dataclass(frozen=True)
class ApiKey:
    """An API key as the store keeps it: the SHA-256 of its secret, never the secret.

    ``key_id`` is replaced with the secret (a browser session names it, so replacing
    or revoking a key ends its sessions); times are epoch seconds."""

    name: str
    key_id: str
    secret_hash: str
    admin: bool
    created: float
    revoked: float | None
    last_used: float | None


@dataclass(frozen=True)
class JobTally:
    """One running count of :mod:`worker.store.tallies`: ``count`` events (and, for a
    histogram bucket, the sum ``total`` of their seconds) of ``tally`` and ``label``."""

    process_id: str
    tally: str
    label: str
    count: int
    total: float


@dataclass(frozen=True)
class WorkerInfo:
    """A worker process that registered with the store."""

    worker_id: str
    host: str
    pid: int
    started: float
    heartbeat: float


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
    #: The digest naming its computation (worker.provenance.build.result_key).
    result_key: str | None = None
    #: Whose stored results of the same key it may reuse: its owner's ("owner"), any
    #: owner's shareable ones ("all"), or none (None: it is computed).
    reuse: Literal["owner", "all"] | None = None
    #: Whether jobs of other owners may reuse its result.
    share: bool = True


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
