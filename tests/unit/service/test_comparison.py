"""Jobs side by side: flattening to dotted places, rows that differ, deltas, plots."""

from __future__ import annotations

from datetime import UTC, datetime

from service.pages.comparison import comparison_context, flat_values
from worker.contract import ArtifactInfo, JobRecord, JobStatus

T0 = datetime(2026, 11, 28, 5, 0, tzinfo=UTC)


def test_flat_values_keeps_short_lists_whole_and_summarises_long_ones() -> None:
    value = {"grid": {"n": 3}, "links": [1.0, 2.0], "map": list(range(100)),
             "chains": [{"l": 1}, {"l": 2}]}  # fmt: skip
    assert flat_values(value) == {
        "grid.n": 3, "links": [1.0, 2.0], "map": "[100 items]",
        "chains[0].l": 1, "chains[1].l": 2,
    }  # fmt: skip


def job(job_id: str, inputs: dict[str, object], plots: tuple[str, ...] = ()) -> JobRecord:
    artifacts = tuple(ArtifactInfo(name=n, media_type="image/png", title=f"Plot {n}", size=1)
                      for n in plots)  # fmt: skip
    return JobRecord(
        job_id=job_id, process_id="p", status=JobStatus.SUCCESSFUL, inputs=inputs,
        created=T0, updated=T0, started=T0, finished=T0, artifacts=artifacts,
    )  # fmt: skip


def test_rows_mark_differences_with_deltas_from_the_first_job() -> None:
    jobs = [job("a" * 36, {"l": 1.0, "unit": "cm"}, ("m.png",)),
            job("b" * 36, {"l": 1.5, "unit": "cm"}, ("m.png", "n.png"))]  # fmt: skip
    context = comparison_context(jobs, [{"score": 2.0, "kind": "x"}, {"score": 2.5, "kind": "y"}])
    inputs = {r["place"]: r for r in context["inputs"]}
    assert inputs["l"]["differs"] and not inputs["unit"]["differs"]
    assert [c["delta"] for c in inputs["l"]["cells"]] == ["", "+0.5"]
    outputs = {r["place"]: r for r in context["outputs"]}
    assert [c["delta"] for c in outputs["score"]["cells"]] == ["", "+0.5"]
    assert outputs["kind"]["differs"] and [c["delta"] for c in outputs["kind"]["cells"]] == ["", ""]
    assert (context["input_differences"], context["output_differences"]) == (1, 2)
    plots = {p["title"]: p["images"] for p in context["plots"]}
    assert plots["Plot m.png"][0]["href"] == f"/v1/jobs/{'a' * 36}/results/m.png"
    assert plots["Plot n.png"][0] is None and plots["Plot n.png"][1] is not None
