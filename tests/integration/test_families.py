"""Every process's worked examples run through a real `dexlab serve` to success, with
their plots downloadable, and quick processes answer synchronously."""

from __future__ import annotations

import time
from collections.abc import Iterator
from typing import Any

import httpx
import pytest

from tests.integration.servers import Deployment, deployment, wait_for, wait_terminal
from worker.registry import default_registry

pytestmark = pytest.mark.integration

#: Examples above this cost (planar3r-design's three largest, 15-25 s of CPU each) are
#: accepted by the real service and then dismissed here; they run to success, figures
#: checked, in process in tests/unit/families/test_figures.py.
RUN_COST_MAX = 50_000_000


def _runs_here(process_id: str, index: int) -> bool:
    definition = default_registry().get(process_id)
    assert definition is not None
    example = definition.examples[index]
    return definition.cost(definition.inputs_model.model_validate(example.inputs)) <= RUN_COST_MAX


EXAMPLES = [
    pytest.param(d.id, i, id=f"{d.id}-{i}")
    for d in default_registry()
    for i in range(len(d.examples))
]


@pytest.fixture(scope="module")
def embedded(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Deployment]:
    with deployment("embedded", tmp_path_factory.mktemp("families"), workers=2) as dep:
        yield dep


def check_artifacts(client: httpx.Client, results: dict[str, Any]) -> None:
    media = {a["media_type"] for a in results["artifacts"]}
    assert "image/png" in media and "image/svg+xml" in media, media
    for artifact in results["artifacts"]:
        body = client.get(artifact["href"])
        assert body.status_code == 200, artifact
        assert body.headers["content-type"].startswith(artifact["media_type"])
        if artifact["media_type"] == "image/png":
            assert body.content.startswith(b"\x89PNG")


@pytest.mark.parametrize(("process_id", "index"), EXAMPLES)
def test_worked_example_runs_to_success(embedded: Deployment, process_id: str, index: int) -> None:
    client = embedded.client
    example = client.get(f"/v1/processes/{process_id}").json()["examples"][index]
    r = client.post(f"/v1/processes/{process_id}/execution", json={"inputs": example["inputs"]})
    assert r.status_code == 201, r.text
    job_id = r.json()["jobID"]
    if not _runs_here(process_id, index):
        assert client.delete(f"/v1/jobs/{job_id}").status_code == 200
        assert wait_terminal(client, job_id)["status"] == "dismissed"
        return
    status = wait_for(
        client, job_id, lambda d: d["status"] in {"successful", "failed"}, timeout=300
    )
    assert status["status"] == "successful", status
    results = client.get(f"/v1/jobs/{job_id}/results").json()
    assert results["result"], results
    notes, errata = results["result"]["notes"], results["result"]["paper_errata"]
    assert isinstance(notes, list) and isinstance(errata, list)
    assert notes[len(notes) - len(errata) :] == errata  # the paper's errata come last
    check_artifacts(client, results)


SYNC_PROCESSES = [d.id for d in default_registry() if d.sync_cost_limit]


@pytest.mark.parametrize("process_id", SYNC_PROCESSES)
def test_quick_processes_answer_synchronously(embedded: Deployment, process_id: str) -> None:
    client = embedded.client
    doc = client.get(f"/v1/processes/{process_id}").json()
    assert "sync-execute" in doc["jobControlOptions"]
    definition = default_registry().get(process_id)
    assert definition is not None
    cheap = [
        ex
        for ex in definition.examples
        if definition.cost(definition.inputs_model.model_validate(ex.inputs))
        <= definition.sync_cost_limit
    ]
    if not cheap:
        pytest.fail(f"{process_id} allows synchronous execution but no example fits it")
    inputs = (
        {**cheap[0].inputs, "plots": False}
        if "plots" in doc["inputs"]["properties"]
        else cheap[0].inputs
    )
    r = client.post(
        f"/v1/processes/{process_id}/execution",
        json={"inputs": inputs},
        headers={"Prefer": "wait=60"},
    )
    assert r.status_code == 200, r.text
    assert r.headers["Preference-Applied"] == "wait=60"
    body = r.json()
    assert body["processID"] == process_id and body["result"]
    assert wait_terminal(client, body["jobID"])["status"] == "successful"


def test_progress_advances_during_an_spm_optimisation(embedded: Deployment) -> None:
    """Poll a running optimisation: its progress rises through intermediate values (one
    step per finished start) before the job succeeds."""
    client = embedded.client
    inputs = {
        "workspace": {"tilt_max_deg": 60.0, "torsion_deg": [0.0, 360.0],
                      "samples": {"azimuth": 8, "tilt": 24, "torsion": 6}},
        "gamma_deg": 0.0,
        "starts": 32,
        "seed": 7,
        "plots": False,
    }  # fmt: skip
    r = client.post("/v1/processes/spm-optimisation/execution", json={"inputs": inputs})
    assert r.status_code == 201, r.text
    job_id = r.json()["jobID"]
    seen: list[float] = []
    deadline = time.monotonic() + 300
    status: dict[str, Any] = {}
    while time.monotonic() < deadline:
        status = client.get(f"/v1/jobs/{job_id}").json()
        if status["status"] == "running":
            seen.append(status["progress"])
        if status["status"] in {"successful", "failed", "dismissed"}:
            break
        time.sleep(0.05)
    assert status["status"] == "successful", status
    assert seen == sorted(seen), seen
    intermediate = {p for p in seen if 0.0 < p < 100.0}
    assert len(intermediate) >= 3, seen
    result = client.get(f"/v1/jobs/{job_id}/results").json()["result"]
    assert len(result["starts"]) == 32
