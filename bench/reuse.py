"""A repeated worked example answered by reuse, against computing it, in one run.

On the embedded default (`dexlab serve` with a two-process local pool), for each
process's first worked example:

- computed: the example submitted with ``"reuse": false`` (computed afresh each time),
  ``--computed`` times; its time is the job's own ``finished - created`` (submission to
  result, the store's timestamps);
- reused: the same request with ``Prefer: wait=60``, ``--reused`` times, once a result
  is stored; its time is the wall time of the HTTP request that answers 200 with the
  result document (target: p95 under 50 ms for every worked example).

Prints p50 and p95 of both, in ms, and their ratio.

Usage: python bench/reuse.py [--computed 3] [--reused 30] [--processes ID ...]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from datetime import datetime
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import httpx
from timing import percentile

from tests.integration.servers import Deployment, deployment, wait_terminal
from worker.registry import default_registry

#: Every worked example, one per process, except those taking minutes to compute.
SLOW = {"planar3r-design", "planar2dof-optimisation", "spm-optimisation"}


def parse(ts: str) -> float:
    return datetime.fromisoformat(ts.replace("Z", "+00:00")).timestamp()


def example(process_id: str) -> dict[str, Any]:
    definition = default_registry().get(process_id)
    assert definition is not None and definition.examples, process_id
    return dict(definition.examples[0].inputs)


def computed_ms(client: httpx.Client, process_id: str, runs: int) -> list[float]:
    url = f"/v1/processes/{process_id}/execution"
    times = []
    for _ in range(runs):
        job = client.post(url, json={"inputs": example(process_id), "reuse": False}).json()
        status = wait_terminal(client, job["jobID"], timeout=900)
        assert status["status"] == "successful", status
        times.append(1000 * (parse(status["finished"]) - parse(status["created"])))
    return times


def reused_ms(client: httpx.Client, process_id: str, runs: int) -> list[float]:
    url = f"/v1/processes/{process_id}/execution"
    body = {"inputs": example(process_id)}
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        answer = client.post(url, json=body, headers={"Prefer": "wait=60"})
        times.append(1000 * (time.perf_counter() - start))
        assert answer.status_code == 200 and answer.json()["reused_from"], answer.text
    return times


def row(process_id: str, computed: list[float], reused: list[float]) -> str:
    c50, c95 = percentile(computed, 0.5), percentile(computed, 0.95)
    r50, r95 = percentile(reused, 0.5), percentile(reused, 0.95)
    verdict = "ok" if r95 < 50 else "ABOVE TARGET"
    return (f"{process_id:28s} {c50:10.1f} {c95:10.1f} {r50:9.1f} {r95:9.1f} "
            f"{c50 / max(r50, 1e-9):9.0f}x  {verdict}")  # fmt: skip


def run(dep: Deployment, processes: list[str], computed: int, reused: int) -> None:
    print(f"{'worked example':28s} {'computed':>10s} {'':>10s} {'reused':>9s} {'':>9s}")
    print(
        f"{'':28s} {'p50 ms':>10s} {'p95 ms':>10s} {'p50 ms':>9s} {'p95 ms':>9s} {'p50 ratio':>10s}"
    )
    with httpx.Client(base_url=dep.base_url, timeout=120) as client:
        for process_id in processes:
            fresh = computed_ms(client, process_id, computed)
            answered = reused_ms(client, process_id, reused)
            print(row(process_id, fresh, answered), flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--computed", type=int, default=3)
    parser.add_argument("--reused", type=int, default=30)
    parser.add_argument("--processes", nargs="*")
    args = parser.parse_args()
    every = [d.id for d in default_registry() if d.examples and d.id not in SLOW]
    processes = args.processes or every
    with tempfile.TemporaryDirectory() as tmp, deployment("embedded", Path(tmp)) as dep:
        run(dep, processes, args.computed, args.reused)


if __name__ == "__main__":
    main()
