"""Benchmark the planar 3R dexterity kernels against the per-point reference sampler.

    python bench/planar3r_dexterity.py [--points-per-axis 501] [--step-deg 1] [--full-2001]

Everything printed is measured in this run, for the paper's Example 1 arm (15, 14, 8) on
a square grid around its full reach:

1. exact_orientation_dexterity (closed form, unlimited joints) vs
   sampled_orientation_dexterity looped over the points (unlimited joints);
2. limited_orientation_dexterity vs the same loop, with the paper's joint limits
   (th1, th2 in [-150, 150] deg, th3 in [-175, 175] deg);
3. tracemalloc peak of limited_orientation_dexterity on rows of a 2001 x 2001 grid at
   0.5 deg (the whole grid with --full-2001).

The per-point loop over every grid point would take minutes, so it is timed on a random
subset of points and scaled per point; the printout says so.
"""

from __future__ import annotations

import argparse
import math
import os
import time
import tracemalloc

import numpy as np
from timing import best_time, seconds_per_item

from worker.families.planar_serial.kinematics import (
    exact_orientation_dexterity,
    limited_orientation_dexterity,
    orientation_samples,
    reach_radii,
    sampled_orientation_dexterity,
)

LINKS = (15.0, 14.0, 8.0)
PAPER_LIMITS = np.radians([[-150.0, 150.0], [-150.0, 150.0], [-175.0, 175.0]])
NAIVE_SUBSET = 2000
MEMORY_STEP_DEG = 0.5


def square_grid(points_per_axis: int) -> np.ndarray:
    """(m, m, 2) points on a square 5% wider than the full reach."""
    half_width = 1.05 * reach_radii(LINKS)[1]
    axis = np.linspace(-half_width, half_width, points_per_axis)
    xs, ys = np.meshgrid(axis, axis)
    return np.stack([xs, ys], axis=-1)


def naive_seconds_per_point(
    points: np.ndarray, step: float, limits: list[list[float]] | None
) -> float:
    return seconds_per_item(
        lambda p: sampled_orientation_dexterity(LINKS, (float(p[0]), float(p[1])), step, limits),
        points,
    )


def blas_note() -> str:
    config = np.show_config(mode="dicts")
    blas = config.get("Build Dependencies", {}).get("blas", {})
    threads = {
        name: os.environ.get(name, "unset")
        for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
    }
    return (
        f"BLAS: {blas.get('name', '?')} {blas.get('version', '')}; thread settings {threads}; "
        f"{os.cpu_count()} CPUs.\n"
        "  Only limited_orientation_dexterity touches BLAS (a K=4 matrix product per cache\n"
        "  block); with the variables unset OpenBLAS may use every core for it. The exact\n"
        "  closed form and the per-point samplers are single-threaded. For a one-core\n"
        "  comparison run with OPENBLAS_NUM_THREADS=1."
    )


def compare_exact(grid: np.ndarray, step: float, rng: np.random.Generator) -> None:
    flat = grid.reshape(-1, 2)
    n, _ = orientation_samples(step)
    fast = best_time(lambda: exact_orientation_dexterity(LINKS, grid), repeat=3)
    subset = flat[rng.choice(len(flat), size=min(NAIVE_SUBSET, len(flat)), replace=False)]
    per_point = naive_seconds_per_point(subset, step, None)
    naive = per_point * len(flat)
    print(f"\n[1] unlimited joints, {grid.shape[0]} x {grid.shape[1]} = {len(flat):,} points")
    print(f"  exact_orientation_dexterity (closed form):      {fast:9.4f} s")
    print(
        f"  sampled_orientation_dexterity loop, n = {n}:    {naive:9.2f} s  (timed on "
        f"{len(subset):,} random points, {per_point * 1e6:.0f} us/point, scaled)"
    )
    print(f"  speed-up: {naive / fast:,.0f}x (target >= 200x)")


def compare_limited(grid: np.ndarray, step: float, rng: np.random.Generator) -> None:
    flat = grid.reshape(-1, 2)
    n, _ = orientation_samples(step)
    fast = best_time(lambda: limited_orientation_dexterity(LINKS, grid, PAPER_LIMITS, step), 2)
    subset = flat[rng.choice(len(flat), size=min(NAIVE_SUBSET, len(flat)), replace=False)]
    per_point = naive_seconds_per_point(subset, step, PAPER_LIMITS.tolist())
    naive = per_point * len(flat)
    exact_subset = limited_orientation_dexterity(LINKS, subset, PAPER_LIMITS, step)
    reference = [
        sampled_orientation_dexterity(LINKS, p, step, PAPER_LIMITS.tolist()) for p in subset
    ]
    mismatches = int(np.count_nonzero(exact_subset != np.asarray(reference)))
    print(f"\n[2] paper joint limits, {len(flat):,} points x n = {n} orientations")
    print(f"  limited_orientation_dexterity:                  {fast:9.3f} s  "
          f"({len(flat) * n / fast / 1e6:.1f} M point-orientations/s)")  # fmt: skip
    print(
        f"  sampled_orientation_dexterity loop:             {naive:9.2f} s  (timed on "
        f"{len(subset):,} random points, {per_point * 1e6:.0f} us/point, scaled; "
        f"{len(flat) * n / naive / 1e6:.2f} M/s)"
    )
    print(f"  speed-up: {naive / fast:,.0f}x; counts differing on the subset: {mismatches}")


def traced_peak(points: np.ndarray, step: float, **options: object) -> tuple[int, float]:
    tracemalloc.start()
    tracemalloc.reset_peak()
    start = time.perf_counter()
    limited_orientation_dexterity(LINKS, points, PAPER_LIMITS, step, **options)  # type: ignore[arg-type]
    seconds = time.perf_counter() - start
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak, seconds


def memory(full: bool) -> None:
    step = math.radians(MEMORY_STEP_DEG)
    n, _ = orientation_samples(step)
    grid = square_grid(2001)
    default_chunk = 2**22
    chunk_points = default_chunk // n
    print(f"\n[3] tracemalloc peak, 2001 x 2001 grid at {MEMORY_STEP_DEG} deg (n = {n}); "
          f"max_chunk_elements = 2**22 -> {chunk_points:,} points per chunk")  # fmt: skip
    middle = grid.shape[0] // 2  # rows through the base, where most points are reachable
    bands = [grid] if full else [grid[middle - 6 : middle + 6], grid[middle - 24 : middle + 24]]
    for band in bands:
        points = band.reshape(-1, 2)
        peak, seconds = traced_peak(points, step)
        result = 8 * len(points)
        label = "whole grid" if full else f"{band.shape[0]:>2} rows"
        print(
            f"  {label}: {len(points):>9,} points, {math.ceil(len(points) / chunk_points):>3} "
            f"chunks: peak {peak / 2**20:7.2f} MiB = d_z result {result / 2**20:6.2f} MiB + "
            f"working set {(peak - result) / 2**20:5.2f} MiB  ({seconds:.1f} s under tracemalloc, "
            f"{len(points) * n / seconds / 1e6:.1f} M/s)"
        )
    small = grid[middle - 6 : middle + 6].reshape(-1, 2)
    peak, _ = traced_peak(small, step, max_chunk_elements=n * 4)
    print(
        f"  12 rows, max_chunk_elements = 4 n: working set "
        f"{(peak - 8 * len(small)) / 2**20:5.2f} MiB"
    )
    print(
        "  The working set is set by the chunk size (computed in cache blocks of at most\n"
        "  min(max_chunk_elements, 2**14) elements, ~110 bytes each), not by the grid: only\n"
        "  the d_z result (8 bytes per point) grows with the grid."
    )


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points-per-axis", type=int, default=501)
    parser.add_argument("--step-deg", type=float, default=1.0)
    parser.add_argument(
        "--full-2001", action="store_true", help="trace the whole 2001 x 2001 grid at 0.5 deg"
    )
    args = parser.parse_args(argv)
    rng = np.random.default_rng(2012)
    step = math.radians(args.step_deg)
    print(f"numpy {np.__version__}; links {LINKS}; step {args.step_deg} deg")
    print(blas_note())
    grid = square_grid(args.points_per_axis)
    compare_exact(grid, step, rng)
    compare_limited(grid, step, rng)
    memory(args.full_2001)


if __name__ == "__main__":
    main()
