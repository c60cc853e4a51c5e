"""The OGC API - Processes façade over httpx's ASGI transport (embedded backend).

Two apps: one with a real worker pool and a local HTTP receiver on its outbound
allow-list (execution modes, results, job lists, callbacks, inputs by reference), and
one without workers on the default settings (exceptions, refusals, proxies), whose
jobs the tests move through the store themselves.
"""

from __future__ import annotations

import asyncio
import email.parser
import email.policy
import json
import threading
import time
from collections.abc import AsyncIterator, Iterator
from datetime import datetime, timedelta
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any

import httpx
import pytest
from fastapi import FastAPI

from service.app import create_app
from service.config import Settings
from service.ogc.schemas import (
    OgcConfClasses,
    OgcJobList,
    OgcLandingPage,
    OgcProcess,
    OgcProcessList,
    OgcStatusInfo,
)
from service.ogc.vocabulary import REL_CONFORMANCE, REL_JOB_LIST, REL_PROCESSES, REL_RESULTS
from worker.contract import Artifact
from worker.registry import default_registry

pytestmark = [pytest.mark.integration, pytest.mark.anyio]

OGC_EXC = "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/"
CONF = "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/"
FOURBAR = {"lengths": [2, 7, 9, 6], "ground": 1}
FOURBAR_URL = "/ogc/processes/fourbar-grashof/execution"


@pytest.fixture(scope="module")
def anyio_backend() -> str:
    return "asyncio"


class Receiver:
    """A local HTTP server: records POSTed callbacks, serves JSON for input references."""

    def __init__(self) -> None:
        self.posts: list[tuple[str, str, Any]] = []
        self.documents: dict[str, Any] = {"/lengths.json": [2, 7, 9, 6]}
        receiver = self

        class Handler(BaseHTTPRequestHandler):
            def do_POST(self) -> None:
                body = self.rfile.read(int(self.headers.get("Content-Length", 0)))
                receiver.posts.append((self.path, self.headers["Content-Type"], json.loads(body)))
                self.send_response(202 if self.path != "/flaky" else 500)
                self.end_headers()

            def do_GET(self) -> None:
                if self.path == "/moved":
                    self.send_response(302)
                    self.send_header("Location", "/lengths.json")
                    self.end_headers()
                    return
                body = json.dumps(receiver.documents.get(self.path)).encode()
                self.send_response(200 if self.path in receiver.documents else 404)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)

            def log_message(self, *args: Any) -> None:
                pass

        self.server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.url = f"http://127.0.0.1:{self.server.server_address[1]}"
        threading.Thread(target=self.server.serve_forever, daemon=True).start()

    def posted(self, path: str) -> list[Any]:
        return [doc for p, _, doc in self.posts if p == path]


@pytest.fixture(scope="module")
def receiver() -> Iterator[Receiver]:
    r = Receiver()
    yield r
    r.server.shutdown()
    r.server.server_close()


async def _serve(app: FastAPI, ready: bool) -> AsyncIterator[httpx.AsyncClient]:
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://dexlab.test") as c:
            deadline = time.monotonic() + 60
            while ready and (await c.get("/health/ready")).status_code != 200:
                assert time.monotonic() < deadline, "the worker pool never came up"
                await asyncio.sleep(0.2)
            c.app = app  # type: ignore[attr-defined]
            yield c


@pytest.fixture(scope="module")
async def pool(
    tmp_path_factory: pytest.TempPathFactory, receiver: Receiver
) -> AsyncIterator[httpx.AsyncClient]:
    settings = Settings(
        data_dir=tmp_path_factory.mktemp("ogc-pool"),
        workers=1,
        heartbeat_seconds=0.5,
        outbound_allow_hosts=receiver.url.removeprefix("http://"),
    )
    async for client in _serve(create_app(settings), ready=True):
        yield client


@pytest.fixture(scope="module")
async def idle(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[httpx.AsyncClient]:
    settings = Settings(data_dir=Path(tmp_path_factory.mktemp("ogc-idle")), workers=0)
    async for client in _serve(create_app(settings), ready=False):
        yield client


def store_of(client: httpx.AsyncClient) -> Any:
    return client.app.state.store  # type: ignore[attr-defined]


async def wait_status(
    client: httpx.AsyncClient, job_url: str, statuses: set[str]
) -> dict[str, Any]:
    deadline = time.monotonic() + 60
    while True:
        doc: dict[str, Any] = (await client.get(job_url)).json()
        if doc["status"] in statuses or time.monotonic() > deadline:
            return doc
        await asyncio.sleep(0.1)


# -- discovery -------------------------------------------------------------------------
async def test_landing_conformance_and_processes(pool: httpx.AsyncClient) -> None:
    for path in ("/ogc/", "/ogc"):
        landing = (await pool.get(path)).json()
        OgcLandingPage.model_validate(landing)
    rels = {link["rel"]: link for link in landing["links"]}
    assert rels["self"]["href"] == "http://dexlab.test/ogc/"
    assert (rels["alternate"]["href"], rels["alternate"]["type"]) == (
        "http://dexlab.test/ogc/?f=html",
        "text/html",
    )
    assert rels["service-desc"]["href"] == "http://dexlab.test/openapi.json"
    assert rels["service-desc"]["type"] == "application/vnd.oai.openapi+json;version=3.1"
    assert (rels["service-doc"]["href"], rels["service-doc"]["type"]) == (
        "http://dexlab.test/docs",
        "text/html",
    )
    assert rels[REL_CONFORMANCE]["href"] == "http://dexlab.test/ogc/conformance"
    assert rels[REL_PROCESSES]["href"] == "http://dexlab.test/ogc/processes"
    assert rels[REL_JOB_LIST]["href"] == "http://dexlab.test/ogc/jobs"
    openapi = (await pool.get("/openapi.json")).json()
    assert openapi["openapi"].startswith("3.1")
    conformance = (await pool.get("/ogc/conformance")).json()
    OgcConfClasses.model_validate(conformance)
    expected = [
        "core", "ogc-process-description", "json", "html", "job-list", "dismiss", "callback",
    ]  # fmt: skip
    assert conformance["conformsTo"] == [CONF + c for c in expected]  # no oas30: 3.1 is served
    first = (await pool.get("/ogc/processes")).json()  # 10 per page by default
    assert len(first["processes"]) == 10 and "next" in [link["rel"] for link in first["links"]]
    listing = (await pool.get("/ogc/processes", params={"limit": 100})).json()
    OgcProcessList.model_validate(listing)
    rels_of_list = [link["rel"] for link in listing["links"]]
    processes = len(list(default_registry()))  # more than a page of 10
    assert len(listing["processes"]) == processes > 10 and rels_of_list == ["self", "alternate"]
    page = (await pool.get("/ogc/processes", params={"limit": 4, "offset": 4})).json()
    assert [p["id"] for p in page["processes"]] == [p["id"] for p in listing["processes"][4:8]]
    (after,) = [link for link in page["links"] if link["rel"] == "next"]
    assert after["href"] == "http://dexlab.test/ogc/processes?limit=4&offset=8"
    description = (await pool.get("/ogc/processes/chain-parallelism")).json()
    OgcProcess.model_validate(description)
    assert description["inputs"]["chains"]["minOccurs"] == 1
    assert {"path": "chains[].Q", "unit": "length^4", "symbol": "$Q$"}.items() <= next(
        entry for entry in description["result_paths"] if entry["path"] == "chains[].Q"
    ).items()
    assert description["outputs"]["chain_graphs.svg"]["schema"]["contentMediaType"] == (
        "image/svg+xml"
    )
    bad = await pool.get("/ogc/processes", params={"limit": 0})
    assert bad.status_code == 400 and bad.json()["errors"][0]["field"] == "query.limit"
    assert bad.json()["type"] == OGC_EXC + "invalid-parameter-value"


# -- execution modes -------------------------------------------------------------------
async def test_no_preference_runs_synchronously_with_a_results_document(
    pool: httpx.AsyncClient,
) -> None:
    r = await pool.post(FOURBAR_URL, json={"inputs": FOURBAR, "response": "document"})
    assert r.status_code == 200, r.text
    assert "preference-applied" not in r.headers
    job_url = r.headers["location"]
    assert r.headers["link"] == f'<{job_url}>; rel="monitor"; type="application/json"'
    results = r.json()
    assert results["grashof"] == "grashof" and results["classification"] == "crank-rocker"
    assert results["barker"] == {
        "value": {"class": "I-4", "code": "GRRC", "name": "Grashof rocker-crank"},
        "mediaType": "application/json",
    }
    png = results["fourbar_motion.png"]  # a file: by reference by default
    assert png["type"] == "image/png" and png["href"].startswith("http://dexlab.test/v1/jobs/")
    assert (await pool.get(png["href"])).content.startswith(b"\x89PNG")
    # The job is a job like any other: visible through both APIs.
    job_id = job_url.rsplit("/", 1)[-1]
    assert (await pool.get(f"/v1/jobs/{job_id}")).json()["status"] == "successful"
    again = await pool.get(f"{job_url}/results")  # re-fetched as the request asked
    assert again.json() == results


async def test_respond_async_respond_sync_and_wait(pool: httpx.AsyncClient) -> None:
    # computed afresh: an earlier test's stored result would answer at once (reuse)
    body = {"inputs": FOURBAR, "response": "document", "reuse": False}
    r = await pool.post(FOURBAR_URL, json=body, headers={"Prefer": "respond-async"})
    assert r.status_code == 201 and r.headers["preference-applied"] == "respond-async"
    status = r.json()
    OgcStatusInfo.model_validate(status)
    assert r.headers["location"] == f"http://dexlab.test/ogc/jobs/{status['jobID']}"
    assert status["status"] in {"accepted", "running"}
    done = await wait_status(pool, r.headers["location"], {"successful"})
    assert any(link["rel"] == REL_RESULTS for link in done["links"])
    r = await pool.post(FOURBAR_URL, json=body, headers={"Prefer": "respond-sync, wait=30"})
    assert r.status_code == 200 and r.headers["preference-applied"] == "respond-sync, wait=30"
    # A request above the process's sync limit, or a process without one: asynchronous
    # whatever the preference (and no Preference-Applied: it was not honoured).
    synthesis = {
        "task_points": [[16, 19], [18, 0], [-8, -25]],
        "l3": 15,
        "grid": {"points_per_axis": 11},
        "plots": False,
    }
    r = await pool.post(
        "/ogc/processes/planar3r-synthesis/execution",
        json={"inputs": synthesis},
        headers={"Prefer": "respond-sync"},
    )
    assert r.status_code == 201 and "preference-applied" not in r.headers
    big = {"links": [15, 14, 8], "grid": {"points_per_axis": 501}, "plots": False}
    r = await pool.post("/ogc/processes/planar3r-dexterity-map/execution", json={"inputs": big})
    assert r.status_code == 201, r.text
    await pool.delete(r.headers["location"])


async def test_raw_responses(pool: httpx.AsyncClient) -> None:
    one = await pool.post(FOURBAR_URL, json={"inputs": FOURBAR, "outputs": {"grashof": {}}})
    assert one.status_code == 200 and one.json() == "grashof"
    assert one.headers["content-type"] == "application/json"
    svg = await pool.post(
        FOURBAR_URL,
        json={
            "inputs": FOURBAR,
            "outputs": {"fourbar_motion.svg": {"format": {"mediaType": "image/svg+xml"}}},
        },
    )
    assert svg.headers["content-type"] == "image/svg+xml" and b"<svg" in svg.content
    assert "sandbox" in svg.headers["content-security-policy"]
    refs = await pool.post(
        FOURBAR_URL,
        json={
            "inputs": FOURBAR,
            "outputs": {
                "grashof": {"transmissionMode": "reference"},
                "fourbar_motion.png": {"transmissionMode": "reference"},
            },
        },
    )
    assert refs.status_code == 204 and refs.content == b""
    links = [part.strip() for part in refs.headers["link"].split(",")]
    job_url = refs.headers["location"]
    assert links[0] == (
        f'<{job_url}/results/grashof>; rel="{REL_RESULTS}"; '
        'type="application/json"; title="grashof"'
    )
    assert (await pool.get(f"{job_url}/results/grashof")).json() == "grashof"
    png_href = links[1].split(">")[0].lstrip("<")
    assert (await pool.get(png_href)).headers["content-type"] == "image/png"
    multi = await pool.post(
        FOURBAR_URL,
        json={
            "inputs": FOURBAR,
            "outputs": {
                "classification": {},
                "barker": {},
                "fourbar_motion.png": {},
                "fourbar_motion.svg": {"transmissionMode": "reference"},
            },
        },
    )
    assert multi.status_code == 200
    assert multi.headers["content-type"].startswith("multipart/related; boundary=")
    message = email.parser.BytesParser(policy=email.policy.HTTP).parsebytes(
        b"Content-Type: " + multi.headers["content-type"].encode() + b"\r\n\r\n" + multi.content
    )
    parts = {p["Content-ID"]: p for p in message.iter_parts()}
    assert list(parts) == ["classification", "barker", "fourbar_motion.png", "fourbar_motion.svg"]
    assert json.loads(parts["classification"].get_content()) == "crank-rocker"
    assert json.loads(parts["barker"].get_content())["class"] == "I-4"
    assert parts["fourbar_motion.png"].get_content().startswith(b"\x89PNG")
    assert parts["fourbar_motion.svg"]["Content-Location"].endswith("/results/fourbar_motion.svg")
    # Files in line in a document: base64.
    inline = await pool.post(
        FOURBAR_URL,
        json={"inputs": FOURBAR, "response": "document", "outputs": {"fourbar_motion.png": {}}},
    )
    value = inline.json()["fourbar_motion.png"]
    assert (value["encoding"], value["mediaType"]) == ("base64", "image/png")
    import base64

    assert base64.b64decode(value["value"]) == parts["fourbar_motion.png"].get_content()


async def test_async_results_follow_the_execute_request(pool: httpx.AsyncClient) -> None:
    body = {"inputs": FOURBAR, "outputs": {"grashof": {}}}  # raw, one output, by value
    r = await pool.post(FOURBAR_URL, json=body, headers={"Prefer": "respond-async"})
    await wait_status(pool, r.headers["location"], {"successful"})
    results = await pool.get(f"{r.headers['location']}/results")
    assert results.status_code == 200 and results.json() == "grashof"
    # A job created through /v1 answers a results document of every output.
    native = await pool.post("/v1/processes/fourbar-grashof/execution", json={"inputs": FOURBAR})
    job_id = native.json()["jobID"]
    await wait_status(pool, f"/ogc/jobs/{job_id}", {"successful"})
    document = (await pool.get(f"/ogc/jobs/{job_id}/results")).json()
    assert document["grashof"] == "grashof" and "fourbar_motion.svg" in document


async def test_execute_request_errors_name_the_field(pool: httpx.AsyncClient) -> None:
    cases = [
        ({"inputs": {"lengths": [1, 2, 3], "ground": 0}}, 422, "inputs.lengths"),
        ({"inputs": FOURBAR, "response": "nice"}, 422, "response"),
        ({"inputs": FOURBAR, "mode": "async"}, 422, "mode"),
        ({"inputs": FOURBAR, "outputs": {"nope": {}}}, 422, "outputs.nope"),
        (
            {"inputs": FOURBAR, "outputs": {"grashof": {"transmissionMode": "carrier"}}},
            422,
            "outputs.grashof.transmissionMode",
        ),
    ]
    for body, status, field in cases:
        r = await pool.post(FOURBAR_URL, json=body)
        assert r.status_code == status, (body, r.text)
        assert r.headers["content-type"] == "application/problem+json"
        assert r.json()["errors"][0]["field"] == field, r.json()
    r = await pool.post("/ogc/processes/nope/execution", json={"inputs": {}})
    assert r.status_code == 404 and r.json()["type"] == OGC_EXC + "no-such-process"


# -- inputs by reference and callbacks (allowed hosts) ---------------------------------
async def test_inputs_by_reference_from_an_allowed_host(
    pool: httpx.AsyncClient, receiver: Receiver
) -> None:
    inputs = {
        "lengths": {"href": f"{receiver.url}/lengths.json", "type": "application/json"},
        "ground": {"value": 1, "mediaType": "application/json"},
    }
    r = await pool.post(FOURBAR_URL, json={"inputs": inputs, "outputs": {"lengths": {}}})
    assert r.status_code == 200 and r.json() == [2.0, 7.0, 9.0, 6.0]
    for href, why in (
        (f"{receiver.url}/missing.json", "answered 404"),
        (f"{receiver.url}/moved", "answered 302"),  # redirects are not followed
        ("http://203.0.113.1/lengths.json", "not on this server's allow-list"),
    ):
        r = await pool.post(FOURBAR_URL, json={"inputs": {**inputs, "lengths": {"href": href}}})
        assert r.status_code == 422 and why in r.json()["detail"], r.text
        assert r.json()["errors"][0]["field"] == "inputs.lengths.href"


async def test_callbacks_are_sent_once(pool: httpx.AsyncClient, receiver: Receiver) -> None:
    subscriber = {"successUri": f"{receiver.url}/done", "failedUri": f"{receiver.url}/failed"}
    body = {
        "inputs": FOURBAR,
        "outputs": {"grashof": {}, "fourbar_motion.png": {}},
        "subscriber": subscriber,
    }
    r = await pool.post(FOURBAR_URL, json=body, headers={"Prefer": "respond-async"})
    assert r.status_code == 201, r.text
    job_id = r.json()["jobID"]
    deadline = time.monotonic() + 30
    while not receiver.posted("/done") and time.monotonic() < deadline:
        await asyncio.sleep(0.1)
    await asyncio.sleep(1.5)  # later ticks must not send it again
    (document,) = receiver.posted("/done")
    assert document["grashof"] == "grashof"
    # The callback carries files by reference, at the URL the client used.
    assert document["fourbar_motion.png"]["href"] == (
        f"http://dexlab.test/v1/jobs/{job_id}/results/fourbar_motion.png"
    )
    assert receiver.posted("/failed") == []
    # A failing receiver is retried, and its failure is not the job's.
    store = store_of(pool)
    assert store.callback_log(job_id)[0]["delivered"]
    r = await pool.post(
        FOURBAR_URL,
        json={**body, "subscriber": {"successUri": f"{receiver.url}/flaky"}},
        headers={"Prefer": "respond-async"},
    )
    flaky_id = r.json()["jobID"]
    deadline = time.monotonic() + 30
    while len(receiver.posted("/flaky")) < 2 and time.monotonic() < deadline:
        await asyncio.sleep(0.2)
    assert len(receiver.posted("/flaky")) >= 2  # tried again after the 500
    assert (await pool.get(f"/ogc/jobs/{flaky_id}")).json()["status"] == "successful"


async def test_a_failed_job_calls_its_failed_uri(
    pool: httpx.AsyncClient, receiver: Receiver
) -> None:
    from worker.store.base import NewJob

    store = store_of(pool)
    # A job of a process no worker knows fails (the runner says so).
    job, _ = store.create_job(NewJob("retired-process", {}, 60.0, 1))
    store.set_request_options(
        job.job_id,
        {"response": "document", "base": "http://dexlab.test"},
        {"successUri": f"{receiver.url}/ok", "failedUri": f"{receiver.url}/ko"},
    )
    deadline = time.monotonic() + 30
    while not receiver.posted("/ko") and time.monotonic() < deadline:
        await asyncio.sleep(0.1)
    (problem,) = receiver.posted("/ko")
    assert problem["jobID"] == job.job_id and "does not know the process" in problem["detail"]
    assert problem["type"] == OGC_EXC + "no-such-process" and problem["status"] == 404
    assert [c for p, c, _ in receiver.posts if p == "/ko"] == ["application/problem+json"]
    results = await pool.get(f"/ogc/jobs/{job.job_id}/results")
    assert results.headers["content-type"] == "application/problem+json"
    assert "does not know the process" in results.json()["detail"]


# -- the job list ------------------------------------------------------------------------
async def test_job_list_parameters(pool: httpx.AsyncClient) -> None:
    ids = []
    for _ in range(3):
        r = await pool.post(FOURBAR_URL, json={"inputs": FOURBAR, "response": "document"})
        ids.append(r.headers["location"].rsplit("/", 1)[-1])
    chains = await pool.post(
        "/ogc/processes/chain-parallelism/execution",
        json={
            "inputs": {"chains": [{"name": "q", "lengths": [1, 1, 1, 1]}], "plots": False},
            "response": "document",
        },
    )
    chains_id = chains.headers["location"].rsplit("/", 1)[-1]
    slow = await pool.post(
        "/ogc/processes/planar3r-dexterity-map/execution",
        json={
            "inputs": {
                "links": [15, 14, 8],
                "grid": {"points_per_axis": 401},
                "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
                "method": "orientation-sampling",
                "orientation_step_deg": 0.5,
            }
        },
        headers={"Prefer": "respond-async"},
    )
    slow_url = slow.headers["location"]
    slow_id = slow_url.rsplit("/", 1)[-1]

    async def listed(**params: Any) -> list[str]:
        r = await pool.get("/ogc/jobs", params={"limit": 1000, **params})
        assert r.status_code == 200, r.text
        OgcJobList.model_validate(r.json())
        return [j["jobID"] for j in r.json()["jobs"]]

    assert (await listed(processID="chain-parallelism")) == [chains_id]
    both = await listed(processID=["chain-parallelism", "planar3r-dexterity-map"])
    assert both[:2] == [slow_id, chains_id]
    assert set(ids) <= set(await listed(status="successful"))
    assert slow_id not in await listed(status="successful")
    assert slow_id in await listed(status=["accepted", "running"])
    assert len(await listed(type="process")) == len(await listed())
    other = await pool.get("/ogc/jobs", params={"type": "other"})
    assert other.status_code == 400 and other.json()["errors"][0]["field"] == "query.type[0]"
    unknown = await pool.get("/ogc/jobs", params={"processID": ["fourbar-grashof", "nope"]})
    assert unknown.status_code == 400, unknown.text  # the definition lists the IDs
    assert unknown.json()["type"] == OGC_EXC + "invalid-parameter-value"
    assert unknown.json()["errors"][0]["field"] == "query.processID"
    first = (await pool.get(f"/ogc/jobs/{ids[0]}")).json()
    assert await listed(datetime=first["created"]) == [ids[0]]
    since = await listed(datetime=f"{first['created']}/..")
    assert set(since) >= {*ids, chains_id, slow_id} and len(set(since) & set(ids)) == 3
    before = datetime.fromisoformat(first["created"]) - timedelta(microseconds=1)
    assert ids[0] not in await listed(datetime=f"../{before.isoformat()}")
    assert ids[0] in await listed(datetime=f"{before.isoformat()}/{first['created']}")
    assert set(ids) <= set(await listed(maxDuration=30, status="successful"))
    assert not set(ids) & set(await listed(minDuration=3600))
    assert slow_id not in await listed(minDuration=0, status="accepted")  # no duration yet
    # Paging: limit and next links that keep the filters.
    r = (await pool.get("/ogc/jobs", params={"limit": 2, "processID": "fourbar-grashof"})).json()
    assert len(r["jobs"]) == 2
    (next_link,) = [link for link in r["links"] if link["rel"] == "next"]
    assert next_link["href"].startswith("http://dexlab.test/ogc/jobs?limit=2&processID=fourbar")
    following = (await pool.get(next_link["href"])).json()
    assert {j["processID"] for j in following["jobs"]} == {"fourbar-grashof"}
    assert not {j["jobID"] for j in following["jobs"]} & {j["jobID"] for j in r["jobs"]}
    for params, field in (
        ((("status", "paused"),), "query.status[0]"),
        ((("datetime", "yesterday"),), "query.datetime"),
        ((("minDuration", "-1"),), "query.minDuration"),
        ((("limit", "10001"),), "query.limit"),
        ((("cursor", "nope"),), "query.cursor"),
    ):
        bad = await pool.get("/ogc/jobs", params=list(params))
        assert bad.status_code == 400, (params, bad.text)
        assert bad.json()["errors"][0]["field"] == field
        assert bad.json()["type"] == OGC_EXC + "invalid-parameter-value"
    dismissed = await pool.delete(slow_url)
    assert dismissed.status_code == 200 and dismissed.json()["status"] == "dismissed"
    OgcStatusInfo.model_validate(dismissed.json())
    gone = await pool.get(f"{slow_url}/results")
    assert gone.status_code == 404 and gone.json()["type"] == OGC_EXC + "no-such-job"
    assert "dismissed" in gone.json()["detail"]


# -- exceptions, refusals, proxies (no workers) ------------------------------------------
async def test_exceptions_use_the_ogc_types_under_ogc_only(idle: httpx.AsyncClient) -> None:
    r = await idle.post(FOURBAR_URL, json={"inputs": FOURBAR})  # no worker: asynchronous
    assert r.status_code == 201 and "preference-applied" not in r.headers
    job_url = r.headers["location"]
    job_id = r.json()["jobID"]
    not_ready = await idle.get(f"{job_url}/results")
    assert not_ready.status_code == 404
    assert not_ready.json()["type"] == OGC_EXC + "result-not-ready"
    native = await idle.get(f"/v1/jobs/{job_id}/results")
    assert native.json()["type"] == "/problems/result-not-ready"
    for path, slug in (
        ("/ogc/jobs/nope", "no-such-job"),
        ("/ogc/jobs/nope/results", "no-such-job"),
        ("/ogc/processes/nope", "no-such-process"),
    ):
        assert (await idle.get(path)).json()["type"] == OGC_EXC + slug
    assert (await idle.delete("/ogc/jobs/nope")).json()["type"] == OGC_EXC + "no-such-job"
    assert (await idle.get("/v1/jobs/nope")).json()["type"] == "/problems/no-such-job"
    # A failed job's results are its failure, with the failure's status.
    store = store_of(idle)
    claim = store.claim_job(job_id, "tester:1", 30).claim
    error = {"type": "job-error", "title": "The job raised an error", "detail": "boom"}
    assert store.fail(job_id, claim.lease_token, error)
    failed = await idle.get(f"{job_url}/results")
    assert failed.status_code == 500 and failed.json()["detail"] == "boom"
    assert failed.json()["type"] == "/problems/job-error"


async def test_a_job_completed_through_the_store_answers_its_outputs(
    idle: httpx.AsyncClient,
) -> None:
    r = await idle.post(
        FOURBAR_URL,
        json={
            "inputs": FOURBAR,
            "response": "document",
            "outputs": {"grashof": {}, "criterion": {}, "links": {}},
        },
    )
    job_id = r.json()["jobID"]
    store = store_of(idle)
    claim = store.claim_job(job_id, "tester:1", 30).claim
    result = {"grashof": "grashof", "criterion": {"margin": 2.0}, "links": None}
    art = Artifact("fourbar_motion.png", "image/png", b"\x89PNG fake", "plot")
    assert store.complete(job_id, claim.lease_token, result, [art])
    document = (await idle.get(f"/ogc/jobs/{job_id}/results")).json()
    # Objects as qualified values; a null output has no in-line form and is left out.
    assert document == {
        "grashof": "grashof",
        "criterion": {"value": {"margin": 2.0}, "mediaType": "application/json"},
    }
    assert (await idle.get(f"/ogc/jobs/{job_id}/results/links")).json() is None
    file = await idle.get(f"/ogc/jobs/{job_id}/results/fourbar_motion.png")
    assert file.content == b"\x89PNG fake" and file.headers["etag"]
    missing = await idle.get(f"/ogc/jobs/{job_id}/results/nope")
    assert missing.status_code == 404


async def test_callbacks_and_references_are_refused_when_off(idle: httpx.AsyncClient) -> None:
    conformance = (await idle.get("/ogc/conformance")).json()["conformsTo"]
    assert CONF + "callback" not in conformance
    r = await idle.post(
        FOURBAR_URL, json={"inputs": FOURBAR, "subscriber": {"successUri": "http://127.0.0.1:9/x"}}
    )
    assert r.status_code == 422
    problem = r.json()
    assert problem["errors"][0]["field"] == "subscriber.successUri"
    assert "DEXLAB_OUTBOUND_ALLOW_HOSTS" in problem["detail"]
    r = await idle.post(
        FOURBAR_URL, json={"inputs": {**FOURBAR, "lengths": {"href": "http://127.0.0.1:9/l"}}}
    )
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == "inputs.lengths.href"
    listing = (await idle.get("/ogc/jobs")).json()
    assert all(j["status"] for j in listing["jobs"])  # nothing was queued by the refusals


async def test_links_follow_a_trusted_proxy_only(idle: httpx.AsyncClient) -> None:
    headers = {
        "X-Forwarded-Proto": "https",
        "X-Forwarded-Host": "dexlab.example.org",
        "X-Forwarded-Prefix": "/kinematics",
        "X-Forwarded-For": "203.0.113.7",
    }
    r = await idle.post(FOURBAR_URL, json={"inputs": FOURBAR, "reuse": False}, headers=headers)
    job_id = r.json()["jobID"]
    public = f"https://dexlab.example.org/kinematics/ogc/jobs/{job_id}"
    assert r.headers["location"] == public and r.json()["links"][0]["href"] == public
    landing = (await idle.get("/ogc/", headers=headers)).json()
    rels = {link["rel"]: link["href"] for link in landing["links"]}
    assert rels["service-desc"] == "https://dexlab.example.org/kinematics/openapi.json"
    page = (await idle.get("/ogc/", params={"f": "html"}, headers=headers)).text
    assert 'href="https://dexlab.example.org/kinematics/ogc/conformance"' in page
    app = idle.app  # type: ignore[attr-defined]
    outsider = httpx.ASGITransport(app=app, client=("198.51.100.7", 4444))
    async with httpx.AsyncClient(transport=outsider, base_url="http://dexlab.test") as c:
        r = await c.get(f"/ogc/jobs/{job_id}", headers=headers)
        assert r.json()["links"][0]["href"] == f"http://dexlab.test/ogc/jobs/{job_id}"
