"""A chunk's rows as stored (rows.npz and its result) and read back, the reasons'
messages counted within bounds, and a whole study assembled a chunk at a time."""

from __future__ import annotations

import numpy as np

from tests.unit.families.conftest import RecordingContext
from tests.unit.worker.studies.registry import chunk_inputs, run_chunk
from worker.contract import ChildEnd, JobStatus
from worker.studies.assembly import collect
from worker.studies.chunk import ChunkSpec
from worker.studies.examples import STUDY_EXAMPLES
from worker.studies.rows import (
    MAX_MESSAGES,
    NO_VALUE,
    OTHER_MESSAGES,
    REFUSED,
    ROWS_FILE,
    ChunkRows,
    ReasonTally,
)
from worker.studies.spec import StudySpec


def test_messages_are_counted_within_bounds() -> None:
    tally = ReasonTally()
    for n in range(500):
        tally.add(REFUSED, "inputs.workspace", f"design {n} reaches nothing", 1 + (n == 7))
    tally.add(NO_VALUE, "", "no value for indices.gci", 40)
    assert len(tally.counts) <= 2 * MAX_MESSAGES
    assert sum(tally.counts.values()) == 541
    first, second = tally.most_common(2)
    assert (first["reason_code"], first["reason_field"], first["reason"]) == (
        "refused", "inputs.workspace", OTHER_MESSAGES)  # fmt: skip
    assert second == {"reason_code": "no-value", "reason_field": "", "designs": 40,
                      "reason": "no value for indices.gci"}  # fmt: skip
    again = ReasonTally.from_json(tally.as_json())
    assert again.counts == tally.counts


def test_a_chunk_stores_arrays_and_reads_back() -> None:
    inputs = {**dict(STUDY_EXAMPLES[0].inputs), "plots": False}
    spec = StudySpec.model_validate(inputs)
    chunk = ChunkSpec.model_validate(chunk_inputs(spec)[0])
    outcome = run_chunk(chunk, RecordingContext())
    assert [a.name for a in outcome.artifacts] == [ROWS_FILE]
    assert "rows" in outcome.result and isinstance(outcome.result["rows"], str)
    rows = ChunkRows.stored(outcome.result, outcome.artifacts[0].data, 2)
    assert (rows.start, rows.stop, rows.engine) == (chunk.start, chunk.stop, "batched")
    assert rows.objectives.shape == (chunk.stop - chunk.start, 2)
    assert rows.codes.dtype == np.int8 and rows.fields.dtype == np.int16


def test_an_older_chunk_result_with_listed_rows_is_read() -> None:
    older = {"start": 0, "stop": 2, "rows": [
        {"index": 0, "parameters": [1.0], "objectives": [0.5], "reason": None},
        {"index": 1, "parameters": [2.0], "objectives": [None], "reason": "no value for x"},
    ]}  # fmt: skip
    rows = ChunkRows.stored(older, None, 1)
    assert rows.codes.tolist() == [0, NO_VALUE]
    assert rows.objectives[0, 0] == 0.5 and np.isnan(rows.objectives[1, 0])


def test_the_assembly_reads_one_chunk_at_a_time_and_counts_missing_ones() -> None:
    inputs = {**dict(STUDY_EXAMPLES[0].inputs), "plots": False, "chunk_size": 50}
    spec = StudySpec.model_validate(inputs)
    outcomes = [run_chunk(ChunkSpec.model_validate(c), RecordingContext())
                for c in chunk_inputs(spec)]  # fmt: skip
    asked: list[str] = []

    def files(job_id: str, name: str) -> bytes | None:
        asked.append(job_id)
        return outcomes[int(job_id)].artifacts[0].data

    def children():  # type: ignore[no-untyped-def]
        for n, outcome in enumerate(outcomes):
            failed = n == 1
            status = JobStatus.FAILED if failed else JobStatus.SUCCESSFUL
            yield ChildEnd(str(n), status, None), None if failed else outcome.result

    table = collect(spec, children(), files)
    assert asked == ["0", "2", "3"]
    assert table.missing_chunks == ["1"]
    assert table.index.tolist() == [*range(50), *range(100, 169)]
    np.testing.assert_array_equal(table.parameters[:, 0], spec.designs.block(0, 169)[
        table.index, 0])  # fmt: skip
