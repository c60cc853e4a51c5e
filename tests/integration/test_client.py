"""The Python client (dexlab.Client, dexlab.AsyncClient) against a real service, on the
embedded default and on PostgreSQL + Celery over Redis; its retries against real
network faults (a port that refuses, a dropped answer, a 503 from a proxy)."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from dexlab import (
    AsyncClient,
    Client,
    CostLimitExceeded,
    InvalidInputs,
    JobDismissed,
    JobFailed,
    NoSuchArtifact,
    NoSuchJob,
    NoSuchProcess,
    ResultNotReady,
    RetryPolicy,
)
from tests.integration.faulty_proxy import FaultyProxy
from tests.integration.servers import Deployment, deployment, free_port

pytestmark = pytest.mark.integration

CLIENT_BACKENDS = ("embedded", "celery-redis")
#: A joint-limited map that runs for many seconds (cancelled or stopped by the tests).
LONG_MAP = {
    "links": [15, 14, 8],
    "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
    "grid": {"points_per_axis": 801},
    "orientation_step_deg": 0.5,
    "method": "orientation-sampling",
}
#: One quick worked example per family (the paper's number, in the process's order).
FAMILY_EXAMPLES = [
    ("planar3r-synthesis", 2),
    ("planar2dof-conditioning-map", 5),
    ("spm-design-space", 1),
    ("chain-parallelism", 1),
]


@pytest.fixture(scope="module", params=CLIENT_BACKENDS)
def server(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Deployment]:
    with deployment(str(request.param), tmp_path_factory.mktemp("client")) as dep:
        yield dep


@pytest.fixture
def client(server: Deployment) -> Iterator[Client]:
    with Client(server.base_url) as c:
        yield c


def without_plots(client: Client, process_id: str, example: int) -> dict[str, Any]:
    return {**client.examples(process_id)[example]["inputs"], "plots": False}


def test_run_a_worked_example_of_each_family(client: Client) -> None:
    for process_id, example in FAMILY_EXAMPLES:
        job = client.run(process_id, without_plots(client, process_id, example), timeout=120)
        assert job.last_status.status == "successful", (process_id, job.last_status)
        assert job.result and job.process_id == process_id
        assert all(a.media_type != "image/png" for a in job.artifacts)  # plots off
    # One with its plots, by example number (counted from 0 in the process's order).
    job = client.run("fourbar-grashof", example=1, timeout=120)
    assert job.result["classification"] == "crank-rocker"
    assert job.notes and job.notes[0].startswith("Grashof")
    assert {a.name for a in job.artifacts} == {"fourbar_motion.png", "fourbar_motion.svg"}
    assert job.read("fourbar_motion.png").startswith(b"\x89PNG")
    html = job._repr_html_()  # in Jupyter: status, notes, the plot inline
    assert "successful" in html and "Grashof: s + l" in html
    assert 'src="data:image/png;base64,' in html


def test_arrays_table_and_download(client: Client, tmp_path: Path) -> None:
    job = client.run("planar2dof-conditioning-map", example=0, timeout=120)
    maps = job.arrays("conditioning_map.npz")
    x, y, values = maps["x"], maps["y"], maps["inverse_condition"]
    assert x.ndim == 1 and y.ndim == 1 and values.shape == (y.size, x.size)
    assert np.nanmax(values) <= 1.0 + 1e-9 and np.nanmin(values) >= 0.0
    rows = job.table("conditioning_map.csv")
    columns = {"x [units]", "y [units]", "inverse_condition [-]"}
    assert len(rows) == x.size * y.size and columns <= set(rows[0])
    reachable = [r for r in rows if r["reachable [-]"] == 1]
    assert reachable and all(isinstance(r["inverse_condition [-]"], float) for r in reachable)
    assert str(maps["axes"]) and '"inverse_condition": ["y", "x"]' in str(maps["axes"])
    written = job.download(tmp_path / "files")
    assert [p.name for p in written] == [a.name for a in job.artifacts]
    for path, artifact in zip(written, job.artifacts, strict=True):
        assert path.stat().st_size == artifact.size
    with pytest.raises(NoSuchArtifact, match=r"no file 'nope\.npz'"):
        job.arrays("nope.npz")


def test_jobs_iterates_over_every_page(client: Client) -> None:
    inputs = without_plots(client, "fourbar-grashof", 0)
    made = {client.submit("fourbar-grashof", inputs).id for _ in range(5)}
    listed = [job.id for job in client.jobs(process="fourbar-grashof", page_size=2)]
    assert made <= set(listed) and len(listed) == len(set(listed))
    assert all(j.process_id == "fourbar-grashof" for j in client.jobs(process="fourbar-grashof"))
    with pytest.raises(InvalidInputs):
        next(iter(client.jobs(status="half-done")))


def test_problems_raise_typed_exceptions(client: Client) -> None:
    with pytest.raises(InvalidInputs) as invalid:
        client.submit("fourbar-grashof", {"lengths": [30, 17, 18], "ground": 9})
    assert {e["field"] for e in invalid.value.errors} == {"inputs.lengths", "inputs.ground"}
    with pytest.raises(CostLimitExceeded) as costly:
        client.submit("planar3r-dexterity-map", {**LONG_MAP, "grid": {"points_per_axis": 2001},
                                                  "orientation_step_deg": 0.1})  # fmt: skip
    assert (costly.value.cost or 0) > (costly.value.cost_limit or 0) > 0
    with pytest.raises(NoSuchProcess):
        client.describe("no-such-process")
    with pytest.raises(NoSuchJob):
        client.job("no-such-job")
    with pytest.raises(ValueError, match="worked examples"):
        client.submit("fourbar-grashof", example=99)


def test_cancel_a_running_job(client: Client) -> None:
    job = client.submit("planar3r-dexterity-map", LONG_MAP)
    with pytest.raises(ResultNotReady):
        client.job(job.id).results()
    assert job.cancel().status == "dismissed"
    with pytest.raises(JobDismissed):
        job.wait(timeout=30)


@pytest.fixture(scope="module", params=CLIENT_BACKENDS)
def strict_server(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Deployment]:
    """A deployment whose jobs get a 1 s time limit: long jobs fail."""
    env = {"DEXLAB_MAX_TIME_LIMIT_S": "1", "DEXLAB_MAX_ATTEMPTS": "1"}
    with deployment(str(request.param), tmp_path_factory.mktemp("strict"), workers=1,
                    env=env) as dep:  # fmt: skip
        yield dep


def test_a_failing_job_raises_job_failed_with_its_problem(strict_server: Deployment) -> None:
    with Client(strict_server.base_url) as client:
        with pytest.raises(JobFailed) as failed:
            client.run("planar3r-dexterity-map", LONG_MAP, timeout=60)
        assert failed.value.slug == "time-limit-exceeded"
        assert "time limit" in failed.value.detail
        job = client.job(failed.value.job_id or "")
        assert job.last_status.status == "failed"
        with pytest.raises(JobFailed, match="time limit"):
            _ = job.result


@pytest.mark.anyio
async def test_async_client_essentials(server: Deployment, tmp_path: Path) -> None:
    async with AsyncClient(server.base_url) as client:
        assert "fourbar-grashof" in {p["id"] for p in await client.processes()}
        inputs = {**(await client.examples("spm-design-space"))[1]["inputs"], "plots": False}
        job = await client.run("spm-design-space", inputs, timeout=120)
        assert job.result["designs"] and job.notes is not None
        arrays = await job.arrays("design_space.npz")
        assert arrays["f_min"].shape == arrays["beta_deg"].shape
        assert len(await job.table("design_space.csv")) > 0
        assert len(await job.download(tmp_path)) == len(job.artifacts)
        seen = [j.id async for j in client.jobs(process="spm-design-space", page_size=1)]
        assert job.id in seen
        with pytest.raises(InvalidInputs):
            await client.submit("fourbar-grashof", {"lengths": [1, 2]})
        with pytest.raises(NoSuchJob):
            await client.job("nope")
        long = await client.submit("planar3r-dexterity-map", LONG_MAP)
        assert (await long.cancel()).status == "dismissed"
        with pytest.raises(JobDismissed):
            await long.wait(timeout=30)


def quick_retries(attempts: int = 30) -> RetryPolicy:
    return RetryPolicy(attempts=attempts, backoff_s=0.1, max_backoff_s=0.5, jitter=False)


def test_a_submission_whose_answer_is_lost_is_retried_into_the_same_job(
    server: Deployment,
) -> None:
    """The proxy forwards the first submission, then drops the service's answer: the
    client sends it again with the same Idempotency-Key and gets the same job back."""
    with FaultyProxy(server.base_url) as proxy, Client(proxy.url, retry=quick_retries()) as client:
        proxy.faults.append("drop-answer")
        job = client.submit("fourbar-grashof", {"lengths": [2, 7, 9, 6], "ground": 1})
        posts = [r for r in proxy.exchanges if r.method == "POST"]
        assert len(posts) == 2
        keys = {r.headers["idempotency-key"] for r in posts}
        assert len(keys) == 1 and next(iter(keys)).startswith("dexlab-client-")
        assert [r.answer_job_id for r in posts] == [job.id, job.id]
        assert posts[1].answer_headers.get("idempotent-replayed") == "true"


def test_a_503_with_retry_after_is_waited_out(server: Deployment) -> None:
    with FaultyProxy(server.base_url) as proxy, Client(proxy.url, retry=quick_retries()) as client:
        proxy.faults.append("unavailable")
        started = time.monotonic()
        assert client.processes()
        assert time.monotonic() - started >= 1.0  # the proxy's Retry-After: 1
        assert len(proxy.exchanges) == 2


def test_a_service_that_is_not_up_yet_is_waited_for(server: Deployment) -> None:
    """Connection refused at first: the client retries until the port answers."""
    port = free_port()
    proxy = FaultyProxy(server.base_url, port=port)
    opened = threading.Timer(1.0, proxy.start)
    started = time.monotonic()  # the port opens a second after this
    opened.start()
    try:
        with Client(f"http://127.0.0.1:{port}", retry=quick_retries()) as client:
            job = client.submit("fourbar-grashof", {"lengths": [2, 7, 9, 6], "ground": 0})
            assert time.monotonic() - started >= 1.0
            assert job.last_status.status in ("accepted", "running", "successful")
    finally:
        opened.join()
        proxy.stop()
