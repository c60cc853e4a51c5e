"""Per-job overhead of each backend, measured side by side in one run.

For the embedded default (SQLite + local pool) and for PostgreSQL + Celery over Redis
and over RabbitMQ, each with two worker processes, this starts a real deployment
(`dexlab serve` + `dexlab worker`) and measures with trivial jobs (a 2 x 2 map,
no plots):

- submit-to-start latency: ``started - created`` of jobs submitted one at a time;
- throughput: jobs per second finishing a burst submitted at once.

Usage: python bench/backend_overhead.py [--latency-jobs 20] [--burst 60]
(PostgreSQL, Redis and RabbitMQ must be reachable on loopback.)
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from datetime import datetime
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from timing import percentile

from tests.integration.servers import BACKENDS, deployment, wait_terminal

URL = "/v1/processes/planar3r-dexterity-map/execution"


def trivial(n: int) -> dict[str, object]:
    return {"links": [3, 2, 1 + n * 1e-9], "grid": {"points_per_axis": 2}, "plots": False}


def parse(ts: str) -> float:
    return datetime.fromisoformat(ts.replace("Z", "+00:00")).timestamp()


def measure(backend: str, latency_jobs: int, burst: int) -> dict[str, float]:
    with (
        tempfile.TemporaryDirectory() as tmp,
        deployment(backend, Path(tmp), workers=2, env={"DEXLAB_POLL_SECONDS": "0.05"}) as dep,
    ):
        client = dep.client
        for n in range(3):  # warm-up: imports in the worker processes
            wait_terminal(client, client.post(URL, json={"inputs": trivial(n)}).json()["jobID"])
        latencies = []
        for n in range(latency_jobs):
            job_id = client.post(URL, json={"inputs": trivial(100 + n)}).json()["jobID"]
            done = wait_terminal(client, job_id)
            latencies.append(parse(done["started"]) - parse(done["created"]))
        start = time.perf_counter()
        ids = [
            client.post(URL, json={"inputs": trivial(1000 + n)}).json()["jobID"]
            for n in range(burst)
        ]
        finals = [wait_terminal(client, job_id, timeout=600) for job_id in ids]
        elapsed = time.perf_counter() - start
        assert all(f["status"] == "successful" for f in finals)
        return {
            "latency_median_ms": 1000 * statistics.median(latencies),
            "latency_p90_ms": 1000 * percentile(latencies, 0.9),
            "throughput_jobs_s": burst / elapsed,
        }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--latency-jobs", type=int, default=20)
    parser.add_argument("--burst", type=int, default=60)
    parser.add_argument("--backends", nargs="*", default=list(BACKENDS))
    args = parser.parse_args()
    rows = {b: measure(b, args.latency_jobs, args.burst) for b in args.backends}
    base = rows.get("embedded")
    print(
        f"\nTrivial jobs, 2 worker processes each; {args.latency_jobs} latency samples, "
        f"burst of {args.burst}."
    )
    print(
        f"{'backend':<18}{'submit->start median':>22}{'p90':>10}{'throughput':>14}"
        f"{'latency vs embedded':>22}{'throughput vs embedded':>25}"
    )
    for name, row in rows.items():
        lat_ratio = row["latency_median_ms"] / base["latency_median_ms"] if base else float("nan")
        thr_ratio = row["throughput_jobs_s"] / base["throughput_jobs_s"] if base else float("nan")
        print(
            f"{name:<18}{row['latency_median_ms']:>19.1f} ms{row['latency_p90_ms']:>7.1f} ms"
            f"{row['throughput_jobs_s']:>9.1f} /s{lat_ratio:>21.2f}x{thr_ratio:>24.2f}x"
        )


if __name__ == "__main__":
    main()
