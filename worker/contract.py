"""The job contract shared by the HTTP front end and the workers.

Only plain data lives here: the status enum, the records the store hands out, what a
job function receives (:class:`JobContext`) and what it returns (:class:`JobOutcome`).
"""

from __future__ import annotations

import enum
from collections.abc import Mapping
from dataclasses import dataclass, field
from datetime import datetime
from typing import Any, Protocol

__all__ = [
    "TERMINAL_STATUSES",
    "Artifact",
    "ArtifactInfo",
    "ChildEnd",
    "JobContext",
    "JobOutcome",
    "JobRecord",
    "JobStatus",
]


class JobStatus(enum.StrEnum):
    """Where a job is in its life (OGC API - Processes status codes)."""

    #: Committed to the store, waiting for a worker to claim it.
    ACCEPTED = "accepted"
    #: Claimed by a worker holding a live lease; progress is written back.
    RUNNING = "running"
    #: Finished; its result document and artifacts are stored.
    SUCCESSFUL = "successful"
    #: Finished without a result: an error, the time limit, or too many lost attempts.
    FAILED = "failed"
    #: Cancelled by the client; a running attempt's process is stopped.
    DISMISSED = "dismissed"


TERMINAL_STATUSES = frozenset({JobStatus.SUCCESSFUL, JobStatus.FAILED, JobStatus.DISMISSED})


@dataclass(frozen=True)
class Artifact:
    """A file a job produced: a plot (PNG/SVG) or data (CSV/NPZ)."""

    name: str
    media_type: str
    data: bytes
    title: str = ""


@dataclass(frozen=True)
class ArtifactInfo:
    """An artifact's metadata, as listed in a result document."""

    name: str
    media_type: str
    size: int
    title: str = ""


@dataclass(frozen=True)
class JobOutcome:
    """What a job function returns: the result document and its artifacts.

    ``result`` must be JSON-serialisable (plain dicts, lists, str, float, int, bool,
    None).  Numerical outcomes (an optimiser that did not converge, a design that leaves
    a task point short of full dexterity) belong in ``result`` and ``notes``, not in
    exceptions.  ``errata`` are the notes that set the request against a paper's
    printed values (its errata, found by re-computation; ``docs/methods/``): the result
    document lists them after ``notes`` and again under ``paper_errata``.
    """

    result: Mapping[str, Any]
    artifacts: tuple[Artifact, ...] = ()
    notes: tuple[str, ...] = ()
    errata: tuple[str, ...] = ()

    @property
    def all_notes(self) -> tuple[str, ...]:
        """The notes as the result document lists them: ``notes``, then ``errata``."""
        return (*self.notes, *self.errata)


@dataclass(frozen=True)
class ChildEnd:
    """How a child job of a job that fans out ended, as its parent assembles it."""

    job_id: str
    status: JobStatus
    error: Mapping[str, Any] | None


class JobContext(Protocol):
    """What a running job may tell the outside world."""

    def report_progress(self, percent: float, message: str = "") -> None:
        """Record progress (0-100) and a short human-readable message."""


@dataclass(frozen=True)
class JobRecord:
    """A job as stored.  Times are timezone-aware UTC."""

    job_id: str
    process_id: str
    status: JobStatus
    inputs: Mapping[str, Any]
    created: datetime
    updated: datetime
    progress: float = 0.0
    message: str = ""
    started: datetime | None = None
    finished: datetime | None = None
    attempts: int = 0
    max_attempts: int = 3
    time_limit_s: float = 600.0
    error: Mapping[str, Any] | None = None
    worker_id: str | None = None
    artifacts: tuple[ArtifactInfo, ...] = field(default_factory=tuple)
    #: The API key name that created the job ('' = anonymous: the open service's owner).
    owner: str = ""
    #: When the finished job and its files are deleted (None while it is unfinished).
    expires: datetime | None = None
    #: The job this one is a part of (a chunk of a study), or None.
    parent_id: str | None = None
    #: A job that fans out: None before it splits, 'waiting' while its children run,
    #: 'assembling' once they all ended (worker.store.fan_out).
    phase: str | None = None
    #: Its children: how many, how many ended, how many of those failed.
    children_total: int | None = None
    children_done: int = 0
    children_failed: int = 0
    #: The digest naming the computation (worker.provenance.result_key); None for a job
    #: stored before result keys were.
    result_key: str | None = None
    #: For a job answered by reuse: the job that computed its result (it may since
    #: have been deleted), and whether that job was this job's owner's.
    reused_from: str | None = None
    reused_own: bool = False
    #: The reuse its submission asked for ('owner', 'all'; None: none), and whether
    #: other owners may reuse its result (a study's chunks inherit both).
    reuse_scope: str | None = None
    shareable: bool = True
