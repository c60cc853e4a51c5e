"""The browser pages over the real app (ASGI, embedded backend): content negotiation,
every page, escaping, the live-progress stream, the form actions, the method pages."""

from __future__ import annotations

import json
import re
from pathlib import Path

import httpx
import pytest

from tests.integration.test_api_asgi import poll
from worker.registry import default_registry

pytestmark = [pytest.mark.integration, pytest.mark.anyio]

BROWSER = "text/html,application/xhtml+xml,application/xml;q=0.9,image/avif,*/*;q=0.8"
PAGE = {"Accept": BROWSER}
SAME_ORIGIN = {"Origin": "http://dexlab.test"}
FOURBAR = {"lengths": [30, 17, 18, 25], "ground": 0, "length_unit": "cm"}
METHOD_PAGE = """\
# Kinematic chains

Chains compared by $P = \\prod_i l_i$ and $Q$.

## Method

$$
Q = \\sum_{i} \\varepsilon_i^2
$$

## Citation

A. Author, "Parallel <chains>", 2000.
"""


@pytest.fixture
def backend() -> str:
    """The pages are the same on every backend: the embedded one is enough."""
    return "embedded"


@pytest.fixture(autouse=True)
def docs_dir(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A docs directory with one method page (set before the app is built)."""
    root = tmp_path_factory.mktemp("docs")
    (root / "methods").mkdir()
    (root / "methods" / "chains.md").write_text(METHOD_PAGE)
    monkeypatch.setenv("DEXLAB_DOCS_DIR", str(root))
    return root


async def run_fourbar(client: httpx.AsyncClient) -> str:
    r = await client.post("/v1/processes/fourbar-grashof/execution", json={"inputs": FOURBAR})
    assert r.status_code == 201, r.text
    job_id: str = r.json()["jobID"]
    assert (await poll(client, job_id))["status"] == "successful"
    return job_id


def is_page(r: httpx.Response) -> bool:
    return r.headers["content-type"].startswith("text/html")


async def test_negotiation_keeps_json_for_api_clients(asgi_client: httpx.AsyncClient) -> None:
    job_id = await run_fourbar(asgi_client)
    paths = [
        "/",
        "/v1/processes",
        "/v1/processes/fourbar-grashof",
        "/v1/jobs",
        f"/v1/jobs/{job_id}",
        f"/v1/jobs/{job_id}/results",
    ]
    for path in paths:
        plain = await asgi_client.get(path)
        assert plain.headers["content-type"] == "application/json", path
        assert "Accept" in plain.headers["vary"], path
        for headers, query in (
            ({"Accept": "*/*"}, ""),
            ({"Accept": "application/json"}, ""),
            (PAGE, "?f=json"),
            ({"Accept": "text/html;q=0.5, */*"}, ""),
        ):
            same = await asgi_client.get(path + query, headers=headers)
            assert same.content == plain.content, (path, headers, query)
        for headers, query in ((PAGE, ""), ({}, "?f=html"), ({"Accept": "text/html"}, "")):
            page = await asgi_client.get(path + query, headers=headers)
            assert page.status_code == 200 and is_page(page), (path, headers, query)
            assert page.text.startswith("<!doctype html>")
            assert "default-src 'self'" in page.headers["content-security-policy"]
        bad = await asgi_client.get(path + "?f=xml")
        assert bad.status_code == 422 and bad.json()["errors"][0]["field"] == "query.f"


async def test_every_process_page_renders(asgi_client: httpx.AsyncClient) -> None:
    listing = (await asgi_client.get("/v1/processes", headers=PAGE)).text
    for definition in default_registry():
        assert f'href="/v1/processes/{definition.id}"' in listing
        page = (await asgi_client.get(f"/v1/processes/{definition.id}", headers=PAGE)).text
        assert f"<h1>{definition.title.replace(chr(39), '&#39;')}</h1>" in page
        own_arm = "robot" in definition.inputs_schema["properties"]  # "Your own arm"
        forms = max(1, len(definition.examples)) + own_arm
        assert page.count('<form method="post"') == forms
        assert ('id="own-arm"' in page) == own_arm
        assert page.count("Run this example") == max(1, len(definition.examples))
        for name in definition.inputs_schema["properties"]:
            assert f"<code>{name}</code>" in page, (definition.id, name)
        assert f"{definition.cost_limit:,}" in page
        if definition.method_doc == "chains":  # the fixture page: summary, link, reference
            assert "<math" in page and 'rel="describedby" href="/methods/chains"' in page
            assert "Parallel &lt;chains&gt;" in page
        doc = (await asgi_client.get(f"/v1/processes/{definition.id}")).json()
        described = [link for link in doc["links"] if link["rel"] == "describedby"]
        assert described == [
            {
                "href": f"/methods/{definition.method_doc}",
                "rel": "describedby",
                "type": "text/html",
                "title": "The method, its equations and the paper's errata",
            }
        ]
    landing = (await asgi_client.get("/", headers=PAGE)).text
    for href in ("/v1/processes", "/v1/jobs", "/methods", "/docs", "/redoc"):
        assert f'href="{href}"' in landing


async def test_job_pages_show_status_results_plots_and_downloads(
    asgi_client: httpx.AsyncClient,
) -> None:
    job_id = await run_fourbar(asgi_client)
    page = (await asgi_client.get(f"/v1/jobs/{job_id}", headers=PAGE)).text
    assert '<progress id="job-progress" max="100" value="100"' in page
    assert "data-events" not in page  # finished: no live stream, no script
    assert f'<img src="/v1/jobs/{job_id}/results/fourbar_motion.png"' in page
    assert f'href="/v1/jobs/{job_id}/results/fourbar_motion.svg"' in page
    assert "triple-rocker" in page and '<th scope="row">classification</th>' in page
    assert "Non-Grashof" in page  # the notes
    assert "Delete the results" in page
    assert (await asgi_client.get(f"/v1/jobs/{job_id}/results", headers=PAGE)).text == page
    jobs = (await asgi_client.get("/v1/jobs?processID=fourbar-grashof", headers=PAGE)).text
    assert f'href="/v1/jobs/{job_id}"' in jobs
    assert '<option value="fourbar-grashof" selected>' in jobs


async def test_a_result_that_holds_less_than_it_seems_shows_a_warning(
    asgi_client: httpx.AsyncClient,
) -> None:
    """Issue 26: an empty map (no grid node reachable) and a task point out of reach are
    a warning box on the job page, not a quiet grey map."""
    inputs = {"links": [15, 14, 8], "grid": {"points_per_axis": 2}, "task_points": [[40, 0]]}
    r = await asgi_client.post(
        "/v1/processes/planar3r-dexterity-map/execution", json={"inputs": inputs}
    )
    assert r.status_code == 201, r.text
    job_id = r.json()["jobID"]
    assert (await poll(asgi_client, job_id))["status"] == "successful"
    page = (await asgi_client.get(f"/v1/jobs/{job_id}", headers=PAGE)).text
    box = page[page.index('<section class="result-warnings"') :]
    box = box[: box.index("</section>")]
    assert '<h2 id="warnings-title">Warnings</h2>' in box
    assert "The map is empty: no node of the grid" in box
    assert "Task point A (40, 0) is out of reach" in box
    assert page.index("result-warnings") < page.index('id="notes-title"')
    assert page.count('<li class="warning"><span class="warning-tag">Warning</span>') == 2
    assert 'style="' not in box  # the CSP forbids inline styles: the look is in pages.css
    css = (await asgi_client.get("/static/pages/pages.css")).text
    assert ".result-warnings {" in css and "ul.notes li.warning {" in css
    sound = {"links": [15, 14, 8], "grid": {"points_per_axis": 5}, "task_points": [[12, 8]]}
    r = await asgi_client.post(
        "/v1/processes/planar3r-dexterity-map/execution", json={"inputs": sound}
    )
    job_id = r.json()["jobID"]
    assert (await poll(asgi_client, job_id))["status"] == "successful"
    assert "result-warnings" not in (await asgi_client.get(f"/v1/jobs/{job_id}", headers=PAGE)).text


async def test_job_list_pages_follow_the_cursor(asgi_client: httpx.AsyncClient) -> None:
    ids = [await run_fourbar(asgi_client) for _ in range(3)]
    first = (await asgi_client.get("/v1/jobs?limit=2&status=successful", headers=PAGE)).text
    found = re.search(r'href="(/v1/jobs\?[^"]*cursor=[^"]*)" rel="next"', first)
    assert found, first
    href = found.group(1).replace("&amp;", "&")
    assert "status=successful" in href and "limit=2" in href
    second = (await asgi_client.get(href, headers=PAGE)).text
    shown = set(re.findall(r'href="/v1/jobs/([0-9a-f-]{36})"', first + second))
    assert set(ids) <= shown
    assert "First page" in second


async def test_user_text_is_escaped(asgi_client: httpx.AsyncClient) -> None:
    attack = '{"lengths": "</textarea><script>alert(1)</script>", "ground": 0}'
    r = await asgi_client.post(
        "/pages/processes/fourbar-grashof/run",
        data={"inputs": attack, "example": "0"},
        headers=SAME_ORIGIN,
    )
    assert r.status_code == 422 and is_page(r)
    assert "<script>alert(1)" not in r.text
    assert "&lt;/textarea&gt;&lt;script&gt;alert(1)&lt;/script&gt;" in r.text
    missing = await asgi_client.get("/v1/jobs/<script>alert(1)</script>", headers=PAGE)
    assert missing.status_code == 404 and is_page(missing)
    assert "<script>alert(1)" not in missing.text and "&lt;script&gt;" in missing.text


async def test_run_example_form(asgi_client: httpx.AsyncClient) -> None:
    form = {"inputs": json.dumps(FOURBAR), "example": "0"}
    r = await asgi_client.post(
        "/pages/processes/fourbar-grashof/run", data=form, headers=SAME_ORIGIN
    )
    assert r.status_code == 303
    job_id = r.headers["location"].removeprefix("/v1/jobs/")
    assert (await poll(asgi_client, job_id))["status"] == "successful"
    assert (await asgi_client.get(f"/v1/jobs/{job_id}")).json()["processID"] == "fourbar-grashof"

    broken = '{"lengths": [30, 17, 18, 25], "ground": 0,'
    r = await asgi_client.post(
        "/pages/processes/fourbar-grashof/run",
        data={"inputs": broken, "example": "2"},
        headers=SAME_ORIGIN,
    )
    assert r.status_code == 400 and is_page(r)
    assert "The inputs are not valid JSON" in r.text
    textarea = r'<textarea id="inputs-2"[^>]*autofocus[^>]*>'
    assert re.search(textarea + re.escape(html_text(broken)), r.text)

    invalid = json.dumps({"lengths": [30, 17, 18], "ground": 7})
    r = await asgi_client.post(
        "/pages/processes/fourbar-grashof/run",
        data={"inputs": invalid, "example": "1"},
        headers=SAME_ORIGIN,
    )
    assert r.status_code == 422 and "Invalid inputs" in r.text
    assert "<code>inputs.ground</code>" in r.text and "<code>inputs.lengths</code>" in r.text
    assert html_text(invalid) in r.text

    for text in ("[1, 2]", "NaN", '{"lengths": NaN}'):
        r = await asgi_client.post(
            "/pages/processes/fourbar-grashof/run", data={"inputs": text}, headers=SAME_ORIGIN
        )
        assert r.status_code == 400 and "not valid JSON" in r.text, text

    r = await asgi_client.post("/pages/processes/nope/run", data=form, headers=SAME_ORIGIN)
    assert r.status_code == 404 and is_page(r)
    r = await asgi_client.post(
        "/pages/processes/fourbar-grashof/run", json=form, headers=SAME_ORIGIN
    )
    assert r.status_code == 400 and "takes a form" in r.text


def html_text(text: str) -> str:
    return (
        text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&#34;")
    )


async def test_forms_refuse_other_sites(asgi_client: httpx.AsyncClient) -> None:
    before = len((await asgi_client.get("/v1/jobs")).json()["jobs"])
    form = {"inputs": json.dumps(FOURBAR)}
    for headers in (
        {},
        {"Origin": "http://evil.test"},
        {"Origin": "null"},
        {"Sec-Fetch-Site": "cross-site", "Origin": "http://dexlab.test"},
    ):
        r = await asgi_client.post(
            "/pages/processes/fourbar-grashof/run", data=form, headers=headers
        )
        assert r.status_code == 403 and is_page(r), headers
        assert "/problems/forbidden" in r.text
    assert len((await asgi_client.get("/v1/jobs")).json()["jobs"]) == before
    r = await asgi_client.post(
        "/pages/processes/fourbar-grashof/run", data=form, headers={"Sec-Fetch-Site": "same-origin"}
    )
    assert r.status_code == 303
    job_id = r.headers["location"].removeprefix("/v1/jobs/")
    r = await asgi_client.post(
        f"/pages/jobs/{job_id}/dismiss", data={}, headers={"Origin": "http://evil.test"}
    )
    assert r.status_code == 403
    assert (await asgi_client.get(f"/v1/jobs/{job_id}")).json()["status"] != "dismissed"


async def test_dismiss_form(asgi_client: httpx.AsyncClient) -> None:
    job_id = await run_fourbar(asgi_client)
    r = await asgi_client.post(f"/pages/jobs/{job_id}/dismiss", data={}, headers=SAME_ORIGIN)
    assert r.status_code == 303 and r.headers["location"] == f"/v1/jobs/{job_id}"
    page = (await asgi_client.get(r.headers["location"], headers=PAGE)).text
    assert "This job was dismissed" in page and "Delete the results" not in page
    r = await asgi_client.post("/pages/jobs/nope/dismiss", data={}, headers=SAME_ORIGIN)
    assert r.status_code == 404 and is_page(r)


async def test_method_pages(asgi_client: httpx.AsyncClient) -> None:
    listing = await asgi_client.get("/methods")
    assert listing.status_code == 200 and is_page(listing)
    assert 'href="/methods/chains"' in listing.text and "chain-parallelism" in listing.text
    page = await asgi_client.get("/methods/chains")
    assert page.status_code == 200 and "<math" in page.text and "<msub>" in page.text
    assert "Parallel &lt;chains&gt;" in page.text
    missing = await asgi_client.get("/methods/planar-serial")  # not in the fixture docs
    assert missing.status_code == 404 and missing.json()["type"] == "/problems/not-found"
    assert "available: chains" in missing.json()["detail"]
    missing_page = await asgi_client.get("/methods/nope", headers=PAGE)
    assert missing_page.status_code == 404 and is_page(missing_page)


async def test_problem_pages_keep_status_and_headers(asgi_client: httpx.AsyncClient) -> None:
    r = await asgi_client.get("/v1/jobs?limit=0", headers=PAGE)
    assert r.status_code == 422 and is_page(r) and "<code>query.limit</code>" in r.text
    r = await asgi_client.get("/v1/processes/nope/execution", headers=PAGE)
    assert r.status_code == 405 and is_page(r) and "POST" in r.headers["allow"]
    r = await asgi_client.get("/no/such/page", headers=PAGE)
    assert r.status_code == 404 and is_page(r) and "/problems/not-found" in r.text
    r = await asgi_client.get("/no/such/page")
    assert r.headers["content-type"] == "application/problem+json"


async def test_static_files_and_openapi(asgi_client: httpx.AsyncClient) -> None:
    css = await asgi_client.get("/static/pages/pages.css")
    assert css.status_code == 200 and css.headers["content-type"].startswith("text/css")
    script = await asgi_client.get("/static/pages/job-progress.js")
    assert script.status_code == 200 and "EventSource" in script.text
    for asset in (css.text, script.text):
        assert "http://" not in asset and "https://" not in asset
    document = (await asgi_client.get("/openapi.json")).json()
    assert not [p for p in document["paths"] if p.startswith("/pages")]
    for path in (
        "/",
        "/v1/processes",
        "/v1/processes/{process_id}",
        "/v1/jobs",
        "/v1/jobs/{job_id}",
        "/v1/jobs/{job_id}/results",
    ):
        operation = document["paths"][path]["get"]
        f = [p for p in operation["parameters"] if p["name"] == "f"]
        assert f and f[0]["schema"] == {"type": "string", "enum": ["json", "html"]}, path
        assert set(operation["responses"]["200"]["content"]) == {"application/json", "text/html"}
    events = document["paths"]["/v1/jobs/{job_id}/events"]["get"]["responses"]["200"]
    assert list(events["content"]) == ["text/event-stream"]
