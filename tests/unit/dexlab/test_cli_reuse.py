"""``dexlab reuse invalidate``: the request it sends and what it prints, against a fake
service (httpx's MockTransport; the route itself is tested in
tests/unit/service/test_reuse_api.py)."""

from __future__ import annotations

import json

import httpx
import pytest
from click.testing import CliRunner

from dexlab.cli import cli
from dexlab.cli import reuse as reuse_cli
from dexlab.client import Client


def fake_service(request: httpx.Request) -> httpx.Response:
    """An admin key ('root-key') may invalidate; any other key is refused."""
    assert request.method == "DELETE" and request.url.path.startswith("/v1/reuse/")
    if request.headers.get("authorization") != "Bearer root-key":
        problem = {"type": "/problems/forbidden", "title": "Forbidden", "status": 403,
                   "detail": "Only an admin key may invalidate stored results."}  # fmt: skip
        return httpx.Response(
            403, json=problem, headers={"content-type": "application/problem+json"}
        )
    key = request.url.params.get("key")
    process = request.url.path.rsplit("/", 1)[1]
    return httpx.Response(200, json={"processID": process, "result_key": key,
                                     "invalidated": 1 if key else 3})  # fmt: skip


@pytest.fixture(autouse=True)
def faked(monkeypatch: pytest.MonkeyPatch) -> None:
    def open_client(url: str, api_key: str | None) -> Client:
        client = Client("http://dexlab.test", api_key)
        client._http = httpx.Client(
            base_url="http://dexlab.test",
            headers=client.connection.headers(),
            transport=httpx.MockTransport(fake_service),
        )
        return client

    monkeypatch.setattr(reuse_cli, "open_client", open_client)


def test_an_admin_invalidates_a_process_or_one_key() -> None:
    runner = CliRunner()
    done = runner.invoke(cli, ["reuse", "invalidate", "fourbar-grashof", "--api-key", "root-key"])
    assert done.exit_code == 0, done.output
    assert "3 stored results of fourbar-grashof (every result key) will not be reused" in (
        " ".join(done.output.split())
    )
    one = runner.invoke(cli, ["reuse", "invalidate", "fourbar-grashof", "--key", "k1",
                              "--api-key", "root-key", "--json"])  # fmt: skip
    assert one.exit_code == 0
    assert json.loads(one.output) == {"processID": "fourbar-grashof", "result_key": "k1",
                                      "invalidated": 1}  # fmt: skip


def test_another_key_is_refused_with_exit_1() -> None:
    refused = CliRunner().invoke(cli, ["reuse", "invalidate", "fourbar-grashof",
                                       "--api-key", "alice-key"])  # fmt: skip
    assert refused.exit_code == 1 and "admin" in refused.output


def test_the_client_asks_for_a_fresh_unshared_computation() -> None:
    bodies: list[dict[str, object]] = []

    def service(request: httpx.Request) -> httpx.Response:
        bodies.append(json.loads(request.content))
        return httpx.Response(201, json={"jobID": "j", "processID": "p", "status": "accepted"})

    client = Client("http://dexlab.test")
    client._http = httpx.Client(base_url="http://dexlab.test",
                                transport=httpx.MockTransport(service))  # fmt: skip
    client.submit("p", {"x": 1})
    client.submit("p", {"x": 1}, reuse=False, share=False)
    assert bodies == [{"inputs": {"x": 1}}, {"inputs": {"x": 1}, "reuse": False, "share": False}]
