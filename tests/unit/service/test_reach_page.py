"""``serial-reach`` on the pages: its process page offers the "Your own arm" form, and a
pasted DH table with targets runs as a job (over ASGI, the real app)."""

from __future__ import annotations

import json

import httpx
import pytest

pytestmark = pytest.mark.anyio

HTML = {"Accept": "text/html"}
SAME_ORIGIN = {"Origin": "http://dexlab.test"}


async def test_a_pasted_planar_table_and_its_targets_run(client: httpx.AsyncClient) -> None:
    page = (await client.get("/v1/processes/serial-reach", headers=HTML)).text
    assert 'id="own-arm"' in page and 'name="robot_text"' in page
    targets = [{"position": [14, 14]}, {"position": [40, 0]}]
    form = {
        "robot_kind": "dh",
        "robot_text": "a alpha_deg d\n15 0 0\n14 0 0\n8 0 0",
        "convention": "standard",
        "inputs": json.dumps({"targets": targets, "length_unit": "units", "plots": False}),
    }
    done = await client.post("/pages/processes/serial-reach/run", data=form,
                             headers=SAME_ORIGIN)  # fmt: skip
    assert done.status_code == 303, done.text
    job = (await client.get(done.headers["location"])).json()
    assert job["status"] == "accepted"
