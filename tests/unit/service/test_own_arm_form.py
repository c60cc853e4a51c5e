"""The "Your own arm" form on a serial process's page: a DH table or a URDF pasted as
text becomes the job's ``robot``; one that cannot be read comes back on the same form
with its problem and the user's text (over ASGI, the real app)."""

from __future__ import annotations

import html
import json

import httpx
import pytest

from worker.families.serial.arms import UR5_URDF

pytestmark = pytest.mark.anyio

PAGE = "/v1/processes/serial-indices"
RUN = "/pages/processes/serial-indices/run"
HTML = {"Accept": "text/html"}
SAME_ORIGIN = {"Origin": "http://dexlab.test"}
TABLE = "\n".join(["a alpha_deg d", "0 90 0.089459", "-0.425 0 0", "-0.39225 0 0",
                   "0 90 0.10915", "0 -90 0.09465", "0 0 0.0823"])  # fmt: skip
OTHERS = json.dumps({"configurations": [[0, -90, 90, 0, 90, 0]], "plots": False})


async def test_the_page_offers_the_form_with_a_worked_example_table(
    client: httpx.AsyncClient,
) -> None:
    page = (await client.get(PAGE, headers=HTML)).text
    assert 'id="own-arm"' in page and 'name="robot_text"' in page
    text = html.unescape(
        page.split('name="robot_text"', 1)[1].split(">", 1)[1].split("</textarea>")[0]
    )
    assert text.splitlines()[0].split() == ["a", "alpha_deg", "d", "theta_deg", "type"]
    assert len(text.splitlines()) == 7  # the UR5's six joints
    fourbar = (await client.get("/v1/processes/fourbar-grashof", headers=HTML)).text
    assert 'id="own-arm"' not in fourbar


async def test_a_pasted_table_or_urdf_runs_as_the_jobs_robot(client: httpx.AsyncClient) -> None:
    forms = [
        {"robot_kind": "dh", "robot_text": TABLE, "convention": "standard", "inputs": OTHERS},
        {"robot_kind": "urdf", "robot_text": UR5_URDF["urdf"], "base_link": "base_link",
         "tip_link": "tool0", "inputs": OTHERS},
    ]  # fmt: skip
    for form, stored in zip(forms, ('"a": -0.425', '"tip_link": "tool0"'), strict=True):
        done = await client.post(RUN, data=form, headers=SAME_ORIGIN)
        assert done.status_code == 303, done.text
        job = (await client.get(done.headers["location"])).json()
        assert job["status"] == "accepted"
        edit = await client.get(f"/pages/jobs/{job['jobID']}/edit", headers=HTML)
        assert stored in html.unescape(edit.text)  # the job's inputs: the table's rows


async def test_a_bad_table_comes_back_on_its_form_with_the_line(client: httpx.AsyncClient) -> None:
    bad = TABLE.replace("-0.425", "x")
    form = {"robot_kind": "dh", "robot_text": bad, "convention": "standard", "inputs": OTHERS}
    page = await client.post(RUN, data=form, headers=SAME_ORIGIN)
    assert page.status_code == 422
    section = page.text.split('id="own-arm"', 1)[1].split("</form>", 1)[0]
    assert "robot.dh_table" in section and "line 3" in section
    assert html.escape(bad, quote=False) in section  # the user's text kept
    missing = {"robot_kind": "urdf", "robot_text": UR5_URDF["urdf"], "inputs": OTHERS}
    page = await client.post(RUN, data=missing, headers=SAME_ORIGIN)
    assert page.status_code == 422 and "robot.base_link" in page.text
