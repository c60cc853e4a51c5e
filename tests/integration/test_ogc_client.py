"""An OGC API - Processes client from PyPI (OWSLib) against the real server's /ogc/,
on the embedded backend and on PostgreSQL + Celery over Redis.

OWSLib 0.35's ``Processes`` lists, describes and executes processes; it has no call
for a job's status, results or dismissal, so those go through its own request
machinery (``Processes._request``, the method its public calls use), unchanged.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from typing import Any

import pytest
from owslib.ogcapi.processes import Processes

from tests.integration.servers import Deployment, deployment

pytestmark = pytest.mark.integration

FOURBAR = {"lengths": [2, 7, 9, 6], "ground": 1}


@pytest.fixture(scope="module", params=("embedded", "celery-redis"))
def server(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Deployment]:
    """A deployment per backend (two of the three: the client does not depend on the
    broker, and the suite stays quick)."""
    with deployment(str(request.param), tmp_path_factory.mktemp("ogc-client")) as dep:
        yield dep


@pytest.fixture
def client(server: Deployment) -> Iterator[Processes]:
    processes = Processes(f"{server.base_url}/ogc/")
    headers = dict(processes.headers)
    yield processes
    # OWSLib keeps its request headers (and the Prefer it sets) in one shared dict.
    processes.headers.clear()
    processes.headers.update({k: v for k, v in headers.items() if k != "Prefer"})


def monitor(client: Processes, job_id: str, timeout: float = 120) -> dict[str, Any]:
    deadline = time.monotonic() + timeout
    while True:
        status: dict[str, Any] = client._request(path=f"jobs/{job_id}")
        if status["status"] in {"successful", "failed", "dismissed"}:
            return status
        assert time.monotonic() < deadline, status
        time.sleep(0.2)


def test_discover(client: Processes, server: Deployment) -> None:
    assert any(
        link["rel"] == "http://www.opengis.net/def/rel/ogc/1.0/processes" for link in client.links
    )
    conformance = client.conformance()["conformsTo"]
    assert "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/core" in conformance
    ids = [p["id"] for p in client.processes()]
    assert {"fourbar-grashof", "planar3r-dexterity-map", "spm-optimisation"} <= set(ids)
    description = client.process("fourbar-grashof")
    assert description["inputs"]["lengths"]["minOccurs"] == 1
    assert "sync-execute" in description["jobControlOptions"]
    execute = next(link for link in description["links"] if link["rel"].endswith("/execute"))
    assert execute["href"] == f"{server.base_url}/ogc/processes/fourbar-grashof/execution"


def test_execute_async_monitor_results_dismiss(client: Processes, server: Deployment) -> None:
    status = client.execute("fourbar-grashof", inputs=FOURBAR, async_=True)
    assert status["status"] in {"accepted", "running", "successful"}
    location = client.response_headers["Location"]
    assert location == f"{server.base_url}/ogc/jobs/{status['jobID']}"
    assert client.response_headers["Preference-Applied"] == "respond-async"
    done = monitor(client, status["jobID"])
    assert done["status"] == "successful" and done["progress"] == 100
    results = client._request(path=f"jobs/{status['jobID']}/results")
    assert results["grashof"] == "grashof" and results["classification"] == "crank-rocker"
    png = results["fourbar_motion.png"]
    assert png["type"] == "image/png" and png["href"].startswith(server.base_url)
    assert server.client.get(png["href"]).content.startswith(b"\x89PNG")
    # The same job through the native API.
    assert server.client.get(f"/v1/jobs/{status['jobID']}").json()["status"] == "successful"
    dismissed = client._request(method="DELETE", path=f"jobs/{status['jobID']}")
    assert dismissed["status"] == "dismissed"
    with pytest.raises(RuntimeError, match="no-such-job"):
        client._request(path=f"jobs/{status['jobID']}/results")


def test_execute_sync(client: Processes, server: Deployment) -> None:
    results = client.execute(
        "fourbar-grashof", inputs=FOURBAR, outputs={"grashof": {}, "barker": {}}
    )
    assert client.response_headers["Preference-Applied"] == "respond-sync"
    assert results == {
        "grashof": "grashof",
        "barker": {
            "value": {"class": "I-4", "code": "GRRC", "name": "Grashof rocker-crank"},
            "mediaType": "application/json",
        },
    }
    monitor_link = client.response_headers["Link"]
    assert 'rel="monitor"' in monitor_link and f"{server.base_url}/ogc/jobs/" in monitor_link
    jobs = client._request(path="jobs", kwargs={"processID": "fourbar-grashof", "limit": 50})
    assert jobs["jobs"] and {j["processID"] for j in jobs["jobs"]} == {"fourbar-grashof"}
