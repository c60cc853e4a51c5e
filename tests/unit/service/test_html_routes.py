"""Pages and JSON documents at the same URLs, each through its own route.

A request that asks for HTML (``?f=html``, or an ``Accept`` ranking ``text/html``
above JSON) reaches the page route; any other reaches the JSON route.  Both answers
say ``Vary: Accept``; a parameter error is the surface's problem either way.
"""

from __future__ import annotations

import httpx
import pytest

pytestmark = pytest.mark.anyio

BROWSER = "text/html,application/xhtml+xml,application/xml;q=0.9,*/*;q=0.8"

NEGOTIATED = [
    "/",
    "/v1",
    "/v1/processes",
    "/v1/processes/planar3r-dexterity-map",
    "/v1/jobs",
    "/ogc",
    "/ogc/",
    "/ogc/conformance",
    "/ogc/processes",
    "/ogc/processes/planar3r-dexterity-map",
    "/ogc/jobs",
]


def _kind(response: httpx.Response) -> str:
    return response.headers["content-type"].split(";")[0]


@pytest.mark.parametrize("path", NEGOTIATED)
async def test_each_url_answers_json_or_a_page_as_asked(
    client: httpx.AsyncClient, path: str
) -> None:
    asked = {
        "no accept": ({}, {}, "application/json"),
        "a browser": ({"accept": BROWSER}, {}, "text/html"),
        "f=html": ({}, {"f": "html"}, "text/html"),
        "f=json beats a browser": ({"accept": BROWSER}, {"f": "json"}, "application/json"),
        "json preferred": ({"accept": "application/json, text/html;q=0.5"}, {}, "application/json"),
    }
    for label, (headers, params, kind) in asked.items():
        response = await client.get(path, headers=headers, params=params)
        assert response.status_code == 200, (path, label)
        assert _kind(response) == kind, (path, label)
        assert "Accept" in response.headers["vary"], (path, label)
        if kind == "application/json":
            assert isinstance(response.json(), dict)
        else:
            assert response.text.lstrip().lower().startswith("<!doctype html")


async def test_a_job_and_its_results_answer_both_ways(client: httpx.AsyncClient) -> None:
    described = await client.get("/v1/processes/planar3r-dexterity-map")
    inputs = described.json()["examples"][0]["inputs"]
    created = await client.post(
        "/v1/processes/planar3r-dexterity-map/execution", json={"inputs": inputs}
    )
    assert created.status_code == 201
    job_id = created.json()["jobID"]
    for path in (f"/v1/jobs/{job_id}", f"/ogc/jobs/{job_id}"):
        document = await client.get(path)
        assert _kind(document) == "application/json" and document.json()["jobID"] == job_id
        page = await client.get(path, headers={"accept": BROWSER})
        assert _kind(page) == "text/html" and job_id in page.text
        assert "Accept" in document.headers["vary"] and "Accept" in page.headers["vary"]
    # Not finished: JSON says why there are no results; the page is the job's page.
    results = await client.get(f"/v1/jobs/{job_id}/results")
    assert results.status_code == 404 and results.json()["type"].endswith("/result-not-ready")
    page = await client.get(f"/v1/jobs/{job_id}/results", params={"f": "html"})
    assert page.status_code == 200 and job_id in page.text


@pytest.mark.parametrize(("path", "status"), [("/v1/jobs", 422), ("/ogc/jobs", 400)])
async def test_a_bad_parameter_is_the_surfaces_problem_as_json_or_a_page(
    client: httpx.AsyncClient, path: str, status: int
) -> None:
    as_json = await client.get(path, params={"limit": "0"})
    assert as_json.status_code == status
    assert as_json.json()["errors"][0]["field"] == "query.limit"
    as_page = await client.get(path, params={"limit": "0", "f": "html"})
    assert as_page.status_code == status and _kind(as_page) == "text/html"
