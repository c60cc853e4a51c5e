"""A design study's table of designs, for the JSON routes and the study's page.

The caller must see the study as for its results (another owner's is 404); a job that is
not a design study, or has no designs file, is ``404 no-such-artifact``; one not
finished, ``result-not-ready``.  The table is read once per stored file
(:class:`~worker.studies.design_table.DesignTables`, built in the app's lifespan).
"""

from __future__ import annotations

from service.deps import Api
from service.routes.jobs import finished_job
from worker.errors import JobDismissed, NoSuchArtifact
from worker.studies.design_table import DesignTable, DesignTables

__all__ = ["STUDY_PROCESS", "study_table"]

#: The process whose jobs have designs.
STUDY_PROCESS = "design-study"


def study_table(tables: DesignTables, api: Api, job_id: str) -> tuple[str, DesignTable]:
    """The process the study ran, and its designs."""
    job = finished_job(api.store, job_id, api.identity.owner_scope)
    stored = api.store.artifact(job.job_id, "designs.npz")
    result = api.store.get_result(job.job_id) or {}
    if job.process_id != STUDY_PROCESS or stored is None:
        raise NoSuchArtifact(f"Job {job_id} is not a design study: it has no designs.")

    def read() -> bytes:
        try:
            return b"".join(api.store.artifact_chunks(job.job_id, stored))
        except FileNotFoundError as exc:
            raise JobDismissed(f"Job {job_id} was dismissed; it has no results.") from exc

    return str(result.get("process", "")), tables.get(stored.etag, read)
