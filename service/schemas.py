"""The JSON documents of ``/v1``: one pydantic model each, the one source of truth.

The handlers build these models (:mod:`service.documents`, :mod:`service.routes`) and
return them; each route declares its model as ``response_model``, so FastAPI both
publishes it in ``/openapi.json`` and serializes the answer with it (schemathesis checks
every answer against the published schema).  The routes serialize with
``response_model_exclude_unset``: an optional member a document leaves out (a
``worker_id`` a caller may not see, a job's ``error`` before it failed) is absent, not
``null``; a member set to ``None`` is ``null``.
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field
from pydantic.json_schema import models_json_schema

__all__ = [
    "RETENTION",
    "REUSE",
    "SHARE",
    "STREAM_DOCUMENTS",
    "ArtifactLink",
    "Chunks",
    "JobError",
    "JobList",
    "JobResult",
    "Landing",
    "Link",
    "Liveness",
    "LocalPool",
    "ProblemTypeDocument",
    "ProcessDescription",
    "ProcessList",
    "ProcessSummary",
    "ProgressEvent",
    "Readiness",
    "ResultsDocument",
    "StatusDocument",
    "stream_document_schemas",
]

#: The execute body's ``retention_s`` (a number, never a string or a boolean).
RETENTION: Any = Field(
    None,
    gt=0,
    allow_inf_nan=False,
    strict=True,
    description="Keep the finished job and its results this many seconds (at most, and "
    "by default, the service's DEXLAB_RESULT_TTL_S); the status document's `expires` "
    "says until when.",
)


#: The execute body's ``reuse`` (beside ``inputs``, so input schemas and keys stay).
REUSE: Any = Field(
    True,
    strict=True,
    description="false: compute afresh, whatever result of the same inputs is stored "
    "(`Cache-Control: no-cache` says the same); true: a stored result of the same result "
    "key may answer the job at once (`reused_from` in its documents).",
)
#: The execute body's ``share``.
SHARE: Any = Field(
    True,
    strict=True,
    description="false: this job's result is never reused by another API key's job.",
)


#: The status and results documents' ``reused_from``.
REUSED_FROM: Any = Field(
    None,
    description="A job answered at once by a stored result of the same result key: the "
    "ID of the job that computed it when that job was the caller's (or the caller is an "
    "admin), else true; absent for a job that computed its own result.",
)


class _Document(BaseModel):
    model_config = ConfigDict(extra="forbid")


class Link(_Document):
    href: str
    rel: str
    type: str | None = None
    title: str | None = None


class JobError(_Document):
    type: str
    title: str | None = None
    detail: str | None = None


class Chunks(_Document):
    """A design study's chunk jobs (list them with ``GET /v1/jobs?parent=<jobID>``)."""

    total: int
    ended: int
    failed: int


class StatusDocument(_Document):
    """``GET /v1/jobs/{jobID}``: where a job is."""

    jobID: str
    processID: str
    type: Literal["process"]
    status: Literal["accepted", "running", "successful", "failed", "dismissed"]
    progress: int = Field(ge=0, le=100)
    message: str | None
    created: str | None
    started: str | None
    finished: str | None
    updated: str | None
    attempts: int
    max_attempts: int
    time_limit_s: float
    expires: str | None = Field(
        None,
        description="When the finished job and its results are deleted (then 410 "
        "job-expired, later 404); null while it is unfinished.",
    )
    worker_id: str | None = Field(
        None,
        description="The worker process running or last running the job (host:pid); "
        "with API keys, shown to admin keys only.",
    )
    owner: str | None = Field(
        None,
        description="The API key that created the job ('' = anonymous); with API keys, "
        "shown to admin keys only.",
    )
    links: list[Link]
    error: JobError | None = None
    parentID: str | None = Field(
        None, description="The study this job is a chunk of (design-study); absent otherwise."
    )
    chunks: Chunks | None = Field(
        None, description="A study's chunk jobs: how many, how many ended, how many failed."
    )
    reused_from: str | bool | None = REUSED_FROM


class JobList(_Document):
    """``GET /v1/jobs``: a page of jobs, newest first."""

    jobs: list[StatusDocument]
    next_cursor: str | None
    links: list[Link]


class ArtifactLink(_Document):
    name: str
    media_type: str
    title: str
    size: int
    href: str


class JobResult(BaseModel):
    """A job's result: the members its process describes under ``outputs``, then its
    notes.  ``paper_errata`` repeats the notes that set the request against the paper's
    printed values (the errata of docs/methods/<page>.md), so pages can mark them."""

    model_config = ConfigDict(extra="allow")

    notes: list[str] = Field(
        description="What a reader should know about this result, the paper's errata last."
    )
    paper_errata: list[str] = Field(
        default_factory=list,
        description="The notes (also in 'notes', in the same order) that correct the paper's "
        "printed values for a request that is one of its examples; [] for other requests.",
    )


class ResultsDocument(_Document):
    """``GET /v1/jobs/{jobID}/results``: the result and a link to every artifact."""

    jobID: str
    processID: str
    reused_from: str | bool | None = REUSED_FROM
    result: JobResult
    artifacts: list[ArtifactLink]
    links: list[Link]


class ProcessSummary(_Document):
    id: str
    title: str
    description: str
    version: str
    links: list[Link]


class ProcessList(_Document):
    """``GET /v1/processes``."""

    processes: list[ProcessSummary]
    links: list[Link]


class ProcessExampleDocument(_Document):
    title: str
    description: str
    inputs: dict[str, Any]


class ProcessLimits(_Document):
    cost_limit: int
    cost_unit: str
    time_limit_s: float
    sync_cost_limit: int


class ResultPathDocument(_Document):
    """One number a process reports: where it sits in the result, its unit, its symbol."""

    path: str = Field(description="The result path, in the design studies' syntax: '[]' for "
                      "every element of a list, '*' for every key of a mapping keyed by the "
                      "request's own paths (e.g. 'task_points[].d_z').")  # fmt: skip
    unit: str = Field(description="'-' (a pure number), 'length' (the job's length_unit), "
                      "'length^2', 'length^3', 'length^4', 'length^n', 'l1', 'l1^2', 'deg', "
                      "'deg^2' or 'mixed' (docs/data-files.md).")  # fmt: skip
    symbol: str = Field(description="The symbol as mathtext ('$d_z$'); '' for none.")
    description: str
    kernel: bool = Field(False, description="true where the process's study kernel computes "
                         "this number: a design study reading it runs batched (present only "
                         "then).")  # fmt: skip


class ProcessDescription(_Document):
    """``GET /v1/processes/{processID}``: its input schema, worked examples, limits."""

    id: str
    title: str
    description: str
    version: str
    jobControlOptions: list[str]
    inputs: dict[str, Any] = Field(description="The inputs' JSON Schema.")
    outputs: dict[str, str]
    result_paths: list[ResultPathDocument] = Field(
        description="Every number the result holds, with its unit and symbol."
    )
    examples: list[ProcessExampleDocument]
    limits: ProcessLimits
    links: list[Link]


class ProgressEvent(_Document):
    """The data (JSON) of a ``progress`` event of ``GET /v1/jobs/{jobID}/events``."""

    status: Literal["accepted", "running", "successful", "failed", "dismissed"]
    progress: int = Field(ge=0, le=100, description="Percent done, rounded.")
    message: str = Field(description="What the job is doing, as its status says.")


class Landing(_Document):
    """``GET /`` and ``GET /v1``: where to go from here."""

    title: str
    description: str
    links: list[Link]


class Liveness(_Document):
    """``GET /health/live``: the process answers."""

    status: Literal["live"]


class LocalPool(_Document):
    """This process's worker pool: its size and how many of its workers are alive."""

    size: int
    alive: int


class Readiness(_Document):
    """``GET /health/ready`` (200): the store takes a write and a worker is up."""

    status: Literal["ready"]
    store: Literal["ok"]
    live_workers: int
    local_pool: LocalPool | None = Field(
        description="This process's worker pool; null where no pool runs here (a broker's "
        "workers, or DEXLAB_WORKERS=0)."
    )


class ProblemTypeDocument(_Document):
    """``GET /problems/{slug}``: what a problem type means."""

    type: str
    title: str
    status: int
    description: str


#: The documents no route returns as its response model (the progress stream's events):
#: added to the OpenAPI document's components by :mod:`service.openapi`.
STREAM_DOCUMENTS: tuple[type[BaseModel], ...] = (ProgressEvent,)


def stream_document_schemas() -> dict[str, Any]:
    """The component schemas of :data:`STREAM_DOCUMENTS` (and the models they use)."""
    _, top = models_json_schema(
        [(m, "serialization") for m in STREAM_DOCUMENTS],
        ref_template="#/components/schemas/{model}",
    )
    schemas: dict[str, Any] = top.get("$defs", {})
    return schemas
