"""Design studies on a real `dexlab serve`, embedded and Celery over Redis: the chunks run
as jobs on every worker, the parent holds no worker while they run (a pool of one
finishes), the assembled objectives are the single process's numbers, chunks are not
listed, and dismissing the study stops its chunks."""

from __future__ import annotations

import io
import os
import signal
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.integration.servers import deployment, wait_for, wait_terminal
from tests.integration.test_server import pid_of, wait_dead
from tests.unit.families.conftest import RecordingContext
from worker.registry import default_registry
from worker.studies.evaluation import design_inputs
from worker.studies.spec import StudySpec

pytestmark = pytest.mark.integration

URL = "/v1/processes/design-study/execution"
STUDY: dict[str, Any] = {
    "process": "planar3r-dexterity-map",
    "fixed": {"links": [15, 14, 8], "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
              "task_points": [[14, 14], [12, 8], [8, -8]], "grid": {"points_per_axis": 5}},
    "vary": {"links[0]": [10, 20, 5], "links[1]": [8, 18, 4]},
    "objectives": {"task_points[].d_z|min": "max", "links|sum": "min"},
    "chunk_size": 3,
    "plots": False,
}  # fmt: skip


def single_values(index: int) -> tuple[float, float]:
    """The planar3r-dexterity-map job's own numbers for design ``index``."""
    spec = StudySpec.model_validate(STUDY)
    values = tuple(float(v) for v in spec.designs.block(index, index + 1)[0])
    process = default_registry().get("planar3r-dexterity-map")
    assert process is not None
    inputs = process.inputs_model.model_validate({**design_inputs(spec, values), "plots": False})
    result = process.run(inputs, RecordingContext()).result
    return min(e["d_z"] for e in result["task_points"]), sum(result["links"])


@pytest.mark.parametrize(("backend", "workers"), [("embedded", 2), ("embedded", 1),
                                                  ("celery-redis", 2)])  # fmt: skip
def test_a_study_fans_out_and_assembles_the_single_process_numbers(
    backend: str, workers: int, tmp_path: Path
) -> None:
    with deployment(backend, tmp_path, workers=workers) as dep:
        client = dep.client
        submitted = client.post(URL, json={"inputs": STUDY})
        assert submitted.status_code == 201, submitted.text
        study_id = submitted.json()["jobID"]
        done = wait_terminal(client, study_id, timeout=180)
        assert done["status"] == "successful", done
        result = client.get(f"/v1/jobs/{study_id}/results").json()["result"]
        assert (result["count"], result["evaluated"], result["chunks"]) == (20, 20, 7)
        rows = {p["index"]: p for p in result["pareto"]}
        for index in (0, 7, 19):
            minimum, total = single_values(index)
            best = [e for entries in result["best"].values() for e in entries]
            entry = rows.get(index) or next((e for e in best if e["index"] == index), None)
            if entry is not None:
                assert entry["objectives"] == {"task_points[].d_z|min": minimum, "links|sum": total}
        csv = client.get(f"/v1/jobs/{study_id}/results/designs.csv").text.splitlines()
        assert len(csv) == 21
        for index in (0, 7, 19):
            minimum, total = single_values(index)
            fields = csv[index + 1].split(",")
            assert float(fields[3]) == pytest.approx(minimum, rel=1e-11)
            assert float(fields[4]) == total
        listed = [j["jobID"] for j in client.get("/v1/jobs", params={"limit": 100}).json()["jobs"]]
        assert listed == [study_id]  # the chunks are not listed


def test_a_bad_objective_is_refused_and_dismissing_a_study_stops_its_chunks(
    tmp_path: Path,
) -> None:
    slow = {**STUDY, "fixed": {**STUDY["fixed"], "grid": {"points_per_axis": 301},
                               "method": "orientation-sampling", "orientation_step_deg": 0.5},
            "engine": "per-design", "chunk_size": 1}  # fmt: skip
    with deployment("embedded", tmp_path, workers=1) as dep:
        client = dep.client
        typo = {**STUDY, "objectives": {"task_point[].d_z|min": "max"}}
        refused = client.post(URL, json={"inputs": typo})
        assert refused.status_code == 422, refused.text
        fields = [e["field"] for e in refused.json()["errors"]]
        assert fields == ["inputs.objectives.task_point[].d_z|min"]
        study_id = client.post(URL, json={"inputs": slow}).json()["jobID"]
        wait_for(client, study_id, lambda d: "chunks" in d.get("message", ""), timeout=60)
        assert client.delete(f"/v1/jobs/{study_id}").json()["status"] == "dismissed"
        time.sleep(1.0)
        status = client.get(f"/v1/jobs/{study_id}").json()
        assert status["status"] == "dismissed"
        # nothing is left running: a new small job runs at once on the only worker
        small = {"inputs": {"lengths": [2, 7, 9, 6], "ground": 1}}
        quick = client.post("/v1/processes/fourbar-grashof/execution", json=small).json()
        assert wait_terminal(client, quick["jobID"], timeout=30)["status"] == "successful"


@pytest.mark.parametrize("backend", ["embedded", "celery-redis"])
def test_a_killed_chunk_is_retried_and_no_design_is_counted_twice(
    backend: str, tmp_path: Path
) -> None:
    slow = {**STUDY, "fixed": {**STUDY["fixed"], "grid": {"points_per_axis": 201},
                               "method": "orientation-sampling", "orientation_step_deg": 1},
            "engine": "per-design", "chunk_size": 4}  # fmt: skip
    with deployment(backend, tmp_path, workers=2) as dep:
        client = dep.client
        study_id = client.post(URL, json={"inputs": slow}).json()["jobID"]

        def running_chunk() -> dict[str, Any] | None:
            page = client.get("/v1/jobs", params={"parent": study_id, "status": "running"})
            jobs = page.json()["jobs"]
            return next((j for j in jobs if j.get("worker_id")), None)

        deadline = time.monotonic() + 60
        chunk = running_chunk()
        while chunk is None and time.monotonic() < deadline:
            time.sleep(0.1)
            chunk = running_chunk()
        assert chunk is not None and chunk["parentID"] == study_id
        victim = pid_of(chunk)
        os.kill(victim, signal.SIGKILL)
        wait_dead(victim)
        done = wait_terminal(client, study_id, timeout=300)
        assert done["status"] == "successful", (done, dep.log())
        assert done["chunks"] == {"total": 5, "ended": 5, "failed": 0}
        retried = client.get(f"/v1/jobs/{chunk['jobID']}").json()
        assert retried["status"] == "successful" and retried["attempts"] == 2
        result = client.get(f"/v1/jobs/{study_id}/results").json()["result"]
        assert (result["count"], result["evaluated"], result["missing"]) == (20, 20, 0)
        csv = client.get(f"/v1/jobs/{study_id}/results/designs.csv").text.splitlines()
        assert [int(line.split(",")[0]) for line in csv[1:]] == list(range(20))


SPM_STUDY: dict[str, Any] = {
    "process": "spm-conditioning-map",
    "fixed": {"beta_deg": 90, "gamma_deg": 0,
              "workspace": {"tilt_max_deg": 60, "torsion_deg": [0, 360]}},
    "sample": {"method": "sobol", "count": 35, "seed": 4,
               "bounds": {"alpha1_deg": [30, 150], "alpha2_deg": [40, 140]}},
    "objectives": {"indices.rms_inverse_condition": "max", "indices.min_inverse_condition": "max"},
    "plots": False,
}  # fmt: skip


def designs_arrays(client: Any, study_id: str) -> dict[str, np.ndarray]:
    data = client.get(f"/v1/jobs/{study_id}/results/designs.npz").content
    with np.load(io.BytesIO(data)) as npz:
        return {name: npz[name] for name in ("objectives", "reason_code", "reason_field",
                                             "reason_fields", "index")}  # fmt: skip


@pytest.mark.parametrize("backend", ["embedded", "celery-redis"])
def test_a_batched_study_assembles_the_per_design_numbers(backend: str, tmp_path: Path) -> None:
    """The same SPM study (a Sobol sample of designs) through its kernel and per design
    (``engine: per-design``), on the embedded backend and on Celery + Redis with
    PostgreSQL: the same feasible
    designs, objectives equal to 1e-12, the same reason codes and fields but for the
    kernel's one shortcut (a design the process refuses for reaching none of the cone
    has no C_n either: 'no-value' there)."""
    with deployment(backend, tmp_path, workers=2) as dep:
        client = dep.client
        arrays = {}
        for engine in ("auto", "per-design"):
            submitted = client.post(URL, json={"inputs": {**SPM_STUDY, "engine": engine}})
            assert submitted.status_code == 201, submitted.text
            study_id = submitted.json()["jobID"]
            done = wait_terminal(client, study_id, timeout=300)
            assert done["status"] == "successful", (done, dep.log())
            result = client.get(f"/v1/jobs/{study_id}/results").json()["result"]
            assert result["engine"] == ("batched" if engine == "auto" else "per-design")
            assert result["count"] == result["evaluated"] == 35
            arrays[engine] = designs_arrays(client, study_id)
        fast, slow = arrays["auto"], arrays["per-design"]
        feasible = fast["reason_code"] == 0
        np.testing.assert_array_equal(feasible, slow["reason_code"] == 0)
        assert 0 < feasible.sum() < 35
        np.testing.assert_allclose(fast["objectives"][feasible], slow["objectives"][feasible],
                                   rtol=1e-12, atol=0)  # fmt: skip
        fields = (fast["reason_fields"][fast["reason_field"]],
                  slow["reason_fields"][slow["reason_field"]])  # fmt: skip
        shortcut = (slow["reason_code"] == 1) & (fields[1] == "inputs.workspace")
        assert (fast["reason_code"][shortcut] == 2).all()
        np.testing.assert_array_equal(fast["reason_code"][~shortcut],
                                      slow["reason_code"][~shortcut])  # fmt: skip
        np.testing.assert_array_equal(fields[0][~shortcut], fields[1][~shortcut])
