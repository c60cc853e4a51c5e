"""Retention on a real `dexlab serve`, embedded and Celery over Redis (PostgreSQL).

The service keeps finished jobs 2 s (``DEXLAB_RESULT_TTL_S``).  A job's status
carries ``expires``; once it passes, the sweeper deletes the job's row and files (or
chunk rows), the job answers 410 ``job-expired`` for its grace (its own retention),
then 404.  A request may ask for less with ``retention_s``, never more.  Under a
steady stream of jobs the stored files stay bounded.
"""

from __future__ import annotations

import contextlib
import os
import time
from collections.abc import Iterator
from datetime import datetime
from typing import Any

import httpx
import pytest

from tests.integration.servers import Deployment, deployment, wait_terminal
from worker.settings import WorkerSettings
from worker.store import open_store
from worker.store.base import JobStore
from worker.store.postgres import PostgresJobStore
from worker.store.sqlite import SqliteJobStore

pytestmark = pytest.mark.integration

TTL_S = 2.0
EXECUTE = "/v1/processes/fourbar-grashof/execution"
FOURBAR = {"lengths": [2, 7, 9, 6], "ground": 1}


@pytest.fixture(scope="module", params=["embedded", "celery-redis"])
def short_lived(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Deployment]:
    env = {"DEXLAB_RESULT_TTL_S": str(TTL_S)}
    with deployment(str(request.param), tmp_path_factory.mktemp("ttl"), env=env) as dep:
        yield dep


@pytest.fixture
def store(short_lived: Deployment) -> Iterator[JobStore]:
    """The deployment's own store, opened as a worker would (to look at its rows)."""
    settings = WorkerSettings(
        data_dir=short_lived.data_dir, store_url=short_lived.env.get("DEXLAB_STORE_URL")
    )
    opened = open_store(settings.resolved_store_url(), retry_s=5.0)
    yield opened
    opened.close()


def seconds(stamp: str) -> float:
    return datetime.fromisoformat(stamp.replace("Z", "+00:00")).timestamp()


def run_job(client: httpx.Client, **body: Any) -> dict[str, Any]:
    r = client.post(EXECUTE, json={"inputs": FOURBAR, **body})
    assert r.status_code == 201, r.text
    done = wait_terminal(client, r.json()["jobID"])
    assert done["status"] == "successful", done
    return done


def stored(store: JobStore, job_id: str) -> dict[str, int]:
    """The job's rows and stored bytes (files on SQLite, chunk rows on PostgreSQL)."""
    counts: dict[str, int] = {}
    for table in ("jobs", "artifact_index"):
        query = f"SELECT COUNT(*) AS n FROM {table} WHERE job_id = ?"
        counts[table] = int(store._one(store._conn(), query, (job_id,))["n"])  # type: ignore[attr-defined]
    if isinstance(store, SqliteJobStore):
        folder = store.files.root / job_id
        counts["bytes"] = sum(1 for p in folder.rglob("*") if p.is_file()) if folder.exists() else 0
    else:
        assert isinstance(store, PostgresJobStore)
        query = "SELECT COUNT(*) AS n FROM artifact_chunks WHERE job_id = ?"
        counts["bytes"] = int(store._one(store._conn(), query, (job_id,))["n"])
    return counts


def all_stored_bytes(store: JobStore) -> int:
    if isinstance(store, SqliteJobStore):  # the sweeper deletes files as we count them
        total = 0
        for root, _, names in os.walk(store.files.root):
            for name in names:
                with contextlib.suppress(FileNotFoundError):
                    total += os.stat(os.path.join(root, name)).st_size
        return total
    assert isinstance(store, PostgresJobStore)
    row = store._one(
        store._conn(), "SELECT COALESCE(SUM(LENGTH(data)), 0) AS n FROM artifact_chunks"
    )
    return int(row["n"])


def poll_until(
    client: httpx.Client, path: str, status: int | set[int], timeout: float
) -> httpx.Response:
    wanted = {status} if isinstance(status, int) else status
    deadline = time.monotonic() + timeout
    r = client.get(path)
    while r.status_code not in wanted and time.monotonic() < deadline:
        time.sleep(0.1)
        r = client.get(path)
    assert r.status_code in wanted, (path, r.status_code, r.text)
    return r


def test_a_job_expires_with_its_files_then_is_forgotten(
    short_lived: Deployment, store: JobStore
) -> None:
    client = short_lived.client
    done = run_job(client)
    job_id = done["jobID"]
    assert done["expires"] is not None
    assert seconds(done["expires"]) - seconds(done["finished"]) == pytest.approx(TTL_S, abs=0.01)
    ogc = client.get(f"/ogc/jobs/{job_id}").json()
    assert ogc["expires"] == done["expires"]
    before = stored(store, job_id)
    assert before["jobs"] == 1 and before["artifact_index"] > 0 and before["bytes"] > 0
    artifact = client.get(f"/v1/jobs/{job_id}/results").json()["artifacts"][0]["name"]

    gone = poll_until(client, f"/v1/jobs/{job_id}", 410, timeout=TTL_S + 10)
    assert time.time() >= seconds(done["expires"])
    assert gone.headers["content-type"].startswith("application/problem+json")
    assert gone.json()["type"] == "/problems/job-expired"
    assert stored(store, job_id) == {"jobs": 0, "artifact_index": 0, "bytes": 0}
    for path in (
        f"/v1/jobs/{job_id}/results",
        f"/v1/jobs/{job_id}/results/{artifact}",
        f"/ogc/jobs/{job_id}",
        f"/ogc/jobs/{job_id}/results",
    ):
        r = client.get(path)
        assert r.status_code == 410 and r.json()["type"].endswith("/job-expired"), (path, r.text)
    assert client.delete(f"/v1/jobs/{job_id}").status_code == 410
    assert job_id not in [j["jobID"] for j in client.get("/v1/jobs").json()["jobs"]]

    # The tombstone is kept as long as the job was (2 s), then the ID is unknown.
    forgotten = poll_until(client, f"/v1/jobs/{job_id}", 404, timeout=TTL_S + 10)
    assert forgotten.json()["type"] == "/problems/no-such-job"


def test_a_request_may_ask_for_less_retention_never_more(short_lived: Deployment) -> None:
    client = short_lived.client
    done = run_job(client, retention_s=0.5)
    assert seconds(done["expires"]) - seconds(done["finished"]) == pytest.approx(0.5, abs=0.01)
    for body in ({"retention_s": 3600}, {"retention_s": 0}, {"retention_s": "1"}):
        r = client.post(EXECUTE, json={"inputs": FOURBAR, **body})
        assert r.status_code in (400, 422), r.text
        assert "retention_s" in r.text, r.text
    r = client.post(
        "/ogc/processes/fourbar-grashof/execution",
        json={"inputs": FOURBAR, "retention_s": 3600},
        headers={"Prefer": "respond-async"},
    )
    assert r.status_code in (400, 422) and "retention_s" in r.text, r.text


def test_stored_files_stay_bounded_under_a_steady_load(
    short_lived: Deployment, store: JobStore
) -> None:
    client = short_lived.client
    first = run_job(client)
    files = client.get(f"/v1/jobs/{first['jobID']}/results").json()["artifacts"]
    per_job = sum(int(a["size"]) for a in files)
    job_ids: list[str] = [first["jobID"]]
    peak = 0
    for _ in range(40):  # a job every 0.3 s for 12 s
        r = client.post(EXECUTE, json={"inputs": FOURBAR})
        assert r.status_code == 201, r.text
        job_ids.append(r.json()["jobID"])
        peak = max(peak, all_stored_bytes(store))
        time.sleep(0.3)
    for job_id in job_ids:  # expired (410), or already forgotten (404)
        poll_until(client, f"/v1/jobs/{job_id}", {410, 404}, timeout=60)
    # Kept 2 s, swept every 0.5 s, at a job per 0.3 s: about 9 jobs' files at a time,
    # never the 41 jobs' that would pile up without retention.
    assert peak <= 20 * per_job, (peak, per_job)
    assert all_stored_bytes(store) == 0
