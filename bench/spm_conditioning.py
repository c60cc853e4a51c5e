"""Benchmark the vectorised SPM conditioning kernel against the per-orientation loop.

    python bench/spm_conditioning.py [--repeat 200] [--loop-evaluations 5] [--starts 8]

Everything printed is measured in this run (Bai 2010, Table 1: gamma = 0, 120° cone,
full turn; the paper's 4 x 12 x 3 = 144 default samples):

1. C_n (eq 25, with eq 28 and GCI) of the design (60°, 90°, 90°): workspace_indices
   end to end, and SampleSet.evaluate as the optimiser calls it (rotation terms built
   once), vs per_orientation_reference (a Python loop: Rodrigues, the tan-half
   quadratic, numpy.linalg.inv per orientation); best of ``--repeat`` runs each.
2. The full Table-1 optimisation (``--starts`` starts, seed 0) vs the same optimisation
   driven by the loop: that would take minutes, so the loop's cost per objective
   evaluation is timed on ``--loop-evaluations`` evaluations and scaled by the number of
   evaluations the vectorised run made; the printout says so.
"""

from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np
from timing import best_time

from worker.families.spherical_parallel.kinematics import (
    SampleSet,
    SpmDesign,
    Workspace,
    optimise,
    orientation_samples,
    per_orientation_reference,
    workspace_indices,
)

TABLE_1 = SpmDesign.from_degrees(60.0, 90.0, 90.0)
CONE_120 = Workspace(math.radians(60.0))


def compare_indices(samples: np.ndarray, repeat: int) -> None:
    sample_set = SampleSet.from_samples(samples)
    fast = best_time(lambda: workspace_indices(TABLE_1, samples), repeat)
    kernel = best_time(lambda: sample_set.evaluate(TABLE_1, -1), repeat)
    loop = best_time(lambda: per_orientation_reference(TABLE_1, samples), max(3, repeat // 40))
    a = workspace_indices(TABLE_1, samples)
    b = per_orientation_reference(TABLE_1, samples)
    diff = float(np.max(np.abs(a.inverse_condition - b.inverse_condition)))
    print(f"\n[1] C_n over the {len(samples)} default orientations, design (60, 90, 90)")
    print(f"  C_n (eq 25) = {a.rms_inverse_condition:.6f}, mean(1/kappa^2) (eq 28) = "
          f"{a.mean_square_inverse_condition:.6f}, GCI = {a.gci:.6f}")  # fmt: skip
    print(f"  workspace_indices (vectorised, end to end): {fast * 1e3:8.3f} ms  (target < 1 ms)")
    print(f"  SampleSet.evaluate (rotations reused):      {kernel * 1e3:8.3f} ms")
    print(f"  per_orientation_reference (Python loop):    {loop * 1e3:8.3f} ms")
    print(f"  speed-up: {loop / fast:,.0f}x end to end, {loop / kernel:,.0f}x per evaluation; "
          f"max |1/kappa difference| = {diff:.1e}")  # fmt: skip


def compare_optimisation(samples: np.ndarray, starts: int, loop_evaluations: int) -> None:
    start = time.perf_counter()
    result = optimise(CONE_120, samples, starts=starts, seed=0)
    fast = time.perf_counter() - start
    assert result.design is not None and result.indices is not None
    a1, a2, beta, _ = result.design.degrees()
    converged = sum(s.converged for s in result.starts)
    rng = np.random.default_rng(2010)
    designs = [SpmDesign.from_degrees(60 + 10 * rng.random(), 90, 90)
               for _ in range(loop_evaluations)]  # fmt: skip
    start = time.perf_counter()
    for design in designs:
        per_orientation_reference(design, samples)
    per_evaluation = (time.perf_counter() - start) / loop_evaluations
    loop = per_evaluation * result.evaluations
    print(f"\n[2] Table-1 optimisation: {starts} starts, seed 0, variables {result.variables}")
    indices = result.indices
    print(f"  optimum ({a1:.2f}, {a2:.2f}, {beta:.2f}) deg, mean(1/kappa^2) = "
          f"{indices.mean_square_inverse_condition:.4f}, C_n = "
          f"{indices.rms_inverse_condition:.4f}; {converged}/{starts} converged")  # fmt: skip
    each = fast / result.evaluations * 1e3
    print(f"  vectorised: {fast:7.2f} s for {result.evaluations:,} objective evaluations "
          f"({result.screen_evaluations:,} of them screening the starts; {each:.2f} ms each, "
          "solver and twins included)")  # fmt: skip
    print(f"  loop-driven: {loop:7.1f} s  (loop timed on {loop_evaluations} evaluations, "
          f"{per_evaluation * 1e3:.1f} ms each, scaled by {result.evaluations:,})")  # fmt: skip
    print(f"  speed-up: {loop / fast:,.0f}x (target: the vectorised run in a few seconds)")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=200)
    parser.add_argument("--loop-evaluations", type=int, default=5)
    parser.add_argument("--starts", type=int, default=8)
    args = parser.parse_args(argv)
    samples, layout = orientation_samples(CONE_120)
    threads = {name: os.environ.get(name, "unset") for name in ("OPENBLAS_NUM_THREADS",)}
    print(f"numpy {np.__version__}; {os.cpu_count()} CPUs; {threads}; samples {layout['counts']} "
          f"= {layout['n']} (psi1 x psi2 x psi3, equal-volume tilt cells)")  # fmt: skip
    compare_indices(samples, args.repeat)
    compare_optimisation(samples, args.starts, args.loop_evaluations)


if __name__ == "__main__":
    main()
