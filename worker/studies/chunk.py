"""``design-study-chunk``: one block of a study's designs, evaluated on one worker.

A study's first attempt splits its designs into chunks (:mod:`.process`); each chunk is
a job of this process, stored and dispatched like any job, that rebuilds its block of
designs from the study's inputs and evaluates them (:mod:`.evaluation`).  It is run by
the workers only: the service does not list it or accept it.
"""

from __future__ import annotations

from typing import Any

from pydantic import Field, model_validator

from worker.common.specs import FrozenSpec
from worker.contract import JobContext, JobOutcome
from worker.processes import ProcessDefinition
from worker.studies.spec import MAX_CHUNK, StudySpec

__all__ = ["CHUNK", "ChunkSpec", "run_chunk"]

#: Wall-clock limit of one chunk attempt (a chunk is about a second of work).
CHUNK_TIME_LIMIT_S = 1800.0


class ChunkSpec(FrozenSpec):
    """A study and the designs ``start`` to ``stop`` (exclusive) of it."""

    study: StudySpec
    start: int = Field(..., ge=0)
    stop: int = Field(..., ge=1)

    @model_validator(mode="after")
    def _inside(self) -> ChunkSpec:
        count = self.study.designs.count
        if not self.start < self.stop <= count or self.stop - self.start > MAX_CHUNK:
            raise ValueError(f"designs [{self.start}, {self.stop}) are not a chunk of {count}")
        return self


def run_chunk(spec: ChunkSpec, ctx: JobContext) -> JobOutcome:
    from worker.processes import default_registry
    from worker.studies.evaluation import evaluate_block

    process = default_registry().get(spec.study.process)
    assert process is not None  # the study's validator checked it
    total = spec.stop - spec.start

    def progress(done: int, _: int) -> None:
        ctx.report_progress(100.0 * done / total, f"design {done} of {total}")

    rows = evaluate_block(spec.study, process, spec.start, spec.stop, progress)
    result: dict[str, Any] = {
        "start": spec.start,
        "stop": spec.stop,
        "rows": [row.as_json() for row in rows],
    }
    return JobOutcome(result=result)


CHUNK = ProcessDefinition(
    id="design-study-chunk",
    title="A chunk of a design study",
    description="Evaluates designs start..stop of a design study (run by the workers).",
    inputs_model=ChunkSpec,
    run=run_chunk,
    examples=(),
    outputs={
        "start": "First design of the chunk.",
        "stop": "One past its last design.",
        "rows": "Per design: index, parameters, objectives, reason (null when feasible).",
    },
    cost=lambda spec: spec.stop - spec.start,
    cost_limit=MAX_CHUNK,
    cost_unit="designs",
    time_limit_s=CHUNK_TIME_LIMIT_S,
)
