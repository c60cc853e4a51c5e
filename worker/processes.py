"""What a process is: the contract between the families and the runtime.

A process definition ties together the validated input model (pydantic, frozen,
``extra="forbid"``), the function that runs it, the paper's worked examples, a
description of its outputs, and its cost limit (checked before anything is queued).
A family says who it is with a :class:`FamilyInfo`; a :class:`ProcessRegistry` holds
the definitions by ID and the family of each.  This module imports no family: the
families import it, and :mod:`worker.registry` assembles them.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Protocol

from pydantic import BaseModel

from worker.contract import ChildEnd, JobContext, JobOutcome
from worker.errors import NoSuchProcess
from worker.previews import DataChart, PreviewField, ProcessPreview
from worker.result_paths import ResultPathInfo
from worker.study_kernels import StudyKernel

__all__ = [
    "ChildFiles",
    "ChildResults",
    "DataChart",
    "FamilyInfo",
    "FamilyPackage",
    "FanOutSteps",
    "PaperPoint",
    "PreviewField",
    "ProcessDefinition",
    "ProcessExample",
    "ProcessFile",
    "ProcessPreview",
    "ProcessRegistry",
    "ResultPathInfo",
    "StudyKernel",
    "data_files",
    "figure_files",
]

#: File extension -> media type of the files jobs write.
FILE_MEDIA_TYPES: Mapping[str, str] = {
    "png": "image/png",
    "svg": "image/svg+xml",
    "csv": "text/csv",
    "npz": "application/x-npz",
}


@dataclass(frozen=True)
class ProcessExample:
    """A worked example: the paper's inputs, ready to POST."""

    title: str
    inputs: Mapping[str, Any]
    description: str = ""


@dataclass(frozen=True)
class ProcessFile:
    """A file a job of the process can write (an artifact), by name."""

    name: str
    title: str

    @property
    def media_type(self) -> str:
        return FILE_MEDIA_TYPES[self.name.rsplit(".", 1)[-1]]


def figure_files(stem: str, title: str) -> tuple[ProcessFile, ProcessFile]:
    """A figure's two files: ``<stem>.png`` and ``<stem>.svg``."""
    return ProcessFile(f"{stem}.png", f"{title} (PNG)"), ProcessFile(
        f"{stem}.svg", f"{title} (SVG)"
    )


def data_files(stem: str, title: str) -> tuple[ProcessFile, ProcessFile]:
    """A data set's two files: ``<stem>.csv`` and ``<stem>.npz``."""
    return (
        ProcessFile(f"{stem}.csv", f"{title} (CSV)"),
        ProcessFile(f"{stem}.npz", f"{title} (NumPy arrays)"),
    )


#: A fan-out parent's children as it assembles them: how each ended, and its result.
ChildResults = Iterable[tuple[ChildEnd, Mapping[str, Any] | None]]
#: A child's artifact as its parent assembles it: (child job ID, name) -> its bytes, or
#: None if the child has no such file (one child's file at a time: a study streams them).
ChildFiles = Callable[[str, str], bytes | None]


@dataclass(frozen=True)
class PaperPoint:
    """A design a paper reports for this process (its optimum, typically), as input
    paths and values (``{"alpha1_deg": 60, "workspace.tilt_max_deg": 60}``): a design
    study marks it on its plots when the study contains it (its varied inputs are
    among these paths, within the study's bounds, and the other paths equal the
    study's inputs)."""

    label: str
    inputs: Mapping[str, Any]


@dataclass(frozen=True)
class FanOutSteps:
    """A process that fans out over the workers (``design-study``): its first attempt
    ``split``s the validated inputs into the inputs of ``child_process`` jobs, which run
    like any job; once they all ended, ``assemble`` builds the outcome from them in
    order, reading their files through a :data:`ChildFiles` (worker.store.fan_out).
    ``allow_partial``: whether a failed child is reported as missing instead of failing
    the parent."""

    child_process: str
    split: Callable[[Any], Sequence[Mapping[str, Any]]]
    assemble: Callable[[Any, ChildResults, ChildFiles, JobContext], JobOutcome]
    allow_partial: Callable[[Any], bool] = lambda inputs: False


@dataclass(frozen=True)
class ProcessDefinition:
    """One job kind.

    ``cost`` maps validated inputs to work units (grid points x orientation samples);
    a request whose cost exceeds ``cost_limit`` is refused before it is queued.
    """

    id: str
    title: str
    description: str
    inputs_model: type[BaseModel]
    run: Callable[[Any, JobContext], JobOutcome]
    examples: tuple[ProcessExample, ...]
    outputs: Mapping[str, str]
    cost: Callable[[Any], int]
    cost_limit: int
    cost_unit: str = "grid points x orientation samples"
    time_limit_s: float = 900.0
    version: str = "1.0.0"
    #: Requests costing at most this may be answered synchronously (``Prefer: wait=N``);
    #: 0: never.
    sync_cost_limit: int = 0
    #: The method page in ``docs/methods/<method_doc>.md`` that explains this process
    #: (equations, conventions, the paper's errata, citation); "" for none.
    method_doc: str = ""
    #: Every file a job of this process can write (a job need not write all of them:
    #: ``"plots": false`` writes no figures); checked against real runs by the tests.
    files: tuple[ProcessFile, ...] = ()
    #: A process that fans out its work as child jobs (``run`` then does the same work
    #: in one process, for tests and small requests); None for an ordinary process.
    fan_out: FanOutSteps | None = None
    #: Checks beyond the input model, made at submission (before anything is queued):
    #: field errors ``{"field", "message", "type"}`` for a 422; None: none.
    precheck: Callable[[Any], list[dict[str, Any]]] | None = None
    #: Designs the paper reports, which a design study over this process marks.
    paper_points: tuple[PaperPoint, ...] = ()
    #: Every numeric place of the result, with its unit, symbol and meaning
    #: (:mod:`worker.result_paths`); checked against the worked examples by the tests.
    result_paths: tuple[ResultPathInfo, ...] = ()
    #: The time limit of one attempt for these validated inputs (a job whose work
    #: grows with its inputs); capped at ``time_limit_s``, the limit the process
    #: publishes.  None: ``time_limit_s`` for every job.
    attempt_time_limit: Callable[[Any], float] | None = None
    #: The batched evaluation a design study uses for the result paths it covers
    #: (:mod:`worker.study_kernels`); None: studies of this process run per design.
    study_kernel: StudyKernel | None = None
    #: Measured seconds of one job per unit of ``cost`` (on the reference machine,
    #: plots off), and the seconds a job takes whatever its cost: a design study run per
    #: design cuts its designs into chunks of about a second by these, from its inputs
    #: alone, so that a re-run splits the same way (:mod:`worker.studies.chunking`).
    seconds_per_cost: float = 1e-6
    seconds_per_run: float = 1e-3
    #: Top-level inputs that change how the work is cut, never the result (a study's
    #: ``chunk_size``): left out of the result key, so a re-run differing only in them
    #: reuses the stored result (docs/reuse.md).
    unkeyed_inputs: tuple[str, ...] = ()
    #: The live explorer's evaluation (``POST /v1/processes/{id}/preview``,
    #: :mod:`worker.previews`); None: the process has no preview.
    preview: ProcessPreview | None = None
    #: The heat map a finished job's page draws from the job's CSV (plots stay).
    data_chart: DataChart | None = None

    def keyed_inputs(self, inputs: Mapping[str, Any]) -> dict[str, Any]:
        """The canonical inputs the result key is a digest of: ``inputs`` without
        :attr:`unkeyed_inputs`."""
        return {name: value for name, value in inputs.items() if name not in self.unkeyed_inputs}

    def time_limit_for(self, inputs: Any) -> float:
        """The time limit of one attempt of a job with these validated inputs."""
        if self.attempt_time_limit is None:
            return self.time_limit_s
        return min(self.time_limit_s, self.attempt_time_limit(inputs))

    @cached_property
    def inputs_schema(self) -> dict[str, Any]:
        """The inputs' JSON Schema (published, and checked at submission)."""
        return self.inputs_model.model_json_schema()

    def describe(self) -> dict[str, Any]:
        """The process description served at ``GET /v1/processes/{id}``: each result
        path a study kernel covers says ``"kernel": true``."""
        covered = set(self.study_kernel.covers) if self.study_kernel is not None else set()
        return {
            "id": self.id,
            "title": self.title,
            "description": self.description,
            "version": self.version,
            "jobControlOptions": (
                ["async-execute", "sync-execute", "dismiss"]
                if self.sync_cost_limit
                else ["async-execute", "dismiss"]
            ),
            "inputs": copy.deepcopy(self.inputs_schema),
            "outputs": dict(self.outputs),
            "result_paths": [
                entry.describe(kernel=entry.path in covered) for entry in self.result_paths
            ],
            "examples": [
                {"title": ex.title, "description": ex.description, "inputs": dict(ex.inputs)}
                for ex in self.examples
            ],
            "limits": {
                "cost_limit": self.cost_limit,
                "cost_unit": self.cost_unit,
                "time_limit_s": self.time_limit_s,
                "sync_cost_limit": self.sync_cost_limit,
            },
        }

    def summary(self) -> dict[str, Any]:
        """The short form listed at ``GET /v1/processes``."""
        return {
            "id": self.id,
            "title": self.title,
            "description": self.description,
            "version": self.version,
        }


@dataclass(frozen=True)
class FamilyInfo:
    """What a family of processes says of itself, for the API documents and the pages.

    ``name`` is its package under ``worker/families/`` (``"chains"``; the pages' anchor
    ``family-chains``); ``tag`` its title, the OpenAPI tag its execute operations are
    listed under and the heading of its processes on the pages; ``description`` the
    tag's description; ``paper`` the paper it reproduces, as the worked examples'
    summaries cite it (``"Bai 2010"``)."""

    name: str
    tag: str
    description: str
    paper: str


class FamilyPackage(Protocol):
    """A family's package as the registry reads it: who it is and its processes, in
    the order ``GET /v1/processes`` lists them."""

    @property
    def FAMILY(self) -> FamilyInfo: ...

    @property
    def PROCESSES(self) -> tuple[ProcessDefinition, ...]: ...


class ProcessRegistry:
    """Process definitions by ID, in the order they were registered, and the family of
    each: the processes of ``families`` first, then ``definitions``, processes of no
    family (``design-study``)."""

    def __init__(
        self,
        definitions: Iterable[ProcessDefinition] = (),
        *,
        families: Iterable[FamilyPackage] = (),
    ) -> None:
        packages = tuple(families)
        self._families = tuple(p.FAMILY for p in packages)
        self._family_of = {d.id: p.FAMILY for p in packages for d in p.PROCESSES}
        listed = (*(d for p in packages for d in p.PROCESSES), *definitions)
        self._by_id = {d.id: d for d in listed}
        if len(self._by_id) != len(listed):
            raise ValueError("process IDs must be unique")
        if len({f.name for f in self._families}) != len(self._families):
            raise ValueError("family names must be unique")

    def __iter__(self):  # type: ignore[no-untyped-def]
        return iter(self._by_id.values())

    def __contains__(self, process_id: object) -> bool:
        return process_id in self._by_id

    def get(self, process_id: str) -> ProcessDefinition | None:
        return self._by_id.get(process_id)

    def require(self, process_id: str) -> ProcessDefinition:
        """The definition of ``process_id``; :class:`NoSuchProcess` if there is none."""
        definition = self._by_id.get(process_id)
        if definition is None:
            raise NoSuchProcess.named(process_id, self.ids())
        return definition

    def ids(self) -> list[str]:
        return list(self._by_id)

    def families(self) -> tuple[FamilyInfo, ...]:
        """The families, in the order their processes are listed."""
        return self._families

    def family(self, process_id: str) -> FamilyInfo | None:
        """The family of a process; None for a process of no family (``design-study``)."""
        return self._family_of.get(process_id)
