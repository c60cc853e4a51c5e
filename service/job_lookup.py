"""Finding a job for a request, and saying why when there is none; the page of jobs a
``/v1/jobs`` request lists.

A job the caller may not see, or that never existed, is ``404 no-such-job``; one that
expired (its retention ended, :mod:`worker.store.retention`) is ``410 job-expired``
while its tombstone is kept, then ``404`` too.  Blocking store work: call it from the
threadpool (a sync route, or ``run_in_threadpool``).
"""

from __future__ import annotations

from service.auth.identity import Identity
from service.parameters import JobListQuery
from worker.contract import JobRecord
from worker.errors import DexlabError, JobExpired, NoSuchJob
from worker.store.base import JobFilter, JobPage, JobStore

__all__ = ["find_job", "list_jobs", "missing_job"]


def missing_job(store: JobStore, job_id: str, owner: str | None) -> DexlabError:
    """The error for a job ``owner`` (None: anyone) cannot find: expired, or none."""
    expired = store.expired_at(job_id, owner=owner)
    if expired is None:
        return NoSuchJob(f"No job {job_id!r}.")
    when = expired.isoformat(timespec="seconds").replace("+00:00", "Z")
    return JobExpired(
        f"Job {job_id} expired at {when}: its retention ended, and it and its results were deleted."
    )


def find_job(store: JobStore, job_id: str, owner: str | None) -> JobRecord:
    """The job, if it exists and ``owner`` (None: anyone) owns it; else the error that
    says why not (:func:`missing_job`)."""
    job = store.get_job(job_id, owner=owner)
    if job is None:
        raise missing_job(store, job_id, owner)
    return job


def list_jobs(store: JobStore, identity: Identity, query: JobListQuery) -> JobPage:
    """The page of jobs ``query`` selects among those ``identity`` may see (an admin:
    ``owner``'s, when it names one)."""
    scope = identity.owner_filter(query.owner)
    where = None if query.parent is None else JobFilter(parent_id=query.parent)
    return store.list_jobs(
        limit=query.limit, cursor=query.cursor, status=query.status,
        process_id=query.process_id, owner=scope, where=where,
    )  # fmt: skip
