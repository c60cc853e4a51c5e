"""The job pages' everyday tools over the real app (ASGI, embedded backend): started,
duration and expiry; "Edit and run again"; the question before a dismissal (the page
that asks without JavaScript); durations and live refresh on the jobs list."""

from __future__ import annotations

import html
import json
import re

import httpx
import pytest

from tests.integration.test_api_asgi import poll
from tests.integration.test_pages_asgi import FOURBAR, PAGE, SAME_ORIGIN, run_fourbar
from worker.registry import default_registry

pytestmark = [pytest.mark.integration, pytest.mark.anyio]


@pytest.fixture
def backend() -> str:
    return "embedded"


def textarea(page: str, index: int = 0) -> str:
    found = re.search(rf'<textarea id="inputs-{index}"[^>]*>(.*?)</textarea>', page, re.S)
    assert found, page
    return html.unescape(found.group(1))


async def test_a_finished_job_page_shows_its_times_and_actions(
    asgi_client: httpx.AsyncClient,
) -> None:
    job_id = await run_fourbar(asgi_client)
    status = (await asgi_client.get(f"/v1/jobs/{job_id}")).json()
    page = (await asgi_client.get(f"/v1/jobs/{job_id}", headers=PAGE)).text
    assert "<dt>Started</dt>" in page and "<dt>Duration</dt>" in page
    duration = re.search(r'<dd id="job-duration">([^<]*)</dd>', page)
    assert duration and re.fullmatch(r"\d+\.\d s|\d+ s|\d+ min \d\d s", duration.group(1))
    assert "Time left" not in page  # finished
    expires = status["expires"]
    assert f"{expires[:10]} {expires[11:19]} UTC" in page
    assert f'href="/pages/jobs/{job_id}/edit"' in page and "Edit and run again" in page
    # Dismissing: a GET form to the page that asks, and the form a dialog posts
    assert f'<form method="get" action="/pages/jobs/{job_id}/dismiss"' in page
    assert 'data-question="Delete the results of this job?' in page
    assert (
        f'<form method="post" action="/pages/jobs/{job_id}/dismiss" id="dismiss-post" hidden>'
        in page
    )
    assert "/static/pages/job-dismiss.js" in page or "job-dismiss.js" in page


async def test_edit_and_run_again_prefills_the_form_and_runs_a_new_job(
    asgi_client: httpx.AsyncClient,
) -> None:
    job_id = await run_fourbar(asgi_client)
    r = await asgi_client.get(f"/pages/jobs/{job_id}/edit")
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/html")
    assert f"the inputs of job {job_id[:8]}" in r.text and "Run as a new job" in r.text
    prefilled = json.loads(textarea(r.text))  # as stored: with the defaults filled in
    assert FOURBAR.items() <= prefilled.items() and prefilled["plots"] is True
    assert 'action="/pages/processes/fourbar-grashof/run"' in r.text
    assert f'<input type="hidden" name="from" value="{job_id}">' in r.text
    edited = {**FOURBAR, "lengths": [30, 17, 18, 20]}
    r = await asgi_client.post("/pages/processes/fourbar-grashof/run",
                               data={"inputs": json.dumps(edited), "example": "0"},
                               headers=SAME_ORIGIN)  # fmt: skip
    assert r.status_code == 303
    new_id = r.headers["location"].removeprefix("/v1/jobs/")
    assert new_id != job_id
    assert (await poll(asgi_client, new_id))["status"] == "successful"
    bad = json.dumps({**FOURBAR, "lengths": [1, 1, 1, 100]})
    refused = await asgi_client.post("/pages/processes/fourbar-grashof/run",
                                     data={"inputs": bad, "example": "0", "from": job_id},
                                     headers=SAME_ORIGIN)  # fmt: skip
    assert refused.status_code == 422 and "the loop cannot close" in refused.text
    assert f"the inputs of job {job_id[:8]}" in refused.text  # back in the re-run form
    assert json.loads(textarea(refused.text)) == json.loads(bad)
    missing = await asgi_client.get("/pages/jobs/no-such-job/edit")
    assert missing.status_code == 404


async def test_the_dismiss_question_page_asks_then_posts(asgi_client: httpx.AsyncClient) -> None:
    job_id = await run_fourbar(asgi_client)
    r = await asgi_client.get(f"/pages/jobs/{job_id}/dismiss")
    assert r.status_code == 200 and "<h1>Delete the results?</h1>" in r.text
    assert "deleted for good" in r.text and f'href="/v1/jobs/{job_id}"' in r.text
    assert f'<form method="post" action="/pages/jobs/{job_id}/dismiss"' in r.text
    assert (await asgi_client.get(f"/v1/jobs/{job_id}")).json()["status"] == "successful"
    r = await asgi_client.post(f"/pages/jobs/{job_id}/dismiss", data={}, headers=SAME_ORIGIN)
    assert r.status_code == 303
    assert (await asgi_client.get(f"/v1/jobs/{job_id}")).json()["status"] == "dismissed"
    again = await asgi_client.get(f"/pages/jobs/{job_id}/dismiss")
    assert again.status_code == 303 and again.headers["location"] == f"/v1/jobs/{job_id}"
    assert (await asgi_client.get("/pages/jobs/no-such-job/dismiss")).status_code == 404


async def test_the_jobs_list_shows_durations_and_refreshes(asgi_client: httpx.AsyncClient) -> None:
    job_id = await run_fourbar(asgi_client)
    page = (await asgi_client.get("/v1/jobs", headers=PAGE)).text
    assert '<th scope="col">Duration</th>' in page
    row = page[page.index(f'href="/v1/jobs/{job_id}"') :].split("</tr>")[0]
    assert re.search(r'<td class="num">(\d+\.\d s|\d+ s)</td>', row), row
    assert 'id="jobs-listing" data-refresh-seconds="5"' in page and "jobs-live.js" in page
    assert 'http-equiv="refresh"' not in page  # nothing running: no reloads without JS


async def test_compare_two_jobs_of_one_process(asgi_client: httpx.AsyncClient) -> None:
    first = await run_fourbar(asgi_client)
    other = {**FOURBAR, "lengths": [30, 17, 18, 40]}
    r = await asgi_client.post("/v1/processes/fourbar-grashof/execution", json={"inputs": other})
    second = r.json()["jobID"]
    assert (await poll(asgi_client, second))["status"] == "successful"
    page = await asgi_client.get("/pages/compare", params={"jobs": [first, second]})
    assert page.status_code == 200, page.text
    rows = {
        m.group(2): m.group(0)
        for m in re.finditer(
            r'<tr( class="differs")?><th scope="row"><code>([^<]+)</code>.*?</tr>', page.text, re.S
        )
    }
    assert 'class="differs"' in rows["lengths"] and "[30.0, 17.0, 18.0, 40.0]" in rows["lengths"]
    assert 'class="differs"' not in rows["ground"] and 'class="differs"' not in rows["length_unit"]
    margin = rows["criterion.margin"]  # p + q - (s + l) differs with l
    assert 'class="differs"' in margin and '<span class="delta">(' in margin
    assert "(1 differ)" in page.text  # of the inputs: the lengths
    assert page.text.count('<figure class="plot">') >= 2
    assert f"/v1/jobs/{first}/results/fourbar_motion.png" in page.text
    assert f"/v1/jobs/{second}/results/fourbar_motion.png" in page.text
    listing = (await asgi_client.get("/v1/jobs", headers=PAGE)).text
    assert f'<input type="checkbox" name="jobs" value="{first}" form="compare-form"' in listing
    assert '<form method="get" action="/pages/compare" id="compare-form"' in listing


async def test_compare_refuses_one_job_and_mixed_processes(asgi_client: httpx.AsyncClient) -> None:
    fourbar = await run_fourbar(asgi_client)
    chains = default_registry().require("chain-parallelism").examples[0].inputs
    r = await asgi_client.post("/v1/processes/chain-parallelism/execution",
                               json={"inputs": dict(chains)})  # fmt: skip
    other = r.json()["jobID"]
    mixed = await asgi_client.get("/pages/compare", params={"jobs": [fourbar, other]})
    # a page action: its problems are pages, naming the field
    assert mixed.status_code == 422 and mixed.headers["content-type"].startswith("text/html")
    assert "query.jobs" in mixed.text and "one process only" in mixed.text
    one = await asgi_client.get("/pages/compare", params={"jobs": [fourbar, fourbar]})
    assert one.status_code == 422 and "at least two different jobs" in one.text
    single = await asgi_client.get("/pages/compare", params={"jobs": [fourbar]})
    assert single.status_code == 422 and "query.jobs" in single.text
    missing = await asgi_client.get("/pages/compare", params={"jobs": [fourbar, "nope"]})
    assert missing.status_code == 404
