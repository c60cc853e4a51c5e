"""Shaping stored records into the JSON documents the API returns (OGC API - Processes)."""

from __future__ import annotations

from collections.abc import Mapping
from datetime import datetime
from typing import Any

from pydantic import BaseModel

from service.schemas import (
    ArtifactLink,
    Chunks,
    JobError,
    JobResult,
    Link,
    ResultsDocument,
    StatusDocument,
)
from worker.contract import ArtifactInfo, JobRecord, JobStatus
from worker.store.base import StoredArtifact

__all__ = [
    "artifact_headers",
    "artifact_link",
    "as_json",
    "job_href",
    "results_document",
    "status_document",
]

JSON = "application/json"


def as_json(document: BaseModel) -> dict[str, Any]:
    """A document as the API sends it (the members it set, by their JSON names): what
    a page shows of it."""
    return document.model_dump(mode="json", by_alias=True, exclude_unset=True)


def _iso(value: datetime | None) -> str | None:
    return None if value is None else value.isoformat().replace("+00:00", "Z")


def job_href(job_id: str) -> str:
    return f"/v1/jobs/{job_id}"


def reused_from(job: JobRecord, admin: bool) -> str | bool | None:
    """What a document says of the job a reused result came from: its ID for an admin
    or when that job was this job's owner's (even once deleted), else ``True``; None
    for a job that computed its own result."""
    if job.reused_from is None:
        return None
    return job.reused_from if admin or job.reused_own else True


def status_document(
    job: JobRecord, *, worker: bool = True, owner: bool = False, admin: bool = False
) -> StatusDocument:
    """``GET /v1/jobs/{jobID}``: where the job is, with links; ``worker_id`` when
    ``worker`` (admins only, with API keys), the job's ``owner`` when ``owner``,
    ``reused_from`` for a job answered by a stored result (:func:`reused_from`)."""
    links = [
        Link(href=job_href(job.job_id), rel="self", type=JSON, title="this status document"),
        Link(href=f"/v1/processes/{job.process_id}", rel="process", type=JSON,
             title="the process description"),
    ]  # fmt: skip
    if job.status is JobStatus.SUCCESSFUL:
        links.append(Link(href=f"{job_href(job.job_id)}/results", rel="results", type=JSON,
                          title="the result document"))  # fmt: skip
    optional: dict[str, Any] = {}
    if worker:
        optional["worker_id"] = job.worker_id
    if owner:
        optional["owner"] = job.owner
    if job.status is JobStatus.FAILED and job.error is not None:
        optional["error"] = JobError.model_validate(
            {k: job.error[k] for k in ("type", "title", "detail") if k in job.error}
        )
    if job.parent_id is not None:
        optional["parentID"] = job.parent_id
    if job.children_total is not None:
        optional["chunks"] = Chunks(total=job.children_total, ended=job.children_done,
                                    failed=job.children_failed)  # fmt: skip
    origin = reused_from(job, admin)
    if origin is not None:
        optional["reused_from"] = origin
    return StatusDocument(
        jobID=job.job_id,
        processID=job.process_id,
        type="process",
        status=job.status.value,
        progress=round(job.progress),
        message=job.message,
        created=_iso(job.created),
        started=_iso(job.started),
        finished=_iso(job.finished),
        updated=_iso(job.updated),
        attempts=job.attempts,
        max_attempts=job.max_attempts,
        time_limit_s=job.time_limit_s,
        expires=_iso(job.expires),
        links=links,
        **optional,
    )


def artifact_link(base: str, artifact: ArtifactInfo) -> ArtifactLink:
    """An artifact of the job at ``base``: what it is and where to download it."""
    return ArtifactLink(
        name=artifact.name,
        media_type=artifact.media_type,
        title=artifact.title,
        size=artifact.size,
        href=f"{base}/results/{artifact.name}",
    )


def results_document(
    job: JobRecord, result: Mapping[str, Any], *, admin: bool = False
) -> ResultsDocument:
    """``GET /v1/jobs/{jobID}/results``: the result and every artifact's link (and
    ``reused_from``, as in :func:`status_document`)."""
    base = job_href(job.job_id)
    origin = reused_from(job, admin)
    return ResultsDocument(
        jobID=job.job_id,
        processID=job.process_id,
        **({} if origin is None else {"reused_from": origin}),
        result=JobResult.model_validate(dict(result)),
        artifacts=[artifact_link(base, a) for a in job.artifacts],
        links=[
            Link(href=f"{base}/results", rel="self", type=JSON),
            Link(href=base, rel="up", type=JSON, title="the job's status"),
        ],
    )


#: Media types a browser must not render in place (data files download).
_DOWNLOADS = frozenset({"text/csv", "application/x-npz", "application/octet-stream"})

#: An SVG is served with a policy that lets it style itself and nothing more: no
#: scripts, no requests, sandboxed.
SVG_POLICY = "default-src 'none'; style-src 'unsafe-inline'; sandbox"


def artifact_headers(stored: StoredArtifact) -> dict[str, str]:
    """The headers of an artifact download: a strong ETag (the bytes' SHA-256),
    ``Cache-Control: private`` (it can be deleted, so never ``immutable``), data files
    as attachments, SVG under a script-free policy."""
    info = stored.info
    disposition = "attachment" if info.media_type in _DOWNLOADS else "inline"
    headers = {
        "ETag": f'"{stored.etag}"',
        "Cache-Control": "private, no-cache",
        "Content-Disposition": f'{disposition}; filename="{info.name}"',
        "X-Content-Type-Options": "nosniff",
    }
    if info.media_type == "image/svg+xml":
        headers["Content-Security-Policy"] = SVG_POLICY
    return headers
