"""The design study as the registry builds it, and its steps as the tests call them
(the study runs the processes of the registry it is built with)."""

from __future__ import annotations

from typing import Any

from worker.contract import JobContext, JobOutcome
from worker.processes import ProcessDefinition
from worker.registry import worker_registry
from worker.studies.chunk import ChunkSpec
from worker.studies.spec import StudySpec


def _process(process_id: str) -> ProcessDefinition:
    process = worker_registry().get(process_id)
    assert process is not None
    return process


STUDY = _process("design-study")
CHUNK = _process("design-study-chunk")
#: The study's inputs model, which checks ``process`` against the registry.
STUDY_INPUTS = STUDY.inputs_model


def dry_check(spec: StudySpec) -> list[dict[str, Any]]:
    assert STUDY.precheck is not None
    return STUDY.precheck(spec)


def study_cost(spec: StudySpec) -> int:
    return STUDY.cost(spec)


def chunk_inputs(spec: StudySpec) -> list[dict[str, Any]]:
    assert STUDY.fan_out is not None
    return list(STUDY.fan_out.split(spec))


def run_chunk(spec: ChunkSpec, ctx: JobContext) -> JobOutcome:
    return CHUNK.run(spec, ctx)
