"""Per-job overhead of each backend, beside raw Celery, measured in one run.

For the embedded default (SQLite + local pool) and for PostgreSQL + Celery over Redis
and over RabbitMQ, each with two worker processes, this starts a real deployment
(`dexlab serve` + `dexlab worker`) and measures with trivial jobs (``fourbar-grashof``
without plots: about 0.1 ms of science, no files):

- drain: a burst of jobs is submitted with no worker running, then two worker
  processes start; jobs per second from the first start to the last finish (the store's
  own timestamps).  This is the job path a design study's chunks take;
- submission: jobs per second accepted over HTTP (4 client threads) while no worker
  runs (validation, pricing, the committed insert, the broker message);
- submit-to-start latency: ``started - created`` of jobs submitted one at a time, the
  workers idle; its median (p50) and 90th percentile for every backend (target on the
  embedded default: p50 at most 5 ms).  The workers keep their default poll interval:
  an idle local pool process is woken by a hint on its pool's socket
  (``worker.dispatch.wake_ups``), a Celery worker by its broker's message.

Raw Celery on the same broker and settings (JSON, late acks, prefetch 1, two prefork
processes, ``bench/raw_celery.py``) drains the same burst of no-op tasks; the ratio
dexlab / raw is printed per broker (target: at least 0.5).  Raw Celery runs one task per
delivery; dexlab's Celery workers run short jobs several to a delivery, taking a
waiting message for each (``DEXLAB_DELIVERY_BATCH_S``; ``--delivery-batch-s 0`` measures
one job per delivery).  The embedded target is at least 300 jobs/s.

Usage: python bench/backend_overhead.py [--burst 1500] [--rounds 3] [--latency-jobs 20]
       [--backends ...] [--delivery-batch-s 0]  (0: one job per Celery delivery)
(PostgreSQL, Redis and RabbitMQ must be reachable on loopback.)
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
import uuid
from concurrent.futures import ThreadPoolExecutor
from datetime import datetime
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from timing import percentile

from tests.integration.servers import (
    BACKENDS,
    Deployment,
    delete_queue,
    deployment,
    kill_group,
    wait_terminal,
)
from tests.services import AMQP_URL, REDIS_URL

HERE = Path(__file__).resolve().parent
URL = "/v1/processes/fourbar-grashof/execution"
BROKERS = {"celery-redis": REDIS_URL, "celery-rabbitmq": AMQP_URL}
SUBMITTERS = 4


def trivial(n: int) -> dict[str, object]:
    return {"inputs": {"lengths": [2, 3, 4, 5 + n * 1e-9], "ground": 0, "plots": False}}


def parse(ts: str) -> float:
    return datetime.fromisoformat(ts.replace("Z", "+00:00")).timestamp()


def submit_burst(dep: Deployment, first: int, count: int) -> tuple[list[str], float]:
    """Submit ``count`` jobs from :data:`SUBMITTERS` threads; their IDs and the rate."""
    import httpx

    def post(numbers: range) -> list[str]:
        with httpx.Client(base_url=dep.base_url, timeout=60) as client:
            return [client.post(URL, json=trivial(n)).json()["jobID"] for n in numbers]

    shares = [range(first + i, first + count, SUBMITTERS) for i in range(SUBMITTERS)]
    start = time.perf_counter()
    with ThreadPoolExecutor(SUBMITTERS) as pool:
        ids = [job_id for share in pool.map(post, shares) for job_id in share]
    return ids, count / (time.perf_counter() - start)


def wait_all(dep: Deployment, ids: list[str]) -> list[dict[str, Any]]:
    """Wait for the last-submitted job (fair order runs one owner's jobs oldest first),
    then collect every status document."""
    wait_terminal(dep.client, ids[-1], timeout=600)
    return [wait_terminal(dep.client, job_id, timeout=600) for job_id in ids]


def measure_dexlab(
    backend: str, burst: int, latency_jobs: int, batch_s: str | None
) -> dict[str, float]:
    env: dict[str, str] = {}
    if batch_s is not None:
        env["DEXLAB_DELIVERY_BATCH_S"] = batch_s
    with (
        tempfile.TemporaryDirectory() as tmp,
        deployment(backend, Path(tmp), workers=0, env=env) as dep,
    ):
        ids, submit_rate = submit_burst(dep, 1000, burst)
        dep.start_worker(2)
        finals = wait_all(dep, ids)
        assert all(f["status"] == "successful" for f in finals), {f["status"] for f in finals}
        first = min(parse(f["started"]) for f in finals)
        last = max(parse(f["finished"]) for f in finals)
        latencies = []
        for n in range(latency_jobs):
            job_id = dep.client.post(URL, json=trivial(n)).json()["jobID"]
            done = wait_terminal(dep.client, job_id)
            latencies.append(parse(done["started"]) - parse(done["created"]))
        return {
            "drain": burst / (last - first),
            "submit": submit_rate,
            "latency_median_ms": 1000 * statistics.median(latencies),
            "latency_p90_ms": 1000 * percentile(latencies, 0.9),
        }


def measure_raw(backend: str, burst: int) -> float:
    """No-op tasks per second drained by a raw Celery worker with two processes."""
    import redis
    from raw_celery import app

    broker = BROKERS[backend]
    queue = f"raw-celery-{uuid.uuid4().hex[:10]}"
    key = f"raw-celery-times-{queue}"
    clock = redis.Redis.from_url(REDIS_URL)
    app.conf.broker_url = broker
    try:
        with app.connection_for_write() as conn, app.producer_pool.acquire(block=True) as prod:
            for _ in range(burst):
                app.send_task("raw.noop", args=[key], queue=queue, connection=conn, producer=prod)
        env = {**os.environ, "RAW_CELERY_BROKER": broker, "RAW_CELERY_QUEUE": queue,
               "RAW_CELERY_REDIS": REDIS_URL}  # fmt: skip
        worker = subprocess.Popen(
            [sys.executable, "-m", "celery", "-A", "raw_celery", "worker", "--concurrency=2",
             "--pool=prefork", f"--queues={queue}", "--prefetch-multiplier=1", "-O", "fair",
             "--without-gossip", "--without-mingle", "--loglevel=WARNING",
             f"--hostname=raw-{os.getpid()}@bench"],
            cwd=HERE, env=env, start_new_session=True,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        )  # fmt: skip
        try:
            deadline = time.monotonic() + 300
            while clock.llen(key) < burst:
                if time.monotonic() > deadline or worker.poll() is not None:
                    raise RuntimeError("the raw Celery worker did not drain its queue")
                time.sleep(0.1)
        finally:
            kill_group(worker)
            worker.wait(timeout=10)
        times = [tuple(map(float, t.split())) for t in clock.lrange(key, 0, -1)]
        return burst / (max(end for _, end in times) - min(start for start, _ in times))
    finally:
        clock.delete(key)
        delete_queue(broker, queue)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--latency-jobs", type=int, default=20)
    parser.add_argument("--burst", type=int, default=1500)
    parser.add_argument("--rounds", type=int, default=3, help="alternating runs (medians)")
    parser.add_argument("--backends", nargs="*", default=list(BACKENDS))
    parser.add_argument(
        "--delivery-batch-s",
        help="DEXLAB_DELIVERY_BATCH_S for the Celery workers (0: one job per delivery)",
    )
    args = parser.parse_args()
    runs: dict[str, list[dict[str, float]]] = {b: [] for b in args.backends}
    raws: dict[str, list[float]] = {b: [] for b in args.backends if b in BROKERS}
    for _ in range(args.rounds):  # alternating, so a slow spell of the machine hits both
        for backend in args.backends:
            runs[backend].append(
                measure_dexlab(backend, args.burst, args.latency_jobs, args.delivery_batch_s)
            )
            if backend in raws:
                raws[backend].append(measure_raw(backend, args.burst))
    rows = {b: {k: statistics.median(r[k] for r in rs) for k in rs[0]} for b, rs in runs.items()}
    raw = {b: statistics.median(v) for b, v in raws.items()}
    print(
        f"\nTrivial jobs (fourbar-grashof, no plots), 2 worker processes each; bursts of "
        f"{args.burst}, {args.latency_jobs} latency samples; medians of {args.rounds} "
        "alternating rounds."
    )
    print(
        f"{'backend':<17}{'drain':>12}{'raw Celery':>13}{'dexlab/raw':>12}"
        f"{'HTTP submit':>14}{'start p50':>12}{'start p90':>12}"
    )
    for name, row in rows.items():
        ref = raw.get(name)
        print(
            f"{name:<17}{row['drain']:>9.0f} /s"
            + (f"{ref:>10.0f} /s{row['drain'] / ref:>11.2f}x" if ref else f"{'-':>13}{'-':>12}")
            + f"{row['submit']:>11.0f} /s{row['latency_median_ms']:>9.1f} ms"
            f"{row['latency_p90_ms']:>9.1f} ms"
        )
    for name in raws:
        print(f"{name}: drains per round {[round(r['drain']) for r in runs[name]]}, "
              f"raw {[round(r) for r in raws[name]]}")  # fmt: skip
    print("start p50/p90: submit -> start (the store's created -> started) of jobs sent one "
          "at a time to idle workers")  # fmt: skip
    if "embedded" in rows:
        print(f"embedded drain vs the 300 jobs/s target: {rows['embedded']['drain'] / 300:.2f}x")
        print(f"embedded submit -> start p50 vs the 5 ms target: "
              f"{rows['embedded']['latency_median_ms']:.1f} ms")  # fmt: skip


if __name__ == "__main__":
    main()
