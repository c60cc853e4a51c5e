"""What the job store keeps beside jobs, as it hands them out: a claimed callback, a
committed artifact's index entry, an API key, a running tally and a registered worker.
(:mod:`worker.store.base` re-exports them with the store's interface.)"""

from __future__ import annotations

from dataclasses import dataclass

from worker.contract import ArtifactInfo

__all__ = ["ApiKey", "CallbackClaim", "JobTally", "StoredArtifact", "WorkerInfo"]


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
