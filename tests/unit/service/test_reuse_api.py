"""Reuse over the real app (ASGI, embedded SQLite store, the queue drained in-process by
a worker loop): what two keys see with DEXLAB_REUSE=all and =owner, through /v1, /ogc
and the pages; reuse: false, Cache-Control: no-cache, share: false; Prefer: wait on a
reused result whatever the sync cost limit; and an admin's invalidation."""

from __future__ import annotations

from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from pathlib import Path
from typing import Any

import httpx
import pytest
from fastapi import FastAPI

from service.app import create_app
from service.config import Settings
from tests.unit.worker.test_runner import registry as toy_registry
from worker.processes import ProcessRegistry
from worker.registry import worker_registry
from worker.runner import WorkerLoop
from worker.settings import WorkerSettings

pytestmark = pytest.mark.anyio

ADMIN, ALICE, BOB = "admin-secret-3f9a0c11", "alice-secret-51d2e7aa", "bob-secret-9e0b4c21"
FOURBAR = "/v1/processes/fourbar-grashof/execution"
FOURBAR_OGC = "/ogc/processes/fourbar-grashof/execution"
INPUTS = {"lengths": [2, 7, 9, 6], "ground": 1}


def key(secret: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {secret}"}


class Service:
    """The app, a client, and a worker loop that runs every queued job when told."""

    def __init__(self, app: FastAPI, client: httpx.AsyncClient, registry: ProcessRegistry):
        self.app, self.client = app, client
        self.loop = WorkerLoop(WorkerSettings(workers=1), app.state.store, registry)

    def drain(self, limit: int = 1000) -> int:
        """Run queued jobs (at most ``limit``) until none is left; how many ran."""
        store, ran = self.app.state.store, 0
        while ran < limit and (claim := store.claim_next(self.loop.worker_id, 30)) is not None:
            self.loop.execute(claim)
            ran += 1
        return ran

    async def submit(self, secret: str, url: str = FOURBAR, **body: Any) -> httpx.Response:
        headers = {**key(secret), **body.pop("headers", {})}
        return await self.client.post(url, json={"inputs": INPUTS, **body}, headers=headers)

    async def results(self, secret: str, job_id: str) -> dict[str, Any]:
        response = await self.client.get(f"/v1/jobs/{job_id}/results", headers=key(secret))
        assert response.status_code == 200, response.text
        body: dict[str, Any] = response.json()
        return body


@asynccontextmanager
async def service(
    tmp_path: Path, reuse: str | None, registry: ProcessRegistry | None = None
) -> AsyncIterator[Service]:
    extra = {} if reuse is None else {"reuse": reuse}
    settings = Settings(data_dir=tmp_path, workers=0, **extra,
                        api_keys=f"root:{ADMIN}:admin,alice:{ALICE},bob:{BOB}")  # fmt: skip
    app = create_app(settings, registry=registry)
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://dexlab.test") as c:
            yield Service(app, c, registry or worker_registry())


async def test_with_reuse_all_two_keys_make_two_jobs_and_one_computation(tmp_path: Path) -> None:
    async with service(tmp_path, "all") as s:
        first = (await s.submit(ALICE)).json()
        assert first["status"] == "accepted" and "reused_from" not in first
        assert s.drain() == 1
        second = await s.submit(BOB)
        assert second.status_code == 201 and s.drain() == 0
        bob = second.json()
        assert bob["status"] == "successful" and bob["jobID"] != first["jobID"]
        assert bob["reused_from"] is True  # bob does not learn alice's job ID
        again = (await s.submit(ALICE)).json()
        assert again["reused_from"] == first["jobID"]  # alice's own
        admin_view = (await s.client.get(f"/v1/jobs/{bob['jobID']}", headers=key(ADMIN))).json()
        assert admin_view["reused_from"] == first["jobID"]
        ogc = f"/ogc/jobs/{bob['jobID']}"
        assert (await s.client.get(ogc, headers=key(BOB))).json()["reused_from"] is True
        ogc_admin = (await s.client.get(ogc, headers=key(ADMIN))).json()
        assert ogc_admin["reused_from"] == first["jobID"]
        listed = (await s.client.get("/ogc/jobs", headers=key(ALICE))).json()["jobs"]
        assert {j["jobID"]: j.get("reused_from") for j in listed} == {
            first["jobID"]: None, again["jobID"]: first["jobID"]}  # fmt: skip
        alice_results = await s.results(ALICE, first["jobID"])
        bob_results = await s.results(BOB, bob["jobID"])
        assert bob_results["reused_from"] is True and "reused_from" not in alice_results
        assert bob_results["result"] == alice_results["result"]
        provenance = bob_results["result"]["provenance"]
        assert provenance["process"]["id"] == "fourbar-grashof"
        assert len(bob_results["result"]["result_hash"]) == 64
        files = [a["href"] for a in bob_results["artifacts"]]
        assert files
        # deleting the computing job leaves the other's results and files whole
        deleted = await s.client.delete(f"/v1/jobs/{first['jobID']}", headers=key(ALICE))
        assert deleted.status_code == 200
        for href in files:
            got = await s.client.get(href, headers=key(BOB))
            assert got.status_code == 200 and got.content
        status = (await s.client.get(f"/v1/jobs/{again['jobID']}", headers=key(ALICE))).json()
        assert status["reused_from"] == first["jobID"]  # stays after the original is deleted


async def test_with_reuse_owner_keys_never_share(tmp_path: Path) -> None:
    async with service(tmp_path, None) as s:  # the default with keys: owner
        await s.submit(ALICE)
        s.drain()
        for url in (FOURBAR, FOURBAR_OGC):
            bob = await s.submit(BOB, url, headers={"Prefer": "respond-async"})
            assert bob.status_code == 201 and bob.json()["status"] == "accepted"
        assert s.drain() == 2
        await s.client.delete("/v1/reuse/fourbar-grashof", headers=key(ADMIN))  # bob's too
        await s.submit(ALICE)
        s.drain()
        page = await s.client.post(
            "/pages/processes/fourbar-grashof/run",
            data={"inputs": '{"lengths": [2, 7, 9, 6], "ground": 1}'},
            headers={**key(BOB), "Origin": "http://dexlab.test"},
        )
        assert page.status_code == 303, page.text
        job = (await s.client.get(page.headers["location"], headers=key(BOB))).json()
        assert job["status"] == "accepted" and "reused_from" not in job
        assert s.drain() == 1
        mine = await s.submit(ALICE)
        assert mine.json()["status"] == "successful"


async def test_reuse_false_no_cache_and_share_false(tmp_path: Path) -> None:
    async with service(tmp_path, "all") as s:
        await s.submit(ALICE, share=False)
        s.drain()
        assert (await s.submit(BOB)).json()["status"] == "accepted"  # not shared
        s.drain()
        assert (await s.submit(ALICE, reuse=False)).json()["status"] == "accepted"
        no_cache = await s.submit(ALICE, headers={"Cache-Control": "no-cache"})
        assert no_cache.json()["status"] == "accepted"
        ogc = await s.submit(ALICE, FOURBAR_OGC, reuse=False,
                             headers={"Prefer": "respond-async"})  # fmt: skip
        assert ogc.status_code == 201 and ogc.json()["status"] == "accepted"
        assert s.drain() == 3
        assert (await s.submit(ALICE)).json()["status"] == "successful"
        wrong = await s.submit(ALICE, reuse="no")
        assert wrong.status_code == 422 and "reuse" in wrong.text


async def test_a_reused_result_answers_prefer_wait_whatever_the_sync_cost_limit(
    tmp_path: Path,
) -> None:
    toy = toy_registry()  # "square" has no sync_cost_limit: never synchronous when computed
    async with service(tmp_path, "owner", toy) as s:
        url = "/v1/processes/square/execution"
        body = {"inputs": {"x": 3}}
        first = await s.client.post(url, json=body, headers={**key(ALICE), "Prefer": "wait=5"})
        assert first.status_code == 201
        s.drain()
        again = await s.client.post(url, json=body, headers={**key(ALICE), "Prefer": "wait=5"})
        assert again.status_code == 200, again.text
        assert again.json()["result"]["square"] == 9.0
        assert again.json()["reused_from"] == first.json()["jobID"]


async def test_an_admin_invalidates_without_deleting_jobs(tmp_path: Path) -> None:
    async with service(tmp_path, "owner") as s:
        first = (await s.submit(ALICE)).json()
        s.drain()
        key_of = (await s.results(ALICE, first["jobID"]))["result"]["provenance"]["result_key"]
        refused = await s.client.delete("/v1/reuse/fourbar-grashof", headers=key(ALICE))
        assert refused.status_code == 403
        unknown = await s.client.delete("/v1/reuse/no-such-process", headers=key(ADMIN))
        assert unknown.status_code == 404
        other = await s.client.delete(
            "/v1/reuse/fourbar-grashof", params={"key": "0" * 64}, headers=key(ADMIN)
        )
        assert other.json()["invalidated"] == 0
        done = await s.client.delete(
            "/v1/reuse/fourbar-grashof", params={"key": key_of}, headers=key(ADMIN)
        )
        assert done.status_code == 200 and done.json()["invalidated"] == 1
        assert (await s.submit(ALICE)).json()["status"] == "accepted"
        assert (await s.results(ALICE, first["jobID"]))["result"]  # the job stays


STUDY: dict[str, Any] = {
    "process": "planar3r-dexterity-map",
    "fixed": {"links": [15, 14, 8], "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
              "task_points": [[14, 14], [12, 8], [8, -8]], "grid": {"points_per_axis": 5}},
    "vary": {"links[0]": [10, 20, 5], "links[1]": [8, 18, 4]},
    "objectives": {"task_points[].d_z|min": "max", "links|sum": "min"},
    "engine": "per-design", "chunk_size": 3, "plots": False,
}  # fmt: skip


async def test_a_study_run_again_reuses_its_stored_chunks(tmp_path: Path) -> None:
    """A study dismissed before its assembly (a crash, a change of mind) leaves its
    chunks stored: running it again computes none of them; with reuse false it computes
    every one; both assemble to the same result_hash."""
    async with service(tmp_path, "owner") as s:
        url = "/v1/processes/design-study/execution"
        first = (await s.client.post(url, json={"inputs": STUDY}, headers=key(ALICE))).json()
        assert s.drain(limit=1) == 1  # the split
        status = await s.client.get(f"/v1/jobs/{first['jobID']}", headers=key(ALICE))
        chunks = status.json()["chunks"]["total"]
        assert chunks > 1 and s.drain(limit=chunks) == chunks  # each chunk, not the assembly
        await s.client.delete(f"/v1/jobs/{first['jobID']}", headers=key(ALICE))
        again = (await s.client.post(url, json={"inputs": STUDY}, headers=key(ALICE))).json()
        assert again["status"] == "accepted" and "reused_from" not in again
        assert s.drain() == 2  # the split and the assembly: every chunk reused
        done = (await s.client.get(f"/v1/jobs/{again['jobID']}", headers=key(ALICE))).json()
        assert done["status"] == "successful"
        assert done["chunks"] == {"total": chunks, "ended": chunks, "failed": 0}
        fresh = await s.client.post(url, json={"inputs": STUDY, "reuse": False},
                                    headers=key(ALICE))  # fmt: skip
        assert fresh.json()["status"] == "accepted"
        assert s.drain() == chunks + 2  # a fresh study computes its chunks
        one = await s.results(ALICE, again["jobID"])
        other = await s.results(ALICE, fresh.json()["jobID"])
        assert one["result"]["result_hash"] == other["result"]["result_hash"]
        assert one["result"]["feasible"] == other["result"]["feasible"]


async def test_chunk_size_is_left_out_of_the_keys(tmp_path: Path) -> None:
    """chunk_size only cuts the work: a finished study asked again with another
    chunk_size is answered by its stored result, and a study cut the same way by an
    explicit chunk_size reuses the chunks another cut left (none of their inputs names
    it)."""
    async with service(tmp_path, "owner") as s:
        url = "/v1/processes/design-study/execution"
        first = (await s.client.post(url, json={"inputs": STUDY}, headers=key(ALICE))).json()
        s.drain()
        other_cut = {**STUDY, "chunk_size": 7}
        again = (await s.client.post(url, json={"inputs": other_cut}, headers=key(ALICE))).json()
        assert again["status"] == "successful" and again["reused_from"] == first["jobID"]
        # a study cut by the cost model (twenty designs: four chunks of five) dismissed after
        # its chunks ran, then asked with that cut spelled out: every chunk reused
        moved = {k: v for k, v in STUDY.items() if k != "chunk_size"}
        moved["fixed"] = {**STUDY["fixed"], "grid": {"points_per_axis": 6}}
        started = (await s.client.post(url, json={"inputs": moved}, headers=key(ALICE))).json()
        assert s.drain(limit=1) == 1
        status = await s.client.get(f"/v1/jobs/{started['jobID']}", headers=key(ALICE))
        chunks = status.json()["chunks"]["total"]
        assert chunks == 4 and s.drain(limit=chunks) == chunks
        await s.client.delete(f"/v1/jobs/{started['jobID']}", headers=key(ALICE))
        same_cut = {**moved, "chunk_size": 5}
        rerun = (await s.client.post(url, json={"inputs": same_cut}, headers=key(ALICE))).json()
        assert rerun["status"] == "accepted"
        assert s.drain() == 2  # the split and the assembly
