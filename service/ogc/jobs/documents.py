"""Status information (statusInfo.yaml) and job lists (jobList.yaml) of the façade."""

from __future__ import annotations

from collections.abc import Sequence
from datetime import datetime

from service.documents import reused_from
from service.ogc.schemas import OgcJobList, OgcLink, OgcStatusInfo
from service.ogc.urls import PublicUrls, self_and_alternate
from service.ogc.vocabulary import JSON, REL_EXCEPTIONS, REL_RESULTS
from worker.contract import JobRecord, JobStatus

__all__ = ["job_list", "status_info"]


def _iso(value: datetime) -> str:
    return value.isoformat().replace("+00:00", "Z")


def status_info(job: JobRecord, urls: PublicUrls, *, admin: bool = False) -> OgcStatusInfo:
    """Where a job is: status, progress, the times known so far, and links to itself
    (as JSON and as a page), the job list, its process and (when finished) its results
    or its exception; ``reused_from`` for a job answered by a stored result (the
    original job's ID when the caller owns it or is an ``admin``, else true)."""
    href = urls.job(job.job_id)
    links = [
        *self_and_alternate(href, "this status information"),
        {"href": f"{urls.ogc}/jobs", "rel": "up", "type": JSON, "title": "the job list"},
        {
            "href": urls.process(job.process_id),
            "rel": "describedby",
            "type": JSON,
            "title": "the process description",
        },
    ]
    if job.status is JobStatus.SUCCESSFUL:
        links.append(
            {
                "href": urls.results(job.job_id),
                "rel": REL_RESULTS,
                "type": JSON,
                "title": "the job's results",
            }
        )
    elif job.status is JobStatus.FAILED:
        links.append(
            {
                "href": urls.results(job.job_id),
                "rel": REL_EXCEPTIONS,
                "type": "application/problem+json",
                "title": "why the job failed",
            }
        )
    # Times not reached yet are left out (the schema has no null date-time); so is
    # dexlab's own ``expires`` (statusInfo.yaml allows members it does not list) until
    # the job has finished: when it and its results are deleted.
    times = {
        name: _iso(value)
        for name, value in (
            ("started", job.started),
            ("finished", job.finished),
            ("expires", job.expires),
        )
        if value is not None
    }
    origin = reused_from(job, admin)
    extra = {} if origin is None else {"reused_from": origin}
    return OgcStatusInfo(
        processID=job.process_id,
        type="process",
        jobID=job.job_id,
        status=job.status.value,
        message=job.message,
        progress=max(0, min(100, round(job.progress))),
        created=_iso(job.created),
        updated=_iso(job.updated),
        **times,
        **extra,
        links=[OgcLink.model_validate(link) for link in links],
    )


def job_list(
    jobs: Sequence[JobRecord],
    urls: PublicUrls,
    self_href: str,
    next_href: str | None,
    *,
    admin: bool = False,
) -> OgcJobList:
    """A page of jobs, newest first, with ``self``, ``alternate`` (the page as HTML)
    and, when more remain, ``next``."""
    links = self_and_alternate(self_href, "this page of jobs")
    if next_href is not None:
        links.append({"href": next_href, "rel": "next", "type": JSON, "title": "the next page"})
    return OgcJobList(
        jobs=[status_info(job, urls, admin=admin) for job in jobs],
        links=[OgcLink.model_validate(link) for link in links],
    )
