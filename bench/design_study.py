"""Design studies, measured in one run: each study kernel against the per-design path,
then a 10^6-design SPM study end to end on two worker processes.

    python bench/design_study.py [--skip-million] [--fan-out]

1. Designs per second in this process, through the process's study kernel (``engine:
   batched``) and per design (``engine: per-design``, the whole process once per
   design), for the SPM (Bai's Example I, the first worked study: 144 samples), the
   3R arm (task-point d_z; its map summary) and the five-bar, and the two chain
   kernels; the ratio, and the targets (the SPM batched >= 200x, the 3R kernel >= 10^5
   design-task-points per second).  A process without a kernel yet prints so.
2. A 10^6-design SPM study (Example I's fixed inputs, a 1000 x 1000 grid of (alpha1,
   alpha2)) on a real `dexlab serve` with two worker processes: wall time from
   submission to the assembled result (target <= 3 minutes).
3. With ``--fan-out``: the fan-out of the per-design path, one worker process against
   two (embedded), Celery over Redis, and the per-chunk overhead (PostgreSQL and Redis
   on loopback).

The machine is shared: the load average is printed with the numbers.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.integration.servers import deployment, wait_terminal
from worker.registry import default_registry
from worker.studies.batched import evaluate_batched
from worker.studies.engine import choose_engine
from worker.studies.evaluation import evaluate_block
from worker.studies.examples import STUDY_EXAMPLES
from worker.studies.spec import StudySpec

URL = "/v1/processes/design-study/execution"
SPM = dict(STUDY_EXAMPLES[0].inputs)
ARM = dict(STUDY_EXAMPLES[3].inputs)
#: (label, study, designs through the kernel, designs per design, points per design)
CASES: list[tuple[str, dict[str, Any], int, int, int]] = [
    ("SPM, 144 samples", {**SPM, "vary": {"alpha1_deg": [30, 150, 200],
                                          "alpha2_deg": [30, 150, 100]}}, 20_000, 12, 1),
    ("3R arm, worst task-point d_z", {**ARM, "vary": {"links[0]": [10, 20, 100],
                                                      "links[1]": [8, 18, 100]}},
     10_000, 12, len(ARM["fixed"]["task_points"])),
    ("3R arm, map summary (51 x 51, limits)", {
        **ARM, "fixed": {**ARM["fixed"], "grid": {"points_per_axis": 51}},
        "vary": {"links[0]": [10, 20, 100], "links[1]": [8, 18, 100]},
        "objectives": {"summary.d_z_mean_reachable": "max", "areas.fully_dexterous": "max"}},
     200, 6, 1),
    ("five-bar, conditioning map", {
        "process": "planar2dof-conditioning-map",
        "fixed": {"architecture": "isotropic", "inverse_condition_limit": 0.5,
                  "grid": {"points_per_axis": 51}},
        "vary": {"l2": [1.0, 2.0, 10_000]},
        "objectives": {"summary.inverse_condition.mean": "max"}}, 10_000, 12, 1),
    ("five-bar, W_kappa0 area", {
        "process": "planar2dof-conditioning-map",
        "fixed": {"architecture": "isotropic", "inverse_condition_limit": 0.5,
                  "grid": {"points_per_axis": 51}},
        "vary": {"l2": [1.0, 2.0, 10_000]},
        "objectives": {"w_kappa0.area": "max"}}, 40, 8, 1),
    ("chain-parallelism, Fig 2", {**dict(STUDY_EXAMPLES[2].inputs),
                                  "vary": {"chains[3].lengths[2]": [6, 24, 200_000]}},
     200_000, 50, 1),
    ("fourbar-grashof", {"process": "fourbar-grashof",
                         "fixed": {"lengths": [2, 7, 9, 6], "ground": 1},
                         "vary": {"lengths[0]": [1, 12, 500], "lengths[2]": [1, 20, 500]},
                         "objectives": {"criterion.margin": "max"}}, 250_000, 100, 1),
]  # fmt: skip
MILLION = {**SPM, "vary": {"alpha1_deg": [30, 150, 1000], "alpha2_deg": [30, 150, 1000]}}


def load() -> str:
    return "load average {:.1f} {:.1f} {:.1f}".format(*os.getloadavg())


def kernel_table() -> None:
    registry = default_registry()
    print(f"designs per second in one process ({load()}):")
    for label, inputs, fast_count, slow_count, points in CASES:
        spec = StudySpec.model_validate({**inputs, "plots": False})
        process = registry.get(spec.process)
        assert process is not None
        choice = choose_engine(spec, process)
        if choice.engine != "batched":
            print(f"  {label:34s} no kernel yet ({choice.why})")
            continue
        evaluate_batched(spec, process, choice, 0, min(fast_count, 1000))  # warm-up
        start = time.perf_counter()
        evaluate_batched(spec, process, choice, 0, fast_count)
        batched = fast_count / (time.perf_counter() - start)
        evaluate_block(spec, process, 0, 2)  # warm-up: imports, caches
        start = time.perf_counter()
        evaluate_block(spec, process, 0, slow_count)
        per_design = slow_count / (time.perf_counter() - start)
        extra = f", {batched * points:,.0f} design-task-points/s" if points > 1 else ""
        print(f"  {label:34s} batched {batched:11,.0f}/s, per design {per_design:9,.1f}/s: "
              f"{batched / per_design:8,.0f}x{extra}")  # fmt: skip
    print("  targets: SPM batched >= 200x per design; 3R kernel >= 100,000 design-task-points/s")


def run(backend: str, inputs: dict[str, Any], timeout: float = 3600,
        **options: Any) -> tuple[float, dict[str, Any]]:  # fmt: skip
    with tempfile.TemporaryDirectory() as tmp, deployment(backend, Path(tmp), **options) as dep:
        client = dep.client
        warm = {**inputs, "vary": {"alpha1_deg": [60, 61, 2], "alpha2_deg": [90, 91, 2]}}
        wait_terminal(client, client.post(URL, json={"inputs": warm}).json()["jobID"])
        start = time.perf_counter()
        job_id = client.post(URL, json={"inputs": inputs}).json()["jobID"]
        done = wait_terminal(client, job_id, timeout=timeout)
        wall = time.perf_counter() - start
        assert done["status"] == "successful", done
        return wall, client.get(f"/v1/jobs/{job_id}/results").json()["result"]


def million() -> None:
    wall, result = run("embedded", MILLION, workers=2)
    print(f"\n10^6-design SPM study, embedded, two worker processes: {wall:.1f} s end to end "
          f"(target <= 180 s), {result['chunks']} chunks, engine {result['engine']}, "
          f"{result['feasible']:,} feasible, {result['pareto_size']} non-dominated; "
          f"{load()}")  # fmt: skip


def fan_out(designs: int = 2000) -> None:
    side = max(2, round(math.sqrt(designs)))
    inputs: dict[str, Any] = {
        "process": "spm-conditioning-map", "engine": "per-design", "plots": False,
        "fixed": {"beta_deg": 90, "gamma_deg": 0,
                  "workspace": {"tilt_max_deg": 60, "torsion_deg": [0, 360],
                                "samples": {"azimuth": 4, "tilt": 2, "torsion": 2}}},
        "vary": {"alpha1_deg": [40, 100, side], "alpha2_deg": [60, 120, math.ceil(designs / side)]},
        "objectives": {"indices.rms_inverse_condition": "max",
                       "indices.min_inverse_condition": "max"},
    }  # fmt: skip
    print(f"\nfan-out of the per-design path, {designs:,} SPM designs ({load()}):")
    walls = {}
    for label, backend, options in (
        ("embedded, 1 worker process", "embedded", {"workers": 1}),
        ("embedded, 2 worker processes", "embedded", {"workers": 2}),
        ("Celery + Redis + PostgreSQL, 2 dexlab workers", "celery-redis",
         {"workers": 0, "worker_processes": 2}),
    ):  # fmt: skip
        walls[label], result = run(backend, inputs, **options)
        print(f"  {label:46s} {walls[label]:7.1f} s, {result['chunks']} chunks")
    one, two = walls["embedded, 1 worker process"], walls["embedded, 2 worker processes"]
    print(f"  speed-up, 2 worker processes against 1 (embedded): {one / two:.2f}x")
    small = {**inputs, "vary": {"alpha1_deg": [40, 100, 20], "alpha2_deg": [60, 120, 10]}}
    print("per-chunk overhead, one worker process, 200 designs:")
    for label, backend, options in (
        ("embedded", "embedded", {"workers": 1}),
        ("Celery + Redis + PostgreSQL", "celery-redis", {"workers": 0, "worker_processes": 1}),
    ):
        many, _ = run(backend, {**small, "chunk_size": 1}, **options)
        few, _ = run(backend, {**small, "chunk_size": 50}, **options)
        print(f"  {label:28s} 200 chunks {many:6.1f} s, 4 chunks {few:6.1f} s: "
              f"{(many - few) / 196 * 1e3:6.1f} ms per chunk")  # fmt: skip


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--skip-million", action="store_true")
    parser.add_argument("--fan-out", action="store_true")
    args = parser.parse_args(argv)
    kernel_table()
    if not args.skip_million:
        million()
    if args.fan_out:
        fan_out()


if __name__ == "__main__":
    main()
