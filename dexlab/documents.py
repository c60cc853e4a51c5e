"""The service's documents as the client hands them out, and its data files read safely.

:class:`JobStatus` is a status document (``GET /v1/jobs/{id}``), :class:`Artifact` one
entry of a result's file list; :func:`read_npz` and :func:`read_csv` read the NPZ and
CSV files jobs write.  No I/O here: both clients use these.
"""

from __future__ import annotations

import csv
import io
import zipfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = [
    "TERMINAL_STATUSES",
    "Artifact",
    "JobStatus",
    "example_inputs",
    "read_csv",
    "read_npz",
    "safe_file_name",
]

#: Statuses a job never leaves.
TERMINAL_STATUSES = frozenset({"successful", "failed", "dismissed"})


@dataclass(frozen=True)
class JobStatus:
    """Where a job is: ``status`` is ``accepted``, ``running``, ``successful``,
    ``failed`` or ``dismissed``; ``progress`` 0-100; ``error`` the failure's
    ``{type, title, detail}`` when failed; ``document`` the whole status document."""

    job_id: str
    process_id: str
    status: str
    progress: int
    message: str
    error: dict[str, Any] | None = None
    document: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @classmethod
    def from_document(cls, doc: Mapping[str, Any]) -> JobStatus:
        error = doc.get("error")
        return cls(
            job_id=str(doc["jobID"]),
            process_id=str(doc.get("processID", "")),
            status=str(doc["status"]),
            progress=int(doc.get("progress") or 0),
            message=str(doc.get("message") or ""),
            error=dict(error) if isinstance(error, Mapping) else None,
            document=dict(doc),
        )

    def with_event(self, event: Mapping[str, Any]) -> JobStatus:
        """This status after a ``progress`` event (``{status, progress, message}``)."""
        doc = {**self.document, "jobID": self.job_id, "processID": self.process_id}
        for key in ("status", "progress", "message"):
            if key in event:
                doc[key] = event[key]
        if doc.get("status") != "failed":
            doc.pop("error", None)
        return JobStatus.from_document(doc)

    @property
    def done(self) -> bool:
        """Whether the job has ended (successful, failed or dismissed)."""
        return self.status in TERMINAL_STATUSES

    def __str__(self) -> str:
        text = f"{self.status} ({self.progress}%)"
        return f"{text}: {self.message}" if self.message else text


@dataclass(frozen=True)
class Artifact:
    """One file a job wrote: ``name`` (e.g. ``heatmap.png``), ``media_type``,
    ``title``, ``size`` in bytes and ``href`` (the service's path to it)."""

    name: str
    media_type: str
    title: str = ""
    size: int = 0
    href: str = ""

    @classmethod
    def from_document(cls, doc: Mapping[str, Any]) -> Artifact:
        return cls(
            name=str(doc["name"]),
            media_type=str(doc.get("media_type", "application/octet-stream")),
            title=str(doc.get("title") or ""),
            size=int(doc.get("size") or 0),
            href=str(doc.get("href") or ""),
        )


def example_inputs(process_id: str, description: Mapping[str, Any], example: int) -> dict[str, Any]:
    """The inputs of worked example ``example`` (from 0, in the order the process
    lists them) of a process description."""
    examples: Sequence[Any] = description.get("examples") or []
    if isinstance(example, bool) or not isinstance(example, int):
        raise TypeError(f"The 'example' parameter must be an int. Got {example!r} instead.")
    if not 0 <= example < len(examples):
        which = f"0 to {len(examples) - 1}" if examples else "none: it has no examples"
        raise ValueError(
            f"The 'example' parameter of {process_id} must be one of its {len(examples)} "
            f"worked examples ({which}). Got {example} instead."
        )
    return dict(examples[example]["inputs"])


def read_npz(data: bytes, name: str = "the file") -> dict[str, NDArray[Any]]:
    """Every array of an NPZ file, by name.  Read with ``allow_pickle=False``: a file
    holding Python objects is refused, never unpickled."""
    import numpy as np

    try:
        with np.load(io.BytesIO(data), allow_pickle=False) as archive:
            return {key: archive[key] for key in archive.files}
    except (ValueError, OSError, zipfile.BadZipFile, EOFError) as exc:
        raise ValueError(f"{name} is not an NPZ file of plain arrays: {exc}") from exc


def _number_or_text(text: str) -> int | float | str:
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        return text


def read_csv(text: str) -> list[dict[str, int | float | str]]:
    """A CSV file's rows as dicts keyed by its header; numbers read as int or float,
    anything else (and an empty cell) kept as text."""
    return [
        {
            key: _number_or_text(value if isinstance(value, str) else "")
            for key, value in row.items()
            if key is not None
        }
        for row in csv.DictReader(io.StringIO(text))
    ]


def safe_file_name(name: str) -> str:
    """``name`` if it is a plain file name (no directory part, not hidden); else a
    ValueError (a file name from the service must never write outside a folder)."""
    if not name or name in {".", ".."} or name.startswith(".") or "/" in name or "\\" in name \
            or "\x00" in name:  # fmt: skip
        raise ValueError(f"The artifact name {name!r} is not a plain file name.")
    return name
