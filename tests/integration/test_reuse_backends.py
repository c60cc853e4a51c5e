"""Reuse and result_hash on a real `dexlab serve`, embedded (SQLite, local pool) and
PostgreSQL + Celery over Redis, with DEXLAB_REUSE=all and two keys.

On each backend: alice's worked example computes, bob's same request is answered by
reuse at once (a job of his own, `reused_from: true`, the same files), and deleting
alice's job leaves bob's results and files whole.  Across the backends (and across
two runs of one backend) the `result_hash` of each worked example is the same.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import httpx
import pytest

from tests.integration.servers import Deployment, deployment, wait_terminal
from worker.registry import default_registry

pytestmark = pytest.mark.integration

ALICE, BOB = "alice-reuse-secret-71c0e9", "bob-reuse-secret-a4d28b"
ENV = {"DEXLAB_API_KEYS": f"alice:{ALICE},bob:{BOB}", "DEXLAB_REUSE": "all"}
#: Worked examples: a chain, a four-bar, a planar 3R map (NPZ arrays), an SPM map.
EXAMPLES = ("fourbar-grashof", "chain-parallelism", "planar3r-dexterity-map",
            "spm-conditioning-map")  # fmt: skip


def example_body(process_id: str) -> dict[str, Any]:
    definition = default_registry().get(process_id)
    assert definition is not None and definition.examples
    return {"inputs": dict(definition.examples[0].inputs)}


def as_key(dep: Deployment, secret: str) -> httpx.Client:
    return httpx.Client(base_url=dep.base_url, timeout=60.0,
                        headers={"Authorization": f"Bearer {secret}"})  # fmt: skip


@pytest.fixture(scope="module")
def served(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Deployment]]:
    """Both backends at once, so each test compares them."""
    with (
        deployment("embedded", tmp_path_factory.mktemp("reuse-embedded"), env=ENV) as embedded,
        deployment("celery-redis", tmp_path_factory.mktemp("reuse-celery"), env=ENV) as celery,
    ):
        yield {"embedded": embedded, "celery-redis": celery}


def computed(client: httpx.Client, process_id: str, **body: Any) -> dict[str, Any]:
    url = f"/v1/processes/{process_id}/execution"
    submitted = client.post(url, json={**example_body(process_id), **body})
    assert submitted.status_code == 201, submitted.text
    status = wait_terminal(client, submitted.json()["jobID"], timeout=300)
    assert status["status"] == "successful", status
    results = client.get(f"/v1/jobs/{status['jobID']}/results").json()
    return {"status": status, "results": results}


def reused_on(dep: Deployment, process_id: str) -> str:
    """Run the example as alice (computed), as bob (reused), and as alice again with
    reuse false (computed afresh); delete alice's jobs; bob's stay whole.  The hash."""
    with as_key(dep, ALICE) as alice, as_key(dep, BOB) as bob:
        first = computed(alice, process_id)
        assert "reused_from" not in first["status"]
        result = first["results"]["result"]
        assert result["provenance"]["backend"] == (
            "local-pool/sqlite" if dep.backend == "embedded" else "celery/postgresql"
        )
        url = f"/v1/processes/{process_id}/execution"
        answered = bob.post(url, json=example_body(process_id), headers={"Prefer": "wait=10"})
        assert answered.status_code == 200, answered.text  # at once, whatever the cost
        theirs = answered.json()
        assert theirs["reused_from"] is True and theirs["jobID"] != first["status"]["jobID"]
        assert theirs["result"]["result_hash"] == result["result_hash"]
        again = computed(alice, process_id, reuse=False)  # a second run, computed afresh
        assert "reused_from" not in again["status"]
        assert again["results"]["result"]["result_hash"] == result["result_hash"]
        for done in (first, again):
            assert alice.delete(f"/v1/jobs/{done['status']['jobID']}").status_code == 200
        kept = bob.get(f"/v1/jobs/{theirs['jobID']}/results")
        assert kept.status_code == 200
        for artifact in kept.json()["artifacts"]:
            got = bob.get(artifact["href"])
            assert got.status_code == 200 and len(got.content) == artifact["size"]
        return str(result["result_hash"])


@pytest.mark.parametrize("process_id", EXAMPLES)
def test_reuse_on_each_backend_and_one_hash_across_them(
    served: dict[str, Deployment], process_id: str
) -> None:
    hashes = {backend: reused_on(dep, process_id) for backend, dep in served.items()}
    assert len(set(hashes.values())) == 1, hashes
