"""Job IDs as people type them: any unique prefix of a job the caller can see.

A job's full ID always works (a study's chunk too).  Otherwise the caller's jobs are
searched for IDs starting with what was typed: client jobs first, then, only if none
matches, the chunk jobs of the caller's studies.  Several matches at the first level
that has any is :class:`AmbiguousJobId` (exit 2, the candidates listed); none is the
service's own ``no-such-job`` (exit 1).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import click

from dexlab.client import Client
from dexlab.connection import api_path
from dexlab.documents import JobStatus
from dexlab.errors import NoSuchJob
from dexlab.job import Job

__all__ = ["AmbiguousJobId", "find_job", "short_ids"]

#: Jobs asked for per listing page while searching (the service's largest page).
_PAGE = 1000
#: Candidates listed when a prefix is ambiguous (the rest are counted).
_SHOWN_CANDIDATES = 10
#: The fewest characters of a job ID a table shows.
_SHORTEST_ID = 8


class AmbiguousJobId(click.ClickException):
    """More than one of the caller's jobs starts with the typed ID (exit status 2)."""

    exit_code = 2

    def __init__(self, given: str, candidates: Sequence[JobStatus]) -> None:
        lines = [f"'{given}' starts {len(candidates)} job IDs; type more of the ID:"]
        for status in candidates[:_SHOWN_CANDIDATES]:
            created = str(status.document.get("created") or "")[:19].replace("T", " ")
            lines.append(f"  {status.job_id}  {status.process_id}  {status.status}  {created}")
        if len(candidates) > _SHOWN_CANDIDATES:
            lines.append(f"  ... and {len(candidates) - _SHOWN_CANDIDATES} more")
        super().__init__("\n".join(lines))
        self.candidates = list(candidates)


def _listing(client: Client, parent: str | None = None) -> Iterable[JobStatus]:
    """Every job the caller sees, newest first: client jobs, or ``parent``'s chunks."""
    params: dict[str, str | int] = {"limit": _PAGE}
    if parent is not None:
        params["parent"] = parent
    while True:
        page = client.document("GET", api_path("jobs"), params=params)
        for doc in page.get("jobs") or []:
            yield JobStatus.from_document(doc)
        cursor = page.get("next_cursor")
        if not cursor:
            return
        params["cursor"] = cursor


def find_job(client: Client, given: str) -> Job:
    """The job whose ID is ``given``, or the one job whose ID starts with it.

    Raises :class:`AmbiguousJobId` for several, :class:`~dexlab.errors.NoSuchJob` for
    none (the answer to the exact ID)."""
    if not given.strip():
        raise click.BadParameter("must not be empty", param_hint="'JOB'")
    try:
        return client.job(given)
    except NoSuchJob as missing:
        not_found = missing
    top_level = list(_listing(client))
    matches = [s for s in top_level if s.job_id.startswith(given)]
    if not matches:
        studies = [s for s in top_level if (s.document.get("chunks") or {}).get("total")]
        matches = [
            chunk
            for study in studies
            for chunk in _listing(client, study.job_id)
            if chunk.job_id.startswith(given)
        ]
    if len(matches) > 1:
        raise AmbiguousJobId(given, matches)
    if not matches:
        raise not_found
    return Job(client, matches[0])


def short_ids(job_ids: Sequence[str]) -> list[str]:
    """Each ID cut to its shortest prefix (at least 8 characters) that no other ID in
    ``job_ids`` shares; what ``find_job`` accepts back while no newer job shares it."""
    shown = []
    for job_id in job_ids:
        length = _SHORTEST_ID
        while length < len(job_id) and any(
            other != job_id and other.startswith(job_id[:length]) for other in job_ids
        ):
            length += 1
        shown.append(job_id[:length])
    return shown
