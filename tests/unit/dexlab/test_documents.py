"""Reading what the service sends: NPZ and CSV files, examples, events, status."""

from __future__ import annotations

import io

import numpy as np
import pytest

from dexlab.documents import JobStatus, example_inputs, read_csv, read_npz, safe_file_name
from dexlab.events import EventStreamParser, progress_of


def npz(**arrays: object) -> bytes:
    buffer = io.BytesIO()
    np.savez(buffer, **arrays)  # type: ignore[arg-type]
    return buffer.getvalue()


def test_npz_arrays_are_read_by_name() -> None:
    x, grid = np.linspace(0, 1, 3), np.arange(6.0).reshape(2, 3)
    arrays = read_npz(npz(x=x, d_z=grid))
    assert set(arrays) == {"x", "d_z"}
    np.testing.assert_array_equal(arrays["d_z"], grid)


def test_an_npz_holding_python_objects_is_refused_not_unpickled() -> None:
    with pytest.raises(ValueError, match="not an NPZ file of plain arrays"):
        read_npz(npz(evil=np.array([{"a": 1}], dtype=object)), "evil.npz")
    with pytest.raises(ValueError, match=r"heatmap\.png is not an NPZ"):
        read_npz(b"\x89PNG not a zip", "heatmap.png")


def test_csv_rows_read_numbers_as_numbers() -> None:
    rows = read_csv("x,reachable,label,d\n0.5,1,inside,nan\n-2,0,,\n")
    assert rows[0] == {"x": 0.5, "reachable": 1, "label": "inside", "d": rows[0]["d"]}
    assert isinstance(rows[0]["d"], float) and rows[0]["d"] != rows[0]["d"]  # nan
    assert rows[1] == {"x": -2, "reachable": 0, "label": "", "d": ""}


def test_examples_count_from_zero_and_a_bad_number_is_named() -> None:
    described = {"examples": [{"inputs": {"a": 1}}, {"inputs": {"a": 2}}]}
    assert example_inputs("p", described, 1) == {"a": 2}
    with pytest.raises(ValueError, match=r"'example' parameter of p .* \(0 to 1\). Got 2"):
        example_inputs("p", described, 2)
    with pytest.raises(TypeError, match="must be an int"):
        example_inputs("p", described, True)


@pytest.mark.parametrize("name", ["../x.png", "a/b.csv", ".hidden", "", "..", "c:\\x"])
def test_artifact_names_that_could_leave_the_folder_are_refused(name: str) -> None:
    with pytest.raises(ValueError, match="not a plain file name"):
        safe_file_name(name)


def test_event_stream_lines_become_progress_events() -> None:
    parser = EventStreamParser()
    lines = ["retry: 2000", "", ": still running", "event: progress",
             'data: {"status": "running", "progress": 40, "message": "map"}', "",
             "data: plain", ""]  # fmt: skip
    events = [e for e in (parser.feed(line) for line in lines) if e is not None]
    assert [e.event for e in events] == ["progress", "message"]
    assert progress_of(events[0]) == {"status": "running", "progress": 40, "message": "map"}
    assert progress_of(events[1]) is None


def test_a_progress_event_updates_the_status_and_clears_a_stale_error() -> None:
    before = JobStatus.from_document(
        {"jobID": "j", "processID": "p", "status": "running", "progress": 10, "message": "a",
         "attempts": 1, "error": {"type": "x"}}
    )  # fmt: skip
    after = before.with_event({"status": "successful", "progress": 100, "message": "done"})
    assert (after.status, after.progress, after.message, after.error) == (
        "successful", 100, "done", None,
    )  # fmt: skip
    assert after.done and not before.done and after.document["attempts"] == 1
