"""The callback sender against a real store and a real local receiver: each event once,
the allow-list re-checked at send time, failures retried then given up."""

from __future__ import annotations

import asyncio
import json
import threading
from collections.abc import Callable, Iterator
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any

import pytest

from service.ogc.callbacks import CallbackSender
from service.ogc.outbound import OutboundPolicy
from worker.registry import default_registry
from worker.store import open_store
from worker.store.base import JobStore, NewJob

pytestmark = pytest.mark.anyio


@pytest.fixture
def receiver() -> Iterator[tuple[str, list[tuple[str, str, Any]]]]:
    posts: list[tuple[str, str, Any]] = []

    class Handler(BaseHTTPRequestHandler):
        def do_POST(self) -> None:
            body = self.rfile.read(int(self.headers["Content-Length"]))
            posts.append((self.path, self.headers["Content-Type"], json.loads(body)))
            self.send_response(500 if self.path == "/broken" else 204)
            self.end_headers()

        def log_message(self, *args: Any) -> None:
            pass

    server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    yield f"127.0.0.1:{server.server_address[1]}", posts
    server.shutdown()
    server.server_close()


@pytest.fixture
def store(tmp_path: Path) -> Iterator[JobStore]:
    s = open_store(f"sqlite:///{tmp_path / 'jobs.db'}")
    yield s
    s.close()


async def run_sender(
    store: JobStore,
    host: str,
    seconds: float,
    attempts: int = 3,
    until: Callable[[], bool] | None = None,
) -> None:
    """Run a sender for ``seconds``; with ``until``, first for as long as it takes that
    to hold (at most 30 s: a loaded machine is slow to start), then ``seconds`` more, in
    which nothing may be sent twice."""
    policy = OutboundPolicy.from_setting(host, timeout_s=2.0)
    sender = CallbackSender(store, default_registry(), policy, attempts, interval_s=0.05)
    sender.start()
    deadline = asyncio.get_running_loop().time() + 30
    while until is not None and not until() and asyncio.get_running_loop().time() < deadline:
        await asyncio.sleep(0.05)
    await asyncio.sleep(seconds)
    await sender.stop()


def subscribed_job(store: JobStore, host: str, **uris: str) -> str:
    job, _ = store.create_job(
        NewJob("fourbar-grashof", {"lengths": [2, 7, 9, 6], "ground": 1}, 60.0, 3)
    )
    subscriber = {name: f"http://{host}{path}" for name, path in uris.items()}
    store.set_request_options(
        job.job_id,
        {"response": "document", "outputs": None, "base": "https://public.example"},
        subscriber,
    )
    return job.job_id


async def test_in_progress_then_success_each_once(store: JobStore, receiver: Any) -> None:
    host, posts = receiver
    job_id = subscribed_job(store, host, inProgressUri="/running", successUri="/done")
    claim = store.claim_next("w:1", 30)
    assert claim is not None
    await run_sender(store, host, 0.4, until=lambda: len(posts) >= 1)
    ((path, media, status),) = posts
    assert (path, media, status["status"]) == ("/running", "application/json", "running")
    assert status["links"][0]["href"] == f"https://public.example/ogc/jobs/{job_id}"
    assert store.complete(job_id, claim.lease_token, {"grashof": "grashof", "notes": []}, [])
    await run_sender(store, host, 0.4, until=lambda: len(posts) >= 2)
    assert [p for p, _, _ in posts] == ["/running", "/done"]
    assert posts[1][2] == {"grashof": "grashof", "notes": []}


async def test_a_host_taken_off_the_allow_list_gets_nothing(store: JobStore, receiver: Any) -> None:
    host, posts = receiver
    job_id = subscribed_job(store, host, successUri="/done")
    claim = store.claim_next("w:1", 30)
    assert claim is not None and store.complete(job_id, claim.lease_token, {"x": 1}, [])
    await run_sender(
        store, "other.example", 0.4, attempts=1,
        until=lambda: any(e["gave_up"] for e in store.callback_log(job_id)),
    )  # fmt: skip
    assert posts == []
    (entry,) = store.callback_log(job_id)
    assert entry["gave_up"] and not entry["delivered"]


async def test_a_failing_receiver_is_retried_then_given_up(store: JobStore, receiver: Any) -> None:
    host, posts = receiver
    job_id = subscribed_job(store, host, successUri="/broken")
    claim = store.claim_next("w:1", 30)
    assert claim is not None and store.complete(job_id, claim.lease_token, {"x": 1}, [])
    sender = CallbackSender(
        store, default_registry(), OutboundPolicy.from_setting(host), 2, interval_s=0.05
    )
    sender.start()
    for _ in range(600):  # the retry waits 2 s after the first failure
        await asyncio.sleep(0.05)
        # the receiver has the second post a moment before the sender records its answer
        if len(posts) == 2 and any(e["gave_up"] for e in store.callback_log(job_id)):
            break
    await sender.stop()
    assert [p for p, _, _ in posts] == ["/broken", "/broken"]
    (entry,) = store.callback_log(job_id)
    assert entry["attempts"] == 2 and entry["gave_up"]
