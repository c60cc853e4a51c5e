"""What a job handle knows without asking the service, shared by :class:`~dexlab.Job`
and :class:`~dexlab.AsyncJob`: the last status seen, the result document once fetched,
the views over it (result, notes, files) and how a job shows itself in Jupyter."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

import httpx

from dexlab.connection import Connection, api_path, json_object, read_bytes
from dexlab.documents import Artifact, JobStatus
from dexlab.errors import DexlabError, NoSuchArtifact, ResultNotReady
from dexlab.notebook import Plot, job_html
from dexlab.waiting import failure_of

__all__ = ["JobView"]


class JobView:
    """A job's state as last seen (see :class:`~dexlab.Job` for the methods that ask)."""

    def __init__(self, connection: Connection, status: JobStatus) -> None:
        self._connection = connection
        self._status = status
        self._results: dict[str, Any] | None = None
        self._plots: dict[str, bytes | str] = {}

    @property
    def id(self) -> str:
        """The job ID."""
        return self._status.job_id

    @property
    def process_id(self) -> str:
        return self._status.process_id

    @property
    def last_status(self) -> JobStatus:
        """The status as last read (no request; ``status()`` reads it again)."""
        return self._status

    def _path(self, *rest: str) -> str:
        return api_path("jobs", self.id, *rest)

    def _absorb(self, document: Any) -> JobStatus:
        doc = json_object(document, "The job's status document")
        self._status = JobStatus.from_document(doc)
        if self._status.status != "successful":
            self._results = None
        return self._status

    def _keep_results(self, document: Any) -> dict[str, Any]:
        self._results = dict(json_object(document, "The job's result document"))
        return self._results

    def _cached_results(self) -> dict[str, Any]:
        """The result document if fetched; else why there is none yet."""
        if self._results is not None:
            return self._results
        failure = failure_of(self._status)
        if failure is not None:
            raise failure
        raise ResultNotReady(
            {"type": "/problems/result-not-ready", "title": "Result not ready",
             "detail": f"Job {self.id} was {self._status} when last read; wait for it "
             "(job.wait()) before reading its results.", "jobID": self.id},
        )  # fmt: skip

    # Views over a result document.

    @staticmethod
    def _result_of(document: Mapping[str, Any]) -> dict[str, Any]:
        return dict(json_object(document.get("result"), "The job's result"))

    @staticmethod
    def _notes_of(document: Mapping[str, Any]) -> list[str]:
        notes = document.get("result", {}).get("notes") or []
        return [str(note) for note in notes] if isinstance(notes, list) else [str(notes)]

    @staticmethod
    def _artifacts_of(document: Mapping[str, Any]) -> list[Artifact]:
        found = document.get("artifacts") or []
        return [Artifact.from_document(a) for a in found if isinstance(a, Mapping)]

    def _artifact_named(self, document: Mapping[str, Any], name: str) -> Artifact:
        files = self._artifacts_of(document)
        for artifact in files:
            if artifact.name == name:
                return artifact
        listed = ", ".join(a.name for a in files) or "none"
        raise NoSuchArtifact(
            {"type": "/problems/no-such-artifact", "title": "No such artifact",
             "detail": f"Job {self.id} has no file {name!r}; it has: {listed}.",
             "jobID": self.id},
        )  # fmt: skip

    # Jupyter.

    def _display_get(self, path: str) -> bytes:
        """GET for display (a synchronous call, as ``_repr_html_`` is): one try."""
        conn = self._connection
        with httpx.Client(base_url=conn.url, headers=conn.headers(), timeout=conn.timeout) as http:
            return read_bytes(http.get(path, headers={"Accept": "*/*"}))

    def _display_results(self) -> dict[str, Any]:
        if self._results is None:
            self._keep_results(json.loads(self._display_get(self._path("results"))))
        return self._cached_results()

    def _display_plot(self, artifact: Artifact) -> bytes | str:
        if artifact.name not in self._plots:
            try:
                self._plots[artifact.name] = self._display_get(self._path("results", artifact.name))
            except (DexlabError, httpx.HTTPError) as exc:
                return str(exc) or type(exc).__name__  # not cached: the next display retries
        return self._plots[artifact.name]

    def _repr_html_(self) -> str:
        """The job in a notebook: status, progress, failure, notes and plots inline."""
        status = self._status
        if status.status != "successful":
            return job_html(status)
        try:
            document = self._display_results()
        except (DexlabError, httpx.HTTPError, ValueError) as exc:
            return job_html(status, notes=[f"The results could not be read: {exc}"])
        files = self._artifacts_of(document)
        plots: list[Plot] = [
            (a, self._display_plot(a)) for a in files if a.media_type == "image/png"
        ]
        return job_html(status, notes=self._notes_of(document), plots=plots, files=files)

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.id} {self.process_id}: {self._status}>"
