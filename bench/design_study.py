"""A design study's fan-out, measured in one run: one worker process against two.

    python bench/design_study.py [--designs 2000] [--chunk-size 0]

A study of SPM conditioning maps (Bai's manipulator, beta = 90 deg, a 60 deg tilt
workspace at a coarse sampling) over a grid of (alpha1, alpha2) runs on a real
`dexlab serve`:

1. embedded (SQLite + local pool) with 1 worker process, then with 2: wall time from
   submission to the assembled result, and the speed-up (target >= 1.7x);
2. Celery over Redis with PostgreSQL and two single-process `dexlab worker`s;
3. the per-chunk overhead, on one worker process (embedded, and Celery with one
   `dexlab worker`): the same 200 designs in 200 chunks of one design and in 4 chunks
   of 50, the difference in wall time per extra chunk.

Chunks default to the study's own sizing (about a second of work each).
(PostgreSQL and Redis must be reachable on loopback for 2.)
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.integration.servers import deployment, wait_terminal
from worker.processes import default_registry
from worker.studies.evaluation import evaluate_block
from worker.studies.spec import StudySpec

URL = "/v1/processes/design-study/execution"


def study(designs: int, chunk_size: int) -> dict[str, Any]:
    side = max(2, round(math.sqrt(designs)))
    inputs: dict[str, Any] = {
        "process": "spm-conditioning-map",
        "fixed": {"beta_deg": 90, "gamma_deg": 0,
                  "workspace": {"tilt_max_deg": 60, "torsion_deg": [0, 360],
                                "samples": {"azimuth": 4, "tilt": 2, "torsion": 2}}},
        "vary": {"alpha1_deg": [40, 100, side], "alpha2_deg": [60, 120, math.ceil(designs / side)]},
        "objectives": {"indices.rms_inverse_condition": "max",
                       "indices.min_inverse_condition": "max"},
        "plots": False,
    }  # fmt: skip
    if chunk_size:
        inputs["chunk_size"] = chunk_size
    return inputs


def seconds_per_design(inputs: dict[str, Any]) -> float:
    spec = StudySpec.model_validate(inputs)
    process = default_registry().get(spec.process)
    assert process is not None
    evaluate_block(spec, process, 0, 5)  # warm-up
    start = time.perf_counter()
    evaluate_block(spec, process, 0, 60)
    return (time.perf_counter() - start) / 60


def run(backend: str, inputs: dict[str, Any], **options: Any) -> tuple[float, dict[str, Any]]:
    with tempfile.TemporaryDirectory() as tmp, deployment(backend, Path(tmp), **options) as dep:
        client = dep.client
        warm = {**inputs, "vary": {"alpha1_deg": [60, 61, 2], "alpha2_deg": [90, 91, 2]}}
        wait_terminal(client, client.post(URL, json={"inputs": warm}).json()["jobID"])
        start = time.perf_counter()
        job_id = client.post(URL, json={"inputs": inputs}).json()["jobID"]
        done = wait_terminal(client, job_id, timeout=3600)
        wall = time.perf_counter() - start
        assert done["status"] == "successful", done
        return wall, client.get(f"/v1/jobs/{job_id}/results").json()["result"]


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=2000)
    parser.add_argument("--chunk-size", type=int, default=0)
    args = parser.parse_args(argv)
    inputs = study(args.designs, args.chunk_size)
    count = StudySpec.model_validate(inputs).designs.count
    per_design = seconds_per_design(inputs)
    print(f"{count:,} SPM designs; one design takes {per_design * 1e3:.1f} ms in this process")
    rows = [
        ("embedded, 1 worker process", "embedded", {"workers": 1}, 1),
        ("embedded, 2 worker processes", "embedded", {"workers": 2}, 2),
        ("Celery + Redis + PostgreSQL, 2 dexlab workers", "celery-redis",
         {"workers": 0, "worker_processes": 2}, 2),
    ]  # fmt: skip
    walls: dict[str, float] = {}
    for label, backend, options, _ in rows:
        wall, result = run(backend, inputs, **options)
        walls[label] = wall
        feasible, front = result["feasible"], result["pareto_size"]
        print(f"  {label:46s} {wall:7.1f} s, {result['chunks']} chunks, {feasible:,} feasible, "
              f"{front} non-dominated")  # fmt: skip
    one, two = walls[rows[0][0]], walls[rows[1][0]]
    print(f"  speed-up, 2 worker processes against 1 (embedded): {one / two:.2f}x (target >= 1.7x)")
    print(
        f"  speed-up, 2 Celery workers against 1 embedded process: {one / walls[rows[2][0]]:.2f}x"
    )
    small = study(200, 1)
    print("\nper-chunk overhead, one worker process, 200 designs:")
    for label, backend, options in (
        ("embedded", "embedded", {"workers": 1}),
        ("Celery + Redis + PostgreSQL", "celery-redis", {"workers": 0, "worker_processes": 1}),
    ):
        many, _ = run(backend, small, **options)
        few, _ = run(backend, {**small, "chunk_size": 50}, **options)
        print(
            f"  {label:28s} 200 chunks {many:6.1f} s, 4 chunks {few:6.1f} s: "
            f"{(many - few) / 196 * 1e3:6.1f} ms per chunk"
        )


if __name__ == "__main__":
    main()
