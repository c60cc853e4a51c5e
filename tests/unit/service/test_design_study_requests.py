"""Design-study requests on the real app (no workers: accepted studies only queue): a
bad study is a 422 naming its field before anything is queued, never a 500, on the
native and the OGC execute routes, with or without ``Prefer: wait``."""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from functools import partial
from pathlib import Path
from typing import Any

import anyio.from_thread
import httpx
import pytest
from hypothesis import event, example, given
from hypothesis import strategies as st

from service.app import create_app
from service.config import Settings
from tests.unit.worker.studies.study_requests import (
    names_a_place,
    property_settings,
    study_bodies,
)
from worker.processes import ProcessRegistry

NATIVE = "/v1/processes/design-study/execution"
OGC = "/ogc/processes/design-study/execution"
PROBLEM = "application/problem+json"
Send = Callable[..., httpx.Response]

CHAINS = {"chains": [{"name": "Fig 2a", "lengths": [15, 15, 15, 15]},
                     {"name": "Fig 2b", "lengths": [20, 10, 20, 10]}]}  # fmt: skip


@contextmanager
def app_client(data_dir: Path, registry: ProcessRegistry | None = None) -> Iterator[Send]:
    """A blocking ``send(method, url, **kwargs)`` to the real app (serving ``registry``,
    by default every process) over httpx's ASGI transport, its lifespan entered, with no
    worker pool."""
    app = create_app(Settings(data_dir=data_dir, workers=0), registry=registry)
    transport = httpx.ASGITransport(app=app)
    client = httpx.AsyncClient(transport=transport, base_url="http://dexlab.test")
    with (
        anyio.from_thread.start_blocking_portal() as portal,
        portal.wrap_async_context_manager(app.router.lifespan_context(app)),
        portal.wrap_async_context_manager(client),
    ):
        yield lambda method, url, **kw: portal.call(partial(client.request, method, url, **kw))


def post(send: Send, url: str, inputs: Any, wait: bool = False) -> httpx.Response:
    """POST an execute body as raw JSON (NaN and Infinity pass as Python writes them)."""
    headers = {"content-type": "application/json"}
    if wait:
        headers["Prefer"] = "wait=5"
    return send("POST", url, content=json.dumps({"inputs": inputs}), headers=headers)


@pytest.fixture
def send(tmp_path: Path) -> Iterator[Send]:
    with app_client(tmp_path) as client:
        yield client


@pytest.mark.parametrize(
    ("inputs", "field", "message"),
    [
        (  # issue 26, finding 6: the list is not in 'fixed' at all
            {"process": "fourbar-grashof", "fixed": {"ground": 0},
             "vary": {"lengths[0]": [1, 5, 3]}, "objectives": {"criterion.margin": "max"}},
            "inputs.vary.lengths[0]",
            "'fixed' has no list 'lengths'",
        ),
        (  # the fuzzer's chains[3]: 'fixed' holds two chains
            {"process": "chain-parallelism", "fixed": CHAINS,
             "vary": {"chains[3]": [10, 20, 3]}, "objectives": {"chains[0].P": "max"}},
            "inputs.vary.chains[3]",
            r"'chains' in 'fixed' is a list of 2: it has no element \[3\]",
        ),
        (  # the fuzzer's links[0], in a sample's bounds
            {"process": "planar3r-dexterity-map", "fixed": {"grid": {"points_per_axis": 5}},
             "sample": {"count": 3, "bounds": {"links[0]": [10, 20]}},
             "objectives": {"links|sum": "min"}},
            "inputs.sample.bounds.links[0]",
            "'fixed' has no list 'links'",
        ),
    ],
)  # fmt: skip
@pytest.mark.parametrize("url", [NATIVE, OGC])
def test_a_varied_path_into_a_list_fixed_lacks_is_a_422_naming_it(
    send: Send, url: str, inputs: dict[str, Any], field: str, message: str
) -> None:
    response = post(send, url, inputs)
    assert response.status_code == 422, response.text
    assert response.headers["content-type"] == PROBLEM
    errors = response.json()["errors"]
    assert [e["field"] for e in errors] == [field]
    assert re.search(message, errors[0]["message"]), errors[0]["message"]
    assert send("GET", "/v1/jobs").json()["jobs"] == []  # nothing was queued


@pytest.mark.parametrize(
    ("change", "field", "message"),
    [
        ({"vary": {"chains[1]": [10, 20, 3]}}, "inputs.vary.chains[1]",
         "chain-parallelism takes no number at 'chains[1]'"),
        ({"vary": {"chains[0].lengths[2]": [10, 20, 3], "chains[0].lengths[02]": [1, 2, 2]}},
         "inputs.vary.chains[0].lengths[02]", "names the same input as 'chains[0].lengths[2]'"),
        ({"vary": {"chains[0].lengths[9]": [10, 20, 3]}}, "inputs.vary.chains[0].lengths[9]",
         "'chains[0].lengths' in 'fixed' is a list of 4"),
        ({"vary": {"chains[0].lengths[2]": [-1e308, 1.7e308, 3]}},
         "inputs.vary.chains[0].lengths[2]", "beyond a float"),
        ({"vary": {"chains[0].lengths[2]": [10, "20", 3]}}, "inputs.vary.chains[0].lengths[2]",
         "lo and hi must be finite numbers"),
        ({"objectives": {"chains[].P": "max"}}, "inputs.objectives.chains[].P", "reduce them"),
        ({"vary": None}, "inputs.vary", "exactly one of"),
        ({"length_unit": "cm"}, "inputs.length_unit", "Extra inputs are not permitted"),
    ],
)  # fmt: skip
def test_other_bad_studies_name_their_field(
    send: Send, change: dict[str, Any], field: str, message: str
) -> None:
    inputs = {"process": "chain-parallelism", "fixed": CHAINS,
              "vary": {"chains[0].lengths[2]": [10, 20, 3]}, "objectives": {"chains[0].P": "max"},
              **change}  # fmt: skip
    response = post(send, NATIVE, inputs)
    assert response.status_code == 422, response.text
    (error,) = response.json()["errors"]
    assert error["field"] == field
    assert message in error["message"]


def check_response(response: httpx.Response, inputs: Any) -> None:
    """No server error; a 422 lists field errors, each naming a place in the request."""
    assert response.status_code < 500, response.text
    assert response.status_code in (201, 422), response.text
    if response.status_code == 422:
        assert response.headers["content-type"] == PROBLEM
        errors = response.json()["errors"]
        assert errors, response.text
        for error in errors:
            assert error["message"], error
            assert names_a_place(error["field"], {"inputs": inputs}), (error, inputs)


EMPTY_GRID = {"process": "fourbar-grashof", "fixed": {"lengths": [2, 7, 9, 6]}, "vary": {},
              "objectives": {"criterion.margin": "max"}}  # fmt: skip


@pytest.mark.slow
def test_no_study_request_is_a_server_error(tmp_path: Path) -> None:
    """Random studies (sound, faulty, or random in every part), each sent to one of the
    native route, the native route with ``Prefer: wait`` and the OGC route."""
    routes = st.sampled_from([(NATIVE, False), (NATIVE, True), (OGC, False)])
    with app_client(tmp_path) as client:

        @property_settings(150)
        @given(inputs=study_bodies(), route=routes)
        @example(inputs=EMPTY_GRID, route=(NATIVE, False))  # a grid of no inputs was a 500
        def check(inputs: dict[str, Any], route: tuple[str, bool]) -> None:
            url, wait = route
            response = post(client, url, inputs, wait)
            event(f"HTTP {response.status_code}")
            check_response(response, inputs)
            if response.status_code == 201:
                job = response.json()["jobID"]
                assert client("DELETE", f"/v1/jobs/{job}").status_code == 200

        check()
