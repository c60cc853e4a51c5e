"""A job on the service, as :class:`~dexlab.Client` hands it out: :class:`Job`."""

from __future__ import annotations

import os
import time
from contextlib import closing, suppress
from pathlib import Path
from typing import TYPE_CHECKING, Any

import httpx

from dexlab.connection import read_bytes
from dexlab.documents import Artifact, JobStatus, read_csv, read_npz, safe_file_name
from dexlab.events import EventStreamParser, progress_of
from dexlab.job_view import JobView
from dexlab.progress import ProgressDisplay, progress_display
from dexlab.waiting import WaitClock, events_unsupported, failure_of

if TYPE_CHECKING:
    from dexlab.client import Client

__all__ = ["Job"]


class Job(JobView):
    """A job on the service.  ``result``, ``notes`` and ``artifacts`` fetch the result
    document once the job has succeeded (and keep it); ``status()`` reads the status
    again.  In Jupyter a job shows its status, notes and plots."""

    def __init__(self, client: Client, status: JobStatus) -> None:
        super().__init__(client.connection, status)
        self._client = client

    def status(self) -> JobStatus:
        """The job's status, read now."""
        return self._absorb(self._client.document("GET", self._path()))

    def results(self) -> dict[str, Any]:
        """The whole result document (``result`` and ``artifacts``); fetched once."""
        if self._results is None:
            self._keep_results(self._client.document("GET", self._path("results")))
        return self._results or {}

    @property
    def result(self) -> dict[str, Any]:
        """The result: the members the process lists under ``outputs``, then ``notes``."""
        return self._result_of(self.results())

    @property
    def notes(self) -> list[str]:
        return self._notes_of(self.results())

    @property
    def artifacts(self) -> list[Artifact]:
        """Every file the job wrote (plots, CSV, NPZ), in the service's order."""
        return self._artifacts_of(self.results())

    def read(self, name: str) -> bytes:
        """The bytes of the file ``name`` (as listed in :attr:`artifacts`)."""
        artifact = self._artifact_named(self.results(), name)
        return read_bytes(
            self._client.request(
                "GET", self._path("results", artifact.name), headers={"Accept": "*/*"}
            )
        )

    def arrays(self, name: str) -> dict[str, Any]:
        """The arrays of an NPZ file (e.g. ``"dexterity_map.npz"``): name -> numpy array."""
        return read_npz(self.read(name), name)

    def table(self, name: str) -> list[dict[str, int | float | str]]:
        """The rows of a CSV file (e.g. ``"sweep.csv"``), keyed by its header."""
        return read_csv(self.read(name).decode("utf-8"))

    def download(self, directory: str | os.PathLike[str]) -> list[Path]:
        """Write every file of the job into ``directory`` (made if missing); their paths."""
        folder = Path(directory)
        folder.mkdir(parents=True, exist_ok=True)
        written = []
        for artifact in self.artifacts:
            target = folder / safe_file_name(artifact.name)
            partial = target.with_name(f".{target.name}.part")
            partial.write_bytes(self.read(artifact.name))
            partial.replace(target)
            written.append(target)
        return written

    def cancel(self) -> JobStatus:
        """Dismiss the job: a queued job never runs, a running one is stopped, a
        finished one's results are deleted."""
        return self._absorb(self._client.document("DELETE", self._path()))

    def wait(
        self, timeout: float | None = None, *, progress: bool | ProgressDisplay = False
    ) -> Job:
        """Wait until the job ends (see :mod:`dexlab.waiting`); the job, its results
        fetched.  Raises :class:`~dexlab.errors.JobFailed` or
        :class:`~dexlab.errors.JobDismissed` if it ended without results, and
        :class:`~dexlab.errors.WaitTimeout` after ``timeout`` seconds."""
        clock = WaitClock(timeout, self.id)
        with closing(progress_display(progress, f"{self.process_id} {self.id[:8]}")) as display:
            status = self.status()
            display.update(status)
            while not status.done:
                clock.check(status)
                self._follow(clock, display)
                status = self.status()
                display.update(status)
        failure = failure_of(status)
        if failure is not None:
            raise failure
        self.results()
        return self

    def _follow(self, clock: WaitClock, display: ProgressDisplay) -> None:
        """Follow the event stream until the job ends or the stream does; poll once
        where there is no stream."""
        if clock.events:
            before = self._status
            with suppress(httpx.TransportError):  # a broken stream: the status read retries
                self._stream(clock, display)
            if self._status != before:
                clock.progressed()
                return
        time.sleep(clock.pause())

    def _stream(self, clock: WaitClock, display: ProgressDisplay) -> None:
        request = self._client.build_request(
            "GET", self._path("events"), headers={"Accept": "text/event-stream"},
            timeout=httpx.Timeout(self._client.connection.timeout, read=clock.read_timeout()),
        )  # fmt: skip
        with closing(self._client.send(request, stream=True)) as response:
            if events_unsupported(response):
                clock.events = False
                return
            if response.status_code >= 400:
                return  # about the job (gone, not yours): the status read reports it
            parser = EventStreamParser()
            for line in response.iter_lines():
                event = parser.feed(line)
                payload = progress_of(event) if event is not None else None
                if payload is not None:
                    self._status = self._status.with_event(payload)
                    display.update(self._status)
                    if self._status.done:
                        return
