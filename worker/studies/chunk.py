"""``design-study-chunk``: one block of a study's designs, evaluated on one worker.

A study's first attempt splits its designs into chunks (:mod:`.chunking`); each chunk is
a job of this process, stored and dispatched like any job, that rebuilds its block of
designs from the study's inputs and evaluates them with the study's engine (the
process's kernel, :mod:`.batched`, or the process per design, :mod:`.evaluation`).
Its rows are written as it finishes, as arrays (``rows.npz``, :mod:`.rows`), which the
assembly reads a chunk at a time.  It is run by the workers only: the service does not
list it or accept it.  The chunks of the studies of a registry's processes are one
process of that registry (:func:`study_chunk`), built with it.
"""

from __future__ import annotations

from functools import partial
from typing import Literal

from pydantic import Field, model_validator

from worker.common.specs import FrozenSpec
from worker.contract import Artifact, JobContext, JobOutcome
from worker.processes import ProcessDefinition, ProcessFile, ProcessRegistry
from worker.studies.batched import evaluate_batched
from worker.studies.engine import choose_engine
from worker.studies.evaluation import chunk_rows, evaluate_block
from worker.studies.rows import ROWS_FILE, ChunkRows
from worker.studies.spec import MAX_CHUNK, StudySpec

__all__ = ["ChunkSpec", "run_chunk", "study_chunk", "target_of"]

#: Wall-clock limit of one chunk attempt (a chunk is about a second of work).
CHUNK_TIME_LIMIT_S = 1800.0


class ChunkSpec(FrozenSpec):
    """A study and the designs ``start`` to ``stop`` (exclusive) of it."""

    study: StudySpec
    start: int = Field(..., ge=0)
    stop: int = Field(..., ge=1)
    engine: Literal["batched", "per-design"] = Field(
        "per-design", description="The engine the study chose for its designs."
    )

    @model_validator(mode="after")
    def _inside(self) -> ChunkSpec:
        count = self.study.designs.count
        if not self.start < self.stop <= count or self.stop - self.start > MAX_CHUNK:
            raise ValueError(f"designs [{self.start}, {self.stop}) are not a chunk of {count}")
        return self


def target_of(studied: ProcessRegistry, spec: StudySpec) -> ProcessDefinition:
    """The process a study evaluates, among those a registry's studies may run."""
    process = studied.get(spec.process)
    if process is None:  # the study's validator checked it when it was submitted
        raise ValueError(f"{spec.process!r} is not a process a study can run here")
    return process


def evaluate_chunk(spec: ChunkSpec, process: ProcessDefinition, ctx: JobContext) -> ChunkRows:
    """The chunk's rows for its study of ``process``, with the study's engine (per
    design should the kernel be unavailable here: the same numbers, more slowly)."""
    total = spec.stop - spec.start

    def progress(done: int, _: int) -> None:
        ctx.report_progress(100.0 * done / total, f"design {done} of {total}")

    if spec.engine == "batched":
        choice = choose_engine(spec.study, process)
        if choice.engine == "batched":
            return evaluate_batched(spec.study, process, choice, spec.start, spec.stop, progress)
    rows = evaluate_block(spec.study, process, spec.start, spec.stop, progress)
    return chunk_rows(rows, spec.start, spec.stop, len(spec.study.objectives))


def run_chunk(studied: ProcessRegistry, spec: ChunkSpec, ctx: JobContext) -> JobOutcome:
    """A chunk of a study of one of ``studied``'s processes: its rows as an artifact."""
    rows = evaluate_chunk(spec, target_of(studied, spec.study), ctx)
    data = Artifact(ROWS_FILE, "application/x-npz", rows.artifact_bytes(), _ROWS_TITLE)
    return JobOutcome(result=rows.result(), artifacts=(data,))


_ROWS_TITLE = "The chunk's designs: objectives, reason codes and fields (NumPy arrays)"


def study_chunk(studied: ProcessRegistry) -> ProcessDefinition:
    """``design-study-chunk`` for the studies of ``studied``'s processes."""
    return ProcessDefinition(
        id="design-study-chunk",
        title="A chunk of a design study",
        description="Evaluates designs start..stop of a design study (run by the workers).",
        inputs_model=ChunkSpec,
        run=partial(run_chunk, studied),
        examples=(),
        files=(ProcessFile(ROWS_FILE, _ROWS_TITLE),),
        outputs={
            "start": "First design of the chunk.",
            "stop": "One past its last design.",
            "engine": "The engine that evaluated its designs: 'batched' or 'per-design'.",
            "rows": f"The artifact holding its designs' arrays ({ROWS_FILE}).",
            "fields": "The fields its refusals name (reason_field indexes them).",
            "reasons": "[code, field, message, designs] for each distinct reason.",
        },
        version="2.0.0",
        cost=lambda spec: spec.stop - spec.start,
        cost_limit=MAX_CHUNK,
        cost_unit="designs",
        time_limit_s=CHUNK_TIME_LIMIT_S,
    )
