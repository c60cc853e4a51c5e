"""The process registry: every job kind the service offers, with its contract.

A process definition ties together the validated input model (pydantic, frozen,
``extra="forbid"``), the function that runs it, the paper's worked examples, a
description of its outputs, and its cost limit (checked before anything is queued).
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from pydantic import BaseModel

from worker.contract import ChildEnd, JobContext, JobOutcome
from worker.result_paths import ResultPathInfo
from worker.study_kernels import StudyKernel

__all__ = [
    "ChildFiles",
    "ChildResults",
    "FanOutSteps",
    "PaperPoint",
    "ProcessDefinition",
    "ProcessExample",
    "ProcessFile",
    "ProcessRegistry",
    "ResultPathInfo",
    "StudyKernel",
    "data_files",
    "default_registry",
    "figure_files",
    "worker_registry",
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


class ProcessRegistry:
    """Process definitions by ID, in the order they were registered."""

    def __init__(self, definitions: tuple[ProcessDefinition, ...]) -> None:
        self._by_id = {d.id: d for d in definitions}
        if len(self._by_id) != len(definitions):
            raise ValueError("process IDs must be unique")

    def __iter__(self):  # type: ignore[no-untyped-def]
        return iter(self._by_id.values())

    def __contains__(self, process_id: object) -> bool:
        return process_id in self._by_id

    def get(self, process_id: str) -> ProcessDefinition | None:
        return self._by_id.get(process_id)

    def ids(self) -> list[str]:
        return list(self._by_id)


def default_registry() -> ProcessRegistry:
    """Every process dexlab ships, built on demand (no import-time work).

    The families, in the order ``GET /v1/processes`` lists their processes: a new family
    is a folder under ``worker/families/`` and one entry here (the architecture test
    checks that every folder is listed).
    """
    from worker.families import chains, planar_parallel, planar_serial, spherical_parallel
    from worker.studies.process import STUDY

    families = (planar_serial, planar_parallel, chains, spherical_parallel)
    return ProcessRegistry((*(d for family in families for d in family.PROCESSES), STUDY))


def worker_registry() -> ProcessRegistry:
    """What the workers run: every public process and the jobs processes make for
    themselves (a study's chunks), which the service neither lists nor accepts."""
    from worker.studies.chunk import CHUNK

    return ProcessRegistry((*default_registry(), CHUNK))


def preload_job_modules() -> list[str]:
    """Import every module a job imports when it runs (each family's ``jobs`` package
    with its figures, hence matplotlib; the design studies); the names, in order.

    Processes import their jobs' modules on first use, so the API stays light.  A
    prefork worker (``dexlab worker`` on Celery) calls this before it forks, so that each
    pool process, and each one started in place of a process that stopped, has them
    already (shared copy-on-write) instead of its first job paying the imports (about
    0.3 s for ``fourbar-grashof``, longer than a thousand such jobs take to run)."""
    import importlib
    import pkgutil

    import worker.families as families
    import worker.studies as studies

    worker_registry()  # the families' own modules (specs, costs, examples)
    packages = [
        f"{m.name}.jobs" for m in pkgutil.iter_modules(families.__path__, "worker.families.")
    ]
    names: list[str] = []
    for package in (*packages, studies.__name__):
        module = importlib.import_module(package)
        names.append(package)
        names += [m.name for m in pkgutil.iter_modules(module.__path__, f"{package}.")]
    for name in names:
        importlib.import_module(name)
    return names
