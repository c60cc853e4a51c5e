"""The HTTP API over httpx's ASGI transport, with the real store and a real pool process."""

from __future__ import annotations

import asyncio
import json
import time
from typing import Any

import httpx
import pytest

pytestmark = [pytest.mark.integration, pytest.mark.anyio]

SMALL_MAP = {"links": [15, 14, 8], "grid": {"points_per_axis": 21}}
PROBLEM = "application/problem+json"


async def poll(client: httpx.AsyncClient, job_id: str, timeout: float = 90) -> dict[str, Any]:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        doc: dict[str, Any] = (await client.get(f"/v1/jobs/{job_id}")).json()
        if doc["status"] in {"successful", "failed", "dismissed"}:
            return doc
        await asyncio.sleep(0.1)
    raise AssertionError(f"job {job_id} did not finish")


async def test_processes_are_described_with_schema_examples_and_limits(
    asgi_client: httpx.AsyncClient,
) -> None:
    listing = (await asgi_client.get("/v1/processes")).json()
    ids = [p["id"] for p in listing["processes"]]
    assert {"planar3r-dexterity-map", "planar3r-synthesis"} <= set(ids)
    doc = (await asgi_client.get("/v1/processes/planar3r-dexterity-map")).json()
    assert doc["inputs"]["properties"]["links"]
    assert doc["inputs"]["additionalProperties"] is False
    assert doc["examples"] and doc["examples"][0]["inputs"]
    assert doc["limits"]["cost_limit"] > 0 and "orientation" in doc["limits"]["cost_unit"]
    assert doc["outputs"]


async def test_every_worked_example_validates(asgi_client: httpx.AsyncClient) -> None:
    """The examples a user copies from the description are accepted as they are."""
    for pid in ("planar3r-dexterity-map", "planar3r-synthesis"):
        doc = (await asgi_client.get(f"/v1/processes/{pid}")).json()
        for example in doc["examples"]:
            r = await asgi_client.post(
                f"/v1/processes/{pid}/execution", json={"inputs": example["inputs"]}
            )
            assert r.status_code == 201, (pid, example["title"], r.text)
            await asgi_client.delete(r.headers["Location"])


async def test_submit_poll_results_and_artifacts(asgi_client: httpx.AsyncClient) -> None:
    r = await asgi_client.post(
        "/v1/processes/planar3r-dexterity-map/execution", json={"inputs": SMALL_MAP}
    )
    assert r.status_code == 201, r.text
    job_id = r.json()["jobID"]
    assert r.headers["Location"] == f"/v1/jobs/{job_id}"
    assert r.json()["status"] in {"accepted", "running"}
    status = await poll(asgi_client, job_id)
    assert status["status"] == "successful", status
    assert status["progress"] == 100 and status["finished"] and status["started"]
    results = (await asgi_client.get(f"/v1/jobs/{job_id}/results")).json()
    assert results["jobID"] == job_id
    assert results["result"]["method"] == "exact-closed-form"
    names = {a["name"]: a for a in results["artifacts"]}
    assert {"heatmap.png", "heatmap.svg", "dexterity_map.csv", "dexterity_map.npz"} <= set(names)
    png = await asgi_client.get(names["heatmap.png"]["href"])
    assert png.status_code == 200 and png.headers["content-type"] == "image/png"
    assert png.content.startswith(b"\x89PNG")
    csv = await asgi_client.get(names["dexterity_map.csv"]["href"])
    assert csv.headers["content-type"].startswith("text/csv")
    assert len(csv.text.strip().splitlines()) == 1 + 21 * 21
    missing = await asgi_client.get(f"/v1/jobs/{job_id}/results/nope.png")
    assert missing.status_code == 404 and missing.headers["content-type"] == PROBLEM


async def test_invalid_inputs_name_the_field(asgi_client: httpx.AsyncClient) -> None:
    cases = [
        ({"links": [15, -14, 8]}, "inputs.links[1]"),
        ({"links": [15, 14]}, "inputs.links"),
        ({"links": [15, 14, 8], "colour": "red"}, "inputs.colour"),
        ({"links": [15, 14, 8], "grid": {"points_per_axis": 5000}}, "inputs.grid.points_per_axis"),
        (
            {"links": [15, 14, 8], "joint_limits_deg": [[0, 10], [20, 10], [0, 1]]},
            "inputs.joint_limits_deg",
        ),
    ]
    for inputs, field in cases:
        r = await asgi_client.post(
            "/v1/processes/planar3r-dexterity-map/execution", json={"inputs": inputs}
        )
        assert r.status_code == 422, (inputs, r.text)
        assert r.headers["content-type"] == PROBLEM
        body = r.json()
        assert body["type"].endswith("/invalid-inputs") and body["status"] == 422
        fields = [e["field"] for e in body["errors"]]
        assert any(f.startswith(field) for f in fields), (inputs, fields)
        assert field.split("[")[0] in body["detail"]
    listing = (await asgi_client.get("/v1/jobs")).json()
    assert listing["jobs"] == []  # nothing was queued


@pytest.mark.parametrize(
    ("process_id", "inputs"),
    [
        ("planar3r-dexterity-map", {"links": [15, 14, 8]}),
        ("planar3r-synthesis", {"l3": 8, "task_points": [[12, 8]]}),
        ("planar3r-design", {"task_points": [[12, 8]], "total_length_max": 37}),
        ("design-study", None),
    ],
)
async def test_joint_limits_in_radians_are_refused(
    asgi_client: httpx.AsyncClient, process_id: str, inputs: dict[str, Any] | None
) -> None:
    """Issue 26: [[-2.618, 2.618], ...] was a successful job with an all-grey map."""
    radians = [[-2.618, 2.618], [-2.618, 2.618], [-3.054, 3.054]]
    if inputs is None:  # a study forwarding them to the map
        body = {"process": "planar3r-dexterity-map", "vary": {"links[2]": [6, 10, 3]},
                "fixed": {"links": [15, 14, 8], "joint_limits_deg": radians,
                          "task_points": [[14, 14]], "grid": {"points_per_axis": 5}},
                "objectives": {"task_points[].d_z|min": "max"}}  # fmt: skip
        field = "inputs.fixed.joint_limits_deg"
    else:
        body, field = {**inputs, "joint_limits_deg": radians}, "inputs.joint_limits_deg"
    r = await asgi_client.post(f"/v1/processes/{process_id}/execution", json={"inputs": body})
    assert r.status_code == 422, r.text
    assert r.headers["content-type"] == PROBLEM
    errors = r.json()["errors"]
    assert [e["field"] for e in errors] == [field]
    assert "degrees expected; these look like radians" in errors[0]["message"]
    assert (await asgi_client.get("/v1/jobs")).json()["jobs"] == []


async def test_malformed_body_is_a_problem(asgi_client: httpx.AsyncClient) -> None:
    r = await asgi_client.post(
        "/v1/processes/planar3r-dexterity-map/execution", json={"links": [1, 2, 3]}
    )
    assert r.status_code == 422 and r.headers["content-type"] == PROBLEM
    assert {e["field"] for e in r.json()["errors"]} >= {"inputs", "links"}
    r = await asgi_client.post(
        "/v1/processes/planar3r-dexterity-map/execution",
        content=b"{not json",
        headers={"content-type": "application/json"},
    )
    assert r.status_code == 400 and r.headers["content-type"] == PROBLEM
    assert r.json()["type"] == "/problems/malformed-request"
    assert "line 1 column 2" in r.json()["detail"]


async def test_cost_limit_refuses_before_queuing(asgi_client: httpx.AsyncClient) -> None:
    inputs = {
        "links": [15, 14, 8],
        "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
        "grid": {"points_per_axis": 2001},
        "orientation_step_deg": 0.1,
        "method": "orientation-sampling",
    }
    r = await asgi_client.post(
        "/v1/processes/planar3r-dexterity-map/execution", json={"inputs": inputs}
    )
    assert r.status_code == 422 and r.headers["content-type"] == PROBLEM
    body = r.json()
    assert body["type"].endswith("/cost-limit-exceeded")
    assert body["cost"] == 2001 * 2001 * 3600 and body["cost"] > body["cost_limit"]
    assert (await asgi_client.get("/v1/jobs")).json()["jobs"] == []


async def test_idempotency_key(asgi_client: httpx.AsyncClient) -> None:
    url = "/v1/processes/planar3r-dexterity-map/execution"
    headers = {"Idempotency-Key": "design-42"}
    first = await asgi_client.post(url, json={"inputs": SMALL_MAP}, headers=headers)
    again = await asgi_client.post(url, json={"inputs": SMALL_MAP}, headers=headers)
    assert first.status_code == 201 and again.status_code == 201
    assert first.json()["jobID"] == again.json()["jobID"]
    assert again.headers["Idempotent-Replayed"] == "true"
    other = {**SMALL_MAP, "links": [15, 14, 9]}
    conflict = await asgi_client.post(url, json={"inputs": other}, headers=headers)
    assert conflict.status_code == 422
    assert conflict.json()["type"].endswith("/idempotency-conflict")
    jobs = (await asgi_client.get("/v1/jobs")).json()["jobs"]
    assert len(jobs) == 1


async def test_unknown_things_are_404_problems(asgi_client: httpx.AsyncClient) -> None:
    for path, kind in [
        ("/v1/processes/nope", "no-such-process"),
        ("/v1/jobs/nope", "no-such-job"),
        ("/v1/jobs/nope/results", "no-such-job"),
        ("/v1/nothing-here", "not-found"),
    ]:
        r = await asgi_client.get(path)
        assert r.status_code == 404 and r.headers["content-type"] == PROBLEM, path
        assert r.json()["type"].endswith(kind), (path, r.json())
    r = await asgi_client.post("/v1/processes/nope/execution", json={"inputs": {}})
    assert r.status_code == 404 and r.json()["type"].endswith("no-such-process")
    r = await asgi_client.delete("/v1/jobs/nope")
    assert r.status_code == 404


async def test_results_not_ready_while_pending(asgi_client: httpx.AsyncClient) -> None:
    # Two jobs: the second waits behind the first in a one-process pool.
    url = "/v1/processes/planar3r-dexterity-map/execution"
    slow = {
        "links": [15, 14, 8],
        "grid": {"points_per_axis": 101},
        "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
        "orientation_step_deg": 2,
        "method": "orientation-sampling",
    }
    first = (await asgi_client.post(url, json={"inputs": slow})).json()["jobID"]
    second = (await asgi_client.post(url, json={"inputs": SMALL_MAP})).json()["jobID"]
    r = await asgi_client.get(f"/v1/jobs/{second}/results")
    assert r.status_code == 404 and r.json()["type"].endswith("/result-not-ready")
    # Dismissing a queued job: it never runs and has no results.
    d = await asgi_client.delete(f"/v1/jobs/{second}")
    assert d.status_code == 200 and d.json()["status"] == "dismissed"
    gone = await asgi_client.get(f"/v1/jobs/{second}/results")
    assert gone.status_code == 410 and gone.json()["type"].endswith("/job-dismissed")
    assert (await poll(asgi_client, first))["status"] == "successful"
    assert (await asgi_client.get(f"/v1/jobs/{second}")).json()["status"] == "dismissed"


async def test_listing_paginates_and_filters(asgi_client: httpx.AsyncClient) -> None:
    url = "/v1/processes/planar3r-dexterity-map/execution"
    ids = []
    for n in range(5):
        inputs = {**SMALL_MAP, "links": [15, 14, 8 + n]}
        ids.append((await asgi_client.post(url, json={"inputs": inputs})).json()["jobID"])
    page = (await asgi_client.get("/v1/jobs", params={"limit": 2})).json()
    assert [j["jobID"] for j in page["jobs"]] == ids[::-1][:2]
    seen = [j["jobID"] for j in page["jobs"]]
    while page["next_cursor"]:
        page = (
            await asgi_client.get("/v1/jobs", params={"limit": 2, "cursor": page["next_cursor"]})
        ).json()
        seen += [j["jobID"] for j in page["jobs"]]
    assert seen == ids[::-1]
    none = (await asgi_client.get("/v1/jobs", params={"processID": "planar3r-synthesis"})).json()
    assert none["jobs"] == []
    bad = await asgi_client.get("/v1/jobs", params={"status": "sleeping"})
    assert bad.status_code == 422 and bad.json()["errors"][0]["field"] == "query.status"
    bad = await asgi_client.get("/v1/jobs", params={"cursor": "garbage"})
    assert bad.status_code == 422 and bad.json()["type"] == "/problems/invalid-request"
    assert bad.json()["errors"][0]["field"] == "query.cursor"


async def test_health_and_docs(asgi_client: httpx.AsyncClient) -> None:
    assert (await asgi_client.get("/health/live")).json()["status"] == "live"
    deadline = time.monotonic() + 60
    while True:
        ready = await asgi_client.get("/health/ready")
        if ready.status_code == 200 or time.monotonic() > deadline:
            break
        await asyncio.sleep(0.2)
    assert ready.status_code == 200, ready.text
    assert ready.json()["live_workers"] >= 1
    assert (await asgi_client.get("/docs")).status_code == 200
    spec = (await asgi_client.get("/openapi.json")).json()
    assert "/v1/processes/{process_id}/execution" in spec["paths"]


async def test_prefer_wait_answers_small_jobs_synchronously(
    asgi_client: httpx.AsyncClient,
) -> None:
    url = "/v1/processes/planar3r-dexterity-map/execution"
    doc = (await asgi_client.get("/v1/processes/planar3r-dexterity-map")).json()
    assert "sync-execute" in doc["jobControlOptions"]
    assert doc["limits"]["sync_cost_limit"] >= 21 * 21
    r = await asgi_client.post(url, json={"inputs": SMALL_MAP}, headers={"Prefer": "wait=60"})
    assert r.status_code == 200, r.text
    assert r.headers["Preference-Applied"] == "wait=60"
    job_id = r.json()["jobID"]
    assert r.headers["Location"] == f"/v1/jobs/{job_id}"
    assert r.json()["result"]["method"] == "exact-closed-form"
    assert any(a["name"] == "heatmap.png" for a in r.json()["artifacts"])
    # The same job stays retrievable like any other.
    assert (await asgi_client.get(f"/v1/jobs/{job_id}")).json()["status"] == "successful"
    # respond-async wins; work above the synchronous limit is queued as usual.
    r = await asgi_client.post(
        url, json={"inputs": SMALL_MAP}, headers={"Prefer": "respond-async, wait=60"}
    )
    assert r.status_code == 201
    big = {"links": [15, 14, 8], "grid": {"points_per_axis": 401}}
    r = await asgi_client.post(url, json={"inputs": big}, headers={"Prefer": "wait=5"})
    assert r.status_code == 201 and "Preference-Applied" not in r.headers


async def test_invalid_chains_are_422_naming_the_loop_or_link(
    asgi_client: httpx.AsyncClient,
) -> None:
    """Open loops, unknown links, chains of different mobility and four-bars that cannot
    close are refused with a problem document naming the loop or link, and nothing runs."""
    doc = (await asgi_client.get("/v1/processes/chain-parallelism")).json()
    fig4 = doc["examples"][2]["inputs"]  # Fig 4a against Fig 4b

    def broken(edit: Any) -> dict[str, Any]:
        inputs = json.loads(json.dumps(fig4))
        edit(inputs["chains"])
        return inputs

    def open_loop(chains: list[Any]) -> None:
        chains[0]["loops"][1] = ["1.b", "4.b", "5", "6"]  # link 7 left out: no closure

    def unknown_link(chains: list[Any]) -> None:
        chains[1]["loops"][2][5] = "9"

    def other_mobility(chains: list[Any]) -> None:
        chains.append({"name": "quad", "lengths": [18, 15, 10, 17]})

    cases = [
        ("chain-parallelism", broken(open_loop), "inputs.chains[0].loops[1]", "does not close"),
        ("chain-parallelism", broken(unknown_link), "inputs.chains[1].loops[2]", "'9'"),
        ("chain-parallelism", broken(other_mobility), "inputs.chains", "degrees of freedom"),
        ("fourbar-grashof", {"lengths": [1, 1, 1, 10], "ground": 0}, "inputs.lengths", "close"),
    ]
    for process_id, inputs, field, words in cases:
        r = await asgi_client.post(
            f"/v1/processes/{process_id}/execution",
            json={"inputs": inputs},
            headers={"Prefer": "wait=10"},
        )
        assert r.status_code == 422, (field, r.text)
        assert r.headers["content-type"] == PROBLEM
        body = r.json()
        assert body["type"].endswith("/invalid-inputs")
        matching = [e for e in body["errors"] if e["field"].startswith(field)]
        assert matching, (field, body["errors"])
        assert any(words in e["message"] for e in matching), (words, matching)
    assert (await asgi_client.get("/v1/jobs")).json()["jobs"] == []
