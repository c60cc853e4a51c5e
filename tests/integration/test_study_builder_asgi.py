"""The study builder on the design-study page over the real app (ASGI, embedded
backend): each GET step, the final POST that runs a study, and refusals on the form."""

from __future__ import annotations

import re
from urllib.parse import urlencode

import httpx
import pytest

from tests.integration.test_api_asgi import poll
from worker.registry import default_registry
from worker.studies.builder import studied_processes

pytestmark = [pytest.mark.integration, pytest.mark.anyio]

PAGE = {"Accept": "text/html"}
SAME_ORIGIN = {"Origin": "http://dexlab.test"}
STUDY_PAGE = "/v1/processes/design-study"
BUILD = "/pages/processes/design-study/build"
#: Bai's Table 1 example varied in alpha1 only: three designs.
SPM = {"process": "spm-conditioning-map", "example": "0"}
OBJECTIVE = "indices.rms_inverse_condition"


@pytest.fixture
def backend() -> str:
    return "embedded"


def tiny_study(**changes: str) -> dict[str, str]:
    form = {
        **SPM,
        "step": "objectives",
        "design": "grid",
        "vary.alpha1_deg": "on",
        "from.alpha1_deg": "50",
        "to.alpha1_deg": "70",
        "count.alpha1_deg": "3",
        f"objective.{OBJECTIVE}": "on",
        f"goal.{OBJECTIVE}": "max",
    }
    form.update(changes)
    return form


async def step(client: httpx.AsyncClient, **params: str) -> str:
    r = await client.get(f"{STUDY_PAGE}?{urlencode(params)}", headers=PAGE)
    assert r.status_code == 200, r.text
    return r.text


async def test_step_one_lists_every_process_a_study_can_run(
    asgi_client: httpx.AsyncClient,
) -> None:
    html = await step(asgi_client)
    assert 'id="builder-step-1"' in html and 'id="builder-step-2"' not in html
    offered = re.findall(r'<option value="([a-z0-9-]+)"', html.split('id="builder-step-1"')[1])
    assert offered == [d.id for d in studied_processes(default_registry())]
    assert "design-study" not in offered
    assert "study-builder.js" in html


async def test_step_two_offers_the_processes_worked_examples(
    asgi_client: httpx.AsyncClient,
) -> None:
    html = await step(asgi_client, process="spm-conditioning-map")
    definition = default_registry().require("spm-conditioning-map")
    step_two = html.split('id="builder-step-2"')[1].split("</form>")[0]
    for example in definition.examples:
        assert example.title in step_two.replace("&#39;", "'")
    assert 'id="builder-step-3"' not in html


async def test_step_three_offers_the_examples_numbers_with_units(
    asgi_client: httpx.AsyncClient,
) -> None:
    html = await step(asgi_client, **SPM)
    step_three = html.split('id="builder-step-3"')[1].split("</form>")[0]
    assert 'name="vary.alpha1_deg"' in step_three
    assert 'name="from.workspace.torsion_deg[1]"' in step_three
    row = step_three.split('name="vary.alpha1_deg"')[1].split("</tr>")[0]
    assert "<td>60</td>" in row and "<td>deg</td>" in row
    assert 'id="builder-step-4"' not in html


async def test_step_four_lists_result_paths_and_keeps_the_chosen_ranges(
    asgi_client: httpx.AsyncClient,
) -> None:
    html = await step(asgi_client, **tiny_study())
    form = html.split('id="builder-step-4"')[1].split("</form>")[0]
    assert 'method="post"' in html.split('id="builder-step-4"')[0][-200:]
    assert 'name="from.alpha1_deg" value="50"' in form  # step 3 carried on, hidden
    assert 'name="from.alpha2_deg"' not in form  # an input not varied is not
    definition = default_registry().require("spm-conditioning-map")
    for entry in definition.result_paths:
        if "*" not in entry.path:
            assert f'name="objective.{entry.path}"' in form
    listed = next(e.path for e in definition.result_paths if "[]" in e.path)
    assert f'name="reduce.{listed}"' in form
    assert f'name="reduce.{OBJECTIVE}"' not in form  # not a list: nothing to reduce
    assert "alpha1_deg</code> from 50 to 70 (3 values) deg" in form


async def test_the_builder_runs_a_study_and_sends_the_browser_to_its_job(
    asgi_client: httpx.AsyncClient,
) -> None:
    r = await asgi_client.post(BUILD, data=tiny_study(), headers=SAME_ORIGIN)
    assert r.status_code == 303, r.text
    job_id = r.headers["location"].rsplit("/", 1)[1]
    assert (await poll(asgi_client, job_id))["status"] == "successful"
    job = (await asgi_client.get(f"/v1/jobs/{job_id}")).json()
    assert job["processID"] == "design-study"
    result = (await asgi_client.get(f"/v1/jobs/{job_id}/results")).json()["result"]
    assert result["count"] == result["evaluated"] == 3 and result["feasible"] >= 1
    alphas = sorted(d["parameters"]["alpha1_deg"] for d in result["pareto"])
    assert set(alphas) <= {50, 60, 70} and alphas


async def test_a_range_from_above_to_is_refused_at_its_field(
    asgi_client: httpx.AsyncClient,
) -> None:
    form = tiny_study(**{"from.alpha1_deg": "80"})
    r = await asgi_client.post(BUILD, data=form, headers={**SAME_ORIGIN, **PAGE})
    assert r.status_code == 422
    assert "inputs.vary.alpha1_deg" in r.text and "exceeds hi" in r.text
    assert 'name="from.alpha1_deg" value="80"' in r.text  # the choice is kept
    assert 'name="vary.alpha1_deg" value="on" checked aria-invalid="true"' in r.text


async def test_a_study_without_objectives_is_refused_at_objectives(
    asgi_client: httpx.AsyncClient,
) -> None:
    form = tiny_study()
    del form[f"objective.{OBJECTIVE}"]
    r = await asgi_client.post(BUILD, data=form, headers=SAME_ORIGIN)
    assert r.status_code == 422
    assert "inputs.objectives" in r.text
    assert 'id="builder-step-4"' in r.text


async def test_too_many_designs_show_the_studys_cost_refusal(
    asgi_client: httpx.AsyncClient,
) -> None:
    # Per design (the whole map, no batched kernel for the cone's tilt): 10^5 designs
    # cost some thousand full maps, beyond the study's cost limit.
    tilt = "workspace.tilt_max_deg"
    form = {**SPM, "design": "grid", f"vary.{tilt}": "on", f"from.{tilt}": "10",
            f"to.{tilt}": "60", f"count.{tilt}": "100000",
            f"objective.{OBJECTIVE}": "on"}  # fmt: skip
    r = await asgi_client.post(BUILD, data=form, headers=SAME_ORIGIN)
    assert r.status_code == 422, r.text[:500]
    assert "cost-limit-exceeded" in r.text
    assert (await asgi_client.get("/v1/jobs")).json()["jobs"] == []


async def test_a_sample_is_built_from_the_bounds(asgi_client: httpx.AsyncClient) -> None:
    form = tiny_study(design="sample", sample_count="2", sample_method="latin_hypercube",
                      seed="3")  # fmt: skip
    r = await asgi_client.post(BUILD, data=form, headers=SAME_ORIGIN)
    assert r.status_code == 303, r.text
    page = (await asgi_client.get(r.headers["location"], headers=PAGE)).text
    assert "latin_hypercube" in page and "alpha1_deg" in page  # the job's inputs


async def test_an_unknown_process_or_a_foreign_post_is_refused(
    asgi_client: httpx.AsyncClient,
) -> None:
    r = await asgi_client.post(BUILD, data=tiny_study(process="nope"), headers=SAME_ORIGIN)
    assert r.status_code == 422 and "process" in r.text
    r = await asgi_client.post(BUILD, data=tiny_study(), headers={"Origin": "http://evil.example"})
    assert r.status_code == 403


async def test_a_refused_json_study_keeps_the_builder_on_its_page(
    asgi_client: httpx.AsyncClient,
) -> None:
    r = await asgi_client.post(
        "/pages/processes/design-study/run", data={"inputs": "{"}, headers=SAME_ORIGIN
    )
    assert r.status_code == 400
    assert "not valid JSON" in r.text and 'id="builder-step-1"' in r.text


async def test_a_whole_number_gets_a_whole_default_range(asgi_client: httpx.AsyncClient) -> None:
    html = await step(asgi_client, process="planar3r-dexterity-map", example="0")
    assert 'name="from.grid.points_per_axis" value="161"' in html
    assert 'name="to.grid.points_per_axis" value="241"' in html
    assert 'name="from.trajectory.polynomial[0]" value="-0.27504"' in html
