"""The live-progress stream of a job page, ``GET /v1/jobs/{jobID}/events`` (ASGI,
embedded backend): its events, its end at the terminal status, its bounded lifetime,
and its end when the client goes away."""

from __future__ import annotations

import asyncio
import json
import time
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import httpx
import pytest

from service.app import create_app
from service.config import Settings
from worker.registry import default_registry

pytestmark = [pytest.mark.integration, pytest.mark.anyio]

FOURBAR = {"lengths": [30, 17, 18, 25], "ground": 0}


@pytest.fixture
def backend() -> str:
    """The stream is the same on every backend: the embedded one is enough."""
    return "embedded"


def parse_events(text: str) -> list[dict[str, Any]]:
    events = []
    for block in text.split("\n\n"):
        lines = dict(line.split(": ", 1) for line in block.splitlines() if ": " in line)
        if lines.get("event") == "progress":
            events.append(json.loads(lines["data"]))
    return events


async def test_progress_stream_ends_with_the_terminal_status(
    asgi_client: httpx.AsyncClient,
) -> None:
    definition = default_registry().get("chain-parallelism")
    assert definition is not None
    inputs = dict(definition.examples[0].inputs)
    r = await asgi_client.post("/v1/processes/chain-parallelism/execution", json={"inputs": inputs})
    job_id = r.json()["jobID"]
    stream = await asgi_client.get(f"/v1/jobs/{job_id}/events")  # returns when it ends
    assert stream.status_code == 200
    assert stream.headers["content-type"].startswith("text/event-stream")
    assert stream.headers["cache-control"] == "no-cache"
    assert stream.text.startswith("retry: 2000\n\n")
    events = parse_events(stream.text)
    assert events[-1] == {"status": "successful", "progress": 100, "message": events[-1]["message"]}
    assert len(events) >= 2 and all(e["status"] != "successful" for e in events[:-1])
    progress = [e["progress"] for e in events]
    assert progress == sorted(progress)
    again = parse_events((await asgi_client.get(f"/v1/jobs/{job_id}/events")).text)
    assert [e["status"] for e in again] == ["successful"]  # a finished job: one event
    missing = await asgi_client.get("/v1/jobs/nope/events")
    assert missing.status_code == 404 and missing.json()["type"] == "/problems/no-such-job"


@pytest.fixture
async def idle_app(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> AsyncIterator[Any]:
    """The app with no worker (jobs stay queued) and 1-second progress streams."""
    monkeypatch.setenv("DEXLAB_EVENT_STREAM_SECONDS", "1")
    monkeypatch.setenv("DEXLAB_EVENT_POLL_SECONDS", "0.1")
    app = create_app(Settings(data_dir=tmp_path, workers=0))
    async with app.router.lifespan_context(app):
        yield app


async def test_progress_stream_lifetime_and_disconnect(idle_app: Any) -> None:
    transport = httpx.ASGITransport(app=idle_app)
    async with httpx.AsyncClient(transport=transport, base_url="http://dexlab.test") as client:
        r = await client.post("/v1/processes/fourbar-grashof/execution", json={"inputs": FOURBAR})
        job_id = r.json()["jobID"]
        started = time.monotonic()
        stream = await client.get(f"/v1/jobs/{job_id}/events")
        assert 0.9 < time.monotonic() - started < 10  # bounded: the browser reconnects
        assert stream.text.startswith("retry: ")
        assert [e["status"] for e in parse_events(stream.text)] == ["accepted"]

    # A client that goes away ends the stream at once (long before its lifetime).
    sent: list[bytes] = []
    disconnect = asyncio.Event()

    async def receive() -> dict[str, Any]:
        await disconnect.wait()
        return {"type": "http.disconnect"}

    async def send(message: dict[str, Any]) -> None:
        if message["type"] == "http.response.body" and message.get("body"):
            sent.append(message["body"])
            disconnect.set()

    assert idle_app.state.pages.settings.event_stream_seconds == 1
    scope = {
        "type": "http",
        "asgi": {"version": "3.0", "spec_version": "2.3"},
        "http_version": "1.1",
        "method": "GET",
        "scheme": "http",
        "server": ("t", 80),
        "client": ("127.0.0.1", 1),
        "root_path": "",
        "path": f"/v1/jobs/{job_id}/events",
        "raw_path": f"/v1/jobs/{job_id}/events".encode(),
        "query_string": b"",
        "headers": [(b"host", b"dexlab.test")],
    }
    started = time.monotonic()
    await asyncio.wait_for(idle_app(scope, receive, send), timeout=5)
    assert time.monotonic() - started < 0.9
    assert sent and sent[0].startswith(b"retry: ")
