"""``POST /v1/processes/{processID}/preview`` and the live explorer's page over the
real app (ASGI, embedded, no workers): the arrays each explorer draws, the same 422 as
a submission, the cost refusal, no job made, keys, the submit rate and the session's
CSRF-checked twin."""

from __future__ import annotations

import math
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from pathlib import Path
from typing import Any

import httpx
import pytest

from service.app import create_app
from service.config import Settings
from worker.registry import default_registry

pytestmark = [pytest.mark.integration, pytest.mark.anyio]

KEY = "preview-key-secret-5a1f0c"
BEARER = {"Authorization": f"Bearer {KEY}"}
SAME_ORIGIN = {"Origin": "http://dexlab.test"}
PREVIEWED = ("spm-conditioning-map", "planar3r-dexterity-map", "planar2dof-conditioning-map")


@pytest.fixture
def anyio_backend() -> str:
    return "asyncio"


@asynccontextmanager
async def serve(tmp_path: Path, **settings: Any) -> AsyncIterator[httpx.AsyncClient]:
    app = create_app(Settings(data_dir=tmp_path, workers=0, **settings))
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://dexlab.test") as c:
            yield c


@pytest.fixture
async def client(tmp_path: Path) -> AsyncIterator[httpx.AsyncClient]:
    async with serve(tmp_path) as c:
        yield c


def start_inputs(process_id: str) -> dict[str, Any]:
    definition = default_registry().require(process_id)
    assert definition.preview is not None
    preview = definition.preview
    return preview.start_inputs(definition.examples[preview.start_example].inputs)


@pytest.mark.parametrize("process_id", PREVIEWED)
async def test_a_preview_answers_the_maps_and_indices_and_stores_nothing(
    client: httpx.AsyncClient, process_id: str
) -> None:
    r = await client.post(f"/v1/processes/{process_id}/preview",
                          json={"inputs": start_inputs(process_id)})  # fmt: skip
    assert r.status_code == 200, r.text
    doc = r.json()
    assert doc["process_id"] == process_id
    assert doc["cost"] <= doc["cost_limit"]
    assert doc["maps"] and doc["indices"]
    for heat_map in doc["maps"]:
        assert len(heat_map["z"]) == len(heat_map["y"])
        assert all(len(row) == len(heat_map["x"]) for row in heat_map["z"])
        values = [v for row in heat_map["z"] for v in row if v is not None]
        assert values and all(math.isfinite(v) for v in values)
        assert heat_map["x_unit"] and heat_map["y_unit"]
    jobs = (await client.get("/v1/jobs")).json()
    assert jobs["jobs"] == []


async def test_the_3r_preview_moves_with_its_links(client: httpx.AsyncClient) -> None:
    """A longer last link changes the map: the preview computes, it does not replay."""
    inputs = start_inputs("planar3r-dexterity-map")
    first = (await client.post("/v1/processes/planar3r-dexterity-map/preview",
                               json={"inputs": inputs})).json()  # fmt: skip
    inputs["links"] = [15.0, 14.0, 12.0]
    second = (await client.post("/v1/processes/planar3r-dexterity-map/preview",
                                json={"inputs": inputs})).json()  # fmt: skip
    assert first["maps"][0]["x"][-1] < second["maps"][0]["x"][-1]  # the reach grew
    assert "(15, 14, 12)" in second["maps"][0]["title"]


async def test_a_bad_field_is_the_submission_422_naming_it(client: httpx.AsyncClient) -> None:
    inputs = {**start_inputs("spm-conditioning-map"), "alpha1_deg": 500}
    r = await client.post("/v1/processes/spm-conditioning-map/preview", json={"inputs": inputs})
    assert r.status_code == 422
    problem = r.json()
    assert problem["type"].endswith("/invalid-inputs")
    assert [e["field"] for e in problem["errors"]] == ["inputs.alpha1_deg"]
    same = await client.post("/v1/processes/spm-conditioning-map/execution",
                             json={"inputs": inputs})  # fmt: skip
    assert same.status_code == 422 and same.json()["errors"] == problem["errors"]


async def test_a_preview_above_its_cost_limit_is_refused_naming_the_cost(
    client: httpx.AsyncClient,
) -> None:
    inputs = {**start_inputs("planar3r-dexterity-map"), "grid": {"points_per_axis": 401}}
    r = await client.post("/v1/processes/planar3r-dexterity-map/preview", json={"inputs": inputs})
    assert r.status_code == 422
    problem = r.json()
    assert problem["type"].endswith("/cost-limit-exceeded")
    assert problem["cost"] > problem["cost_limit"]
    assert f"{problem['cost']:,}" in problem["detail"]
    assert (await client.get("/v1/jobs")).json()["jobs"] == []


async def test_a_process_without_a_preview_is_404(client: httpx.AsyncClient) -> None:
    r = await client.post("/v1/processes/fourbar-grashof/preview",
                          json={"inputs": {"lengths": [2, 7, 9, 6]}})  # fmt: skip
    assert r.status_code == 404
    assert "has no preview" in r.json()["detail"]
    assert (await client.post("/v1/processes/nope/preview", json={"inputs": {}})).status_code == 404


async def test_the_preview_is_in_the_openapi_document(client: httpx.AsyncClient) -> None:
    document = (await client.get("/openapi.json")).json()
    operation = document["paths"]["/v1/processes/{process_id}/preview"]["post"]
    schema = operation["responses"]["200"]["content"]["application/json"]["schema"]
    assert schema["$ref"].endswith("/PreviewDocument")
    assert {"maps", "indices", "cost"} <= set(
        document["components"]["schemas"]["PreviewDocument"]["properties"]
    )


async def test_keys_and_the_submit_rate_apply(tmp_path: Path) -> None:
    async with serve(tmp_path, api_keys=f"alice:{KEY}", submit_rate_per_min=2) as client:
        url = "/v1/processes/planar3r-dexterity-map/preview"
        body = {"inputs": start_inputs("planar3r-dexterity-map")}
        assert (await client.post(url, json=body)).status_code == 401
        answers = [(await client.post(url, json=body, headers=BEARER)).status_code
                   for _ in range(3)]  # fmt: skip
        assert answers == [200, 200, 429]
        limited = await client.post(url, json=body, headers=BEARER)
        assert limited.json()["limit"] == "DEXLAB_SUBMIT_RATE_PER_MIN"
        assert int(limited.headers["Retry-After"]) >= 1


async def test_the_page_twin_needs_the_session_csrf_token(tmp_path: Path) -> None:
    secret = "session-secret-for-tests-0123456789abcdef"
    async with serve(tmp_path, api_keys=f"alice:{KEY}", session_secret=secret) as client:
        login = await client.post("/login", data={"key": KEY, "next": "/v1/jobs"},
                                  headers=SAME_ORIGIN)  # fmt: skip
        assert login.status_code == 303
        body = {"inputs": start_inputs("planar2dof-conditioning-map")}
        # a session may not write through the JSON API
        api = await client.post("/v1/processes/planar2dof-conditioning-map/preview", json=body)
        assert api.status_code in (401, 403)
        page = await client.get("/pages/processes/planar2dof-conditioning-map/explore",
                                headers={"Accept": "text/html"})  # fmt: skip
        token = _csrf(page.text)
        url = "/pages/processes/planar2dof-conditioning-map/preview"
        refused = await client.post(url, json=body, headers=SAME_ORIGIN)
        assert refused.status_code == 403
        r = await client.post(url, json=body, headers={**SAME_ORIGIN, "X-CSRF-Token": token})
        assert r.status_code == 200, r.text
        assert [m["z_label"] for m in r.json()["maps"]] == ["1/κ", "β_min"]


def _csrf(html: str) -> str:
    marker = 'name="csrf_token" value="'
    start = html.index(marker) + len(marker)
    return html[start : html.index('"', start)]


@pytest.mark.parametrize("process_id", PREVIEWED)
async def test_the_explorer_page_has_a_slider_per_design_field(
    client: httpx.AsyncClient, process_id: str
) -> None:
    page = await client.get(f"/pages/processes/{process_id}/explore")
    assert page.status_code == 200
    html = page.text
    definition = default_registry().require(process_id)
    assert definition.preview is not None
    for field in definition.preview.fields:
        assert 'type="range" id="field-' in html and f'data-path="{field.path}"' in html
    assert "needs JavaScript" in html and f'href="/v1/processes/{process_id}#examples"' in html
    assert "style=" not in html.replace("stylesheet", "")
    assert page.headers["Content-Security-Policy"].startswith("default-src 'self'")
    process_page = await client.get(f"/v1/processes/{process_id}", headers={"Accept": "text/html"})
    assert f'href="/pages/processes/{process_id}/explore"' in process_page.text


async def test_a_process_without_a_preview_has_no_explorer(client: httpx.AsyncClient) -> None:
    assert (await client.get("/pages/processes/fourbar-grashof/explore")).status_code == 404
    page = await client.get("/v1/processes/fourbar-grashof", headers={"Accept": "text/html"})
    assert "/explore" not in page.text
