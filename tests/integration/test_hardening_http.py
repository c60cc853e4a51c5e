"""The HTTP boundary under bad requests (issue 10 items 1, 5, 6, 7, 9, 13, 14, 15, 16).

Each test drives a real uvicorn server (in a thread of this process, on the embedded
store, without workers unless it says so) over real TCP connections, so keep-alive,
framing and headers are what a client sees.
"""

from __future__ import annotations

import base64
import sqlite3
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import httpx
import pytest
import uvicorn
from fastapi import FastAPI

from service.app import create_app
from service.config import Settings
from tests.integration.servers import free_port

pytestmark = pytest.mark.integration

PROBLEM = "application/problem+json"
FOURBAR = "/v1/processes/fourbar-grashof/execution"
FOURBAR_BODY = {"inputs": {"lengths": [30, 17, 18, 25], "ground": 0}}


@contextmanager
def serve(app: FastAPI) -> Iterator[httpx.Client]:
    """Run ``app`` under uvicorn on a free port; a keep-alive client to it."""
    port = free_port()
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port, log_level="error"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 30
    while not server.started:
        assert time.monotonic() < deadline and thread.is_alive(), "uvicorn did not start"
        time.sleep(0.05)
    try:
        with httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=30) as client:
            yield client
    finally:
        server.should_exit = True
        thread.join(timeout=30)


def settings_for(tmp_path: Path, **overrides: Any) -> Settings:
    return Settings(**{"data_dir": tmp_path, "workers": 0, **overrides})


@pytest.fixture
def client(tmp_path: Path) -> Iterator[httpx.Client]:
    with serve(create_app(settings_for(tmp_path))) as c:
        yield c


def assert_problem(r: httpx.Response, status: int, slug: str) -> dict[str, Any]:
    assert r.status_code == status, r.text
    assert r.headers["content-type"] == PROBLEM, r.headers
    body: dict[str, Any] = r.json()
    assert body["type"] == f"/problems/{slug}" and body["status"] == status, body
    return body


# -- 1. Prefer: wait=nan ----------------------------------------------------------------


@pytest.mark.parametrize("wait", ["nan", "inf", "-inf", "-5", "0", "NaN"])
def test_non_finite_or_non_positive_waits_are_ignored(client: httpx.Client, wait: str) -> None:
    started = time.monotonic()
    r = client.post(FOURBAR, json=FOURBAR_BODY, headers={"Prefer": f"wait={wait}"})
    assert r.status_code == 201, r.text
    assert "Preference-Applied" not in r.headers
    assert time.monotonic() - started < 5


# -- 5. cursors -------------------------------------------------------------------------


def cursor_of(text: str) -> str:
    return base64.urlsafe_b64encode(text.encode()).decode().rstrip("=")


@pytest.mark.parametrize(
    "text", ["seq:" + "9" * 40, "seq:-1", "seq:+5", "seq:1_0", "seq: 5", "seq:9223372036854775808"]
)
def test_out_of_range_cursors_are_422_naming_the_cursor(client: httpx.Client, text: str) -> None:
    body = assert_problem(client.get("/v1/jobs", params={"cursor": cursor_of(text)}), 422,
                          "invalid-request")  # fmt: skip
    assert body["errors"][0]["field"] == "query.cursor"


def test_the_largest_cursor_is_a_valid_empty_page(client: httpx.Client) -> None:
    r = client.get("/v1/jobs", params={"cursor": cursor_of(f"seq:{2**63 - 1}")})
    assert r.status_code == 200, r.text


# -- 6. the connection survives an unexpected error -------------------------------------


def test_an_unhandled_error_is_a_problem_and_the_connection_stays_usable(tmp_path: Path) -> None:
    app = create_app(settings_for(tmp_path))

    @app.get("/boom")
    def boom() -> None:
        raise ZeroDivisionError("a bug")

    with serve(app) as c:
        body = assert_problem(c.get("/boom"), 500, "internal-error")
        assert "ZeroDivisionError" in body["detail"] and "a bug" not in body["detail"]
        # The next request goes over the same pooled connection and must not be reset.
        pool = c._transport._pool  # type: ignore[attr-defined]
        assert len(pool.connections) == 1
        first = pool.connections[0]
        assert c.get("/health/live").status_code == 200
        assert pool.connections == [first] and first.is_idle()


# -- 7. malformed bodies ----------------------------------------------------------------


@pytest.mark.parametrize(
    ("content", "detail"),
    [
        (b'{"inputs": {"lengths": [30, 17, 18, 25], "x": "\xff\xfe"}}', "not valid UTF-8"),
        (b"[" * 10_000 + b"]" * 10_000, "nests deeper"),
        (b'{"inputs": ' * 100 + b"1" + b"}" * 100, "nests deeper"),
        (b'{"inputs": {"lengths": [NaN, 1, 1, 1], "ground": 0}}', "NaN is not a JSON number"),
        (b'{"inputs": {"lengths": [Infinity, 1, 1, 1]}}', "Infinity is not a JSON number"),
        (b'{"inputs": ', "not valid JSON"),
    ],
)
def test_malformed_bodies_are_400(client: httpx.Client, content: bytes, detail: str) -> None:
    r = client.post(FOURBAR, content=content, headers={"Content-Type": "application/json"})
    body = assert_problem(r, 400, "malformed-request")
    assert detail in body["detail"], body
    assert client.get("/v1/jobs").json()["jobs"] == []  # nothing was queued


# -- 13. request size -------------------------------------------------------------------


def test_bodies_over_the_limit_are_413_declared_or_streamed(tmp_path: Path) -> None:
    with serve(create_app(settings_for(tmp_path, max_body_bytes=4096))) as c:
        big = b'{"inputs": {"pad": "' + b"x" * 5000 + b'"}}'
        assert_problem(c.post(FOURBAR, content=big), 413, "request-too-large")

        def chunks() -> Iterator[bytes]:
            for _ in range(10):
                yield b"x" * 1000

        r = c.post(FOURBAR, content=chunks(), headers={"Content-Type": "application/json"})
        assert_problem(r, 413, "request-too-large")
        assert c.post(FOURBAR, json=FOURBAR_BODY).status_code == 201


# -- 9. store trouble -------------------------------------------------------------------


def test_a_locked_store_is_503_with_retry_after_and_readiness_says_so(tmp_path: Path) -> None:
    settings = settings_for(tmp_path, store_retry_seconds=0.5)
    with serve(create_app(settings)) as c:
        assert c.post(FOURBAR, json=FOURBAR_BODY).status_code == 201
        locker = sqlite3.connect(tmp_path / "jobs.db", timeout=5, isolation_level=None)
        try:
            locker.execute("BEGIN EXCLUSIVE")
            r = c.post(FOURBAR, json=FOURBAR_BODY)
            assert_problem(r, 503, "store-unavailable")
            assert int(r.headers["Retry-After"]) >= 1
            assert c.get("/v1/jobs").status_code == 200  # WAL: reads go on
            ready = c.get("/health/ready")
            assert ready.status_code == 503 and ready.json()["store"] == "unavailable"
            assert int(ready.headers["Retry-After"]) >= 1
        finally:
            locker.execute("ROLLBACK")
            locker.close()
        assert c.get("/v1/jobs").status_code == 200
        assert len(c.get("/v1/jobs").json()["jobs"]) == 1  # the refused submit left nothing


# -- 14. nosniff everywhere; 15. OPTIONS and Allow ---------------------------------------


def test_every_response_says_nosniff(client: httpx.Client) -> None:
    for r in (
        client.get("/"),
        client.get("/openapi.json"),
        client.get("/v1/processes"),
        client.get("/v1/jobs/nope"),
        client.post(FOURBAR, content=b"{", headers={"Content-Type": "application/json"}),
        client.put("/v1/jobs"),
        client.options("/v1/jobs"),
    ):
        assert r.headers.get("X-Content-Type-Options") == "nosniff", (r.request.url, r.headers)


def test_options_and_405_list_every_method_of_the_path(client: httpx.Client) -> None:
    job = client.post(FOURBAR, json=FOURBAR_BODY).json()["jobID"]
    r = client.options(f"/v1/jobs/{job}")
    assert r.status_code == 204
    assert set(r.headers["Allow"].split(", ")) == {"GET", "DELETE", "OPTIONS"}
    r = client.put(f"/v1/jobs/{job}")
    assert_problem(r, 405, "method-not-allowed")
    assert set(r.headers["Allow"].split(", ")) == {"GET", "DELETE", "OPTIONS"}
    assert client.options(FOURBAR).headers["Allow"] == "POST, OPTIONS"
    assert_problem(client.options("/no/such/path"), 404, "not-found")


def test_openapi_documents_every_problem_status_and_artifact_types(client: httpx.Client) -> None:
    doc = client.get("/openapi.json").json()
    assert "ProblemDocument" in doc["components"]["schemas"]
    paths = doc["paths"]
    expected = {
        ("get", "/v1/jobs/{job_id}"): {"200", "404", "500", "503"},
        ("delete", "/v1/jobs/{job_id}"): {"200", "404", "500", "503"},
        ("get", "/v1/jobs/{job_id}/results"): {"200", "404", "410", "500", "503", "507"},
        ("post", "/v1/processes/{process_id}/execution"): {
            "200", "201", "400", "404", "413", "422", "500", "503", "507",
        },
        ("post", FOURBAR): {"200", "201", "400", "413", "422", "500", "503", "507"},
    }  # fmt: skip
    for (method, path), statuses in expected.items():
        responses = paths[path][method]["responses"]
        assert statuses <= set(responses), (path, sorted(responses))
        pages = {"text/html"} if method == "get" else set()  # a browser gets a problem page
        for status in statuses - {"200", "201"}:
            content = responses[status]["content"]
            assert set(content) == {PROBLEM, *pages}, (path, status, content)
    artifact = paths["/v1/jobs/{job_id}/results/{name}"]["get"]["responses"]
    assert set(artifact["200"]["content"]) == {
        "image/png", "image/svg+xml", "text/csv", "application/x-npz",
    }  # fmt: skip
    assert "304" in artifact and "410" in artifact


def test_documents_match_their_published_schemas(tmp_path: Path) -> None:
    """Every JSON document of a real job's life validates against the schema the
    OpenAPI document gives its route (a field added but not described fails here)."""
    from jsonschema import Draft202012Validator

    with serve(create_app(settings_for(tmp_path, workers=1))) as c:
        doc = c.get("/openapi.json").json()

        def check(path: str, method: str, status: str, body: Any) -> None:
            ref = doc["paths"][path][method]["responses"][status]["content"]
            schema = {**ref["application/json"]["schema"], "components": doc["components"]}
            errors = [e.message for e in Draft202012Validator(schema).iter_errors(body)]
            assert not errors, (path, status, errors)

        r = c.post(FOURBAR, json=FOURBAR_BODY)
        check(FOURBAR, "post", "201", r.json())
        job = r.json()["jobID"]
        deadline = time.monotonic() + 60
        while (status := c.get(f"/v1/jobs/{job}").json())["status"] != "successful":
            assert time.monotonic() < deadline and status["status"] != "failed", status
            time.sleep(0.2)
        check("/v1/jobs/{job_id}", "get", "200", status)
        check("/v1/jobs/{job_id}/results", "get", "200", c.get(f"/v1/jobs/{job}/results").json())
        check("/v1/jobs", "get", "200", c.get("/v1/jobs").json())
        check("/v1/processes", "get", "200", c.get("/v1/processes").json())
        for process in c.get("/v1/processes").json()["processes"]:
            described = c.get(f"/v1/processes/{process['id']}").json()
            check("/v1/processes/{process_id}", "get", "200", described)
        check("/", "get", "200", c.get("/").json())
        check("/v1/jobs/{job_id}", "delete", "200", c.delete(f"/v1/jobs/{job}").json())
