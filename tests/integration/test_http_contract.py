"""What the HTTP API promises at its edges (issue 26, finding 8): HEAD on an artifact,
a 507 with Retry-After, 503s that do not say where the store is, and an OpenAPI
document that describes the progress stream's events and the 422 of an over-long
If-None-Match.

Each test drives a real uvicorn server (in a thread of this process, on the embedded
store) over real TCP connections, like tests/integration/test_hardening_http.py.
"""

from __future__ import annotations

import json
import sqlite3
import time
from pathlib import Path
from typing import Any

import pytest
from jsonschema import Draft202012Validator

from service.app import create_app
from tests.integration.test_faults import fill_disk, small_tmpfs
from tests.integration.test_hardening_http import (
    FOURBAR,
    FOURBAR_BODY,
    assert_problem,
    serve,
    settings_for,
)
from worker.contract import Artifact
from worker.store import NewJob, open_store

pytestmark = pytest.mark.integration

SVG = b'<svg xmlns="http://www.w3.org/2000/svg" width="4" height="4"></svg>' * 300


def finished_job(data_dir: Path) -> str:
    """A successful fourbar-grashof job with one artifact, ``fourbar_motion.svg``
    (:data:`SVG`), committed straight into the service's store."""
    store = open_store(f"sqlite:///{data_dir / 'jobs.db'}")
    try:
        job, _ = store.create_job(NewJob("fourbar-grashof", FOURBAR_BODY["inputs"], 60.0, 1))
        claim = store.claim_next("test:1", 60)
        assert claim is not None and claim.job.job_id == job.job_id
        result = {"grashof": True, "notes": []}
        artifact = Artifact("fourbar_motion.svg", "image/svg+xml", SVG)
        assert store.complete(job.job_id, claim.lease_token, result, [artifact])
    finally:
        store.close()
    return job.job_id


# -- HEAD on an artifact ----------------------------------------------------------------


def test_head_on_an_artifact_answers_its_headers_without_the_bytes(tmp_path: Path) -> None:
    with serve(create_app(settings_for(tmp_path))) as c:
        job_id = finished_job(tmp_path)
        for href in (
            f"/v1/jobs/{job_id}/results/fourbar_motion.svg",
            f"/ogc/jobs/{job_id}/results/fourbar_motion.svg",
            f"/ogc/jobs/{job_id}/results/grashof",  # a result member, as JSON
        ):
            got, head = c.get(href), c.head(href)
            assert got.status_code == 200 and head.status_code == 200, (href, head.text)
            assert head.content == b"", href
            assert head.headers["content-length"] == str(len(got.content)), href
            for name in ("content-type", "etag", "cache-control", "content-disposition"):
                assert head.headers.get(name) == got.headers.get(name), (href, name)
            assert "HEAD" in c.options(href).headers["Allow"], href
        v1 = f"/v1/jobs/{job_id}/results/fourbar_motion.svg"
        etag = c.get(v1).headers["etag"]
        assert c.head(v1, headers={"If-None-Match": etag}).status_code == 304
        assert int(c.head(v1).headers["content-length"]) == len(SVG)
        missing = c.head(f"/v1/jobs/{job_id}/results/nope.png")
        assert missing.status_code == 404 and missing.content == b""
        assert missing.headers["content-type"] == "application/problem+json"


# -- 507 with Retry-After ---------------------------------------------------------------


def test_a_full_disk_is_507_with_retry_after(tmp_path: Path) -> None:
    """The store's disk is full: a submit is refused 507 storage-full and told when to
    come back (space comes back when someone frees it, not within a retry window)."""
    disk = tmp_path / "disk"
    with small_tmpfs(disk, 16), serve(create_app(settings_for(disk / "data"))) as c:
        assert c.post(FOURBAR, json=FOURBAR_BODY).status_code == 201
        db = sqlite3.connect(disk / "data" / "jobs.db", isolation_level=None)
        try:  # the write-ahead log emptied, so the next write must grow it
            db.execute("PRAGMA wal_checkpoint(TRUNCATE)")
        finally:
            db.close()
        fill_disk(disk / "filler", leave_free=0)
        r = c.post(FOURBAR, json=FOURBAR_BODY)
        body = assert_problem(r, 507, "storage-full")
        assert int(r.headers["Retry-After"]) >= 30, dict(r.headers)
        assert str(disk) not in body["detail"], body
        (disk / "filler").unlink()
        assert c.post(FOURBAR, json=FOURBAR_BODY).status_code == 201


# -- 503 details ------------------------------------------------------------------------


def test_store_trouble_does_not_say_where_the_store_is(tmp_path: Path) -> None:
    """A locked SQLite store: the submit's 503 and readiness's name no file path (nor
    the database's own message); the log has them."""
    with serve(create_app(settings_for(tmp_path, store_retry_seconds=0.5))) as c:
        assert c.post(FOURBAR, json=FOURBAR_BODY).status_code == 201
        locker = sqlite3.connect(tmp_path / "jobs.db", timeout=5, isolation_level=None)
        try:
            locker.execute("BEGIN EXCLUSIVE")
            answers = [c.post(FOURBAR, json=FOURBAR_BODY), c.get("/health/ready")]
        finally:
            locker.execute("ROLLBACK")
            locker.close()
        for r in answers:
            assert r.status_code == 503, r.text
            assert str(tmp_path) not in r.text and "jobs.db" not in r.text, r.text
            assert "locked" not in r.text, r.text


# -- the OpenAPI document ---------------------------------------------------------------


def progress_events(stream: str) -> list[dict[str, Any]]:
    events = []
    for block in stream.split("\n\n"):
        fields = dict(line.split(": ", 1) for line in block.splitlines() if ": " in line)
        if fields.get("event") == "progress":
            events.append(json.loads(fields["data"]))
    return events


def test_the_document_describes_the_progress_events_the_stream_sends(tmp_path: Path) -> None:
    with serve(create_app(settings_for(tmp_path, workers=1))) as c:
        document = c.get("/openapi.json").json()
        content = document["paths"]["/v1/jobs/{job_id}/events"]["get"]["responses"]["200"][
            "content"
        ]["text/event-stream"]
        events = content["x-itemSchema"]["oneOf"]
        progress = next(e for e in events if e["properties"].get("event") == {"const": "progress"})
        ref = progress["properties"]["data"]["contentSchema"]["$ref"]
        assert ref == "#/components/schemas/ProgressEvent"
        assert "ProgressEvent" in content["schema"]["description"]
        schema = {**document["components"]["schemas"]["ProgressEvent"]}
        validator = Draft202012Validator({**schema, "components": document["components"]})
        for event in progress_events(content["example"]):  # the example is one too
            assert not list(validator.iter_errors(event)), event

        job_id = c.post(FOURBAR, json=FOURBAR_BODY).json()["jobID"]
        deadline = time.monotonic() + 60
        while c.get(f"/v1/jobs/{job_id}").json()["status"] != "successful":
            assert time.monotonic() < deadline
            time.sleep(0.2)
        sent = progress_events(c.get(f"/v1/jobs/{job_id}/events").text)
        assert sent and sent[-1]["status"] == "successful", sent
        for event in sent:
            errors = [e.message for e in validator.iter_errors(event)]
            assert not errors, (event, errors)


def test_an_over_long_if_none_match_is_a_documented_422(tmp_path: Path) -> None:
    with serve(create_app(settings_for(tmp_path))) as c:
        job_id = finished_job(tmp_path)
        href = f"/v1/jobs/{job_id}/results/fourbar_motion.svg"
        r = c.get(href, headers={"If-None-Match": '"' + "a" * 1200 + '"'})
        body = assert_problem(r, 422, "invalid-request")
        assert "if-none-match" in body["errors"][0]["field"].lower(), body
        responses = c.get("/openapi.json").json()["paths"]["/v1/jobs/{job_id}/results/{name}"][
            "get"
        ]["responses"]
        assert set(responses["422"]["content"]) >= {"application/problem+json"}
