"""Benchmark exact d_z under joint limits (closed-form events) against orientation sampling.

    python bench/planar3r_limited_exact.py [--points-per-axis 2001] [--step-deg 0.5]

Everything printed is measured in this run, for the paper's Example 1 arm (15, 14, 8)
with the paper's joint limits (th1, th2 in [-150, 150] deg, th3 in [-175, 175] deg) on a
square grid 5% wider than the full reach:

1. the map: exact_limited_orientation_dexterity (method "exact-events") vs
   limited_orientation_dexterity sampled every --step-deg (method
   "orientation-sampling", today's 0.5 deg for a 2001 x 2001 map), both on one core;
   then the sampler's error measured against the exact values;
2. task points: the exact events vs the sampler refined by bisection to 1e-10 rad (the
   previous method for task points and trajectories), on random reachable points.

BLAS is pinned to one thread (the sampler's matrix products would otherwise use every
core; the exact method does not use BLAS), so the ratio compares one core with one.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import argparse
import math
import time

import numpy as np

from worker.families.planar_serial.kinematics import (
    limited_orientation_dexterity,
    orientation_samples,
    reach_radii,
)
from worker.families.planar_serial.kinematics.limited_exact import (
    exact_limited_orientation_dexterity,
)

LINKS = (15.0, 14.0, 8.0)
PAPER_LIMITS = np.radians([[-150.0, 150.0], [-150.0, 150.0], [-175.0, 175.0]])
TASK_POINTS = 20_000


def square_grid(points_per_axis: int) -> np.ndarray:
    half_width = 1.05 * reach_radii(LINKS)[1]
    axis = np.linspace(-half_width, half_width, points_per_axis)
    xs, ys = np.meshgrid(axis, axis)
    return np.stack([xs, ys], axis=-1)


def timed(function: object) -> tuple[np.ndarray, float]:
    start = time.perf_counter()
    value = function()  # type: ignore[operator]
    return np.asarray(value), time.perf_counter() - start


def compare_map(points_per_axis: int, step_deg: float) -> None:
    grid = square_grid(points_per_axis)
    step = math.radians(step_deg)
    n, _ = orientation_samples(step)
    cell = (grid[0, 1, 0] - grid[0, 0, 0]) ** 2
    exact, exact_s = timed(lambda: exact_limited_orientation_dexterity(LINKS, grid, PAPER_LIMITS))
    sampled, sampled_s = timed(
        lambda: limited_orientation_dexterity(LINKS, grid, PAPER_LIMITS, step)
    )
    error = sampled - exact
    reachable = exact > 0
    full_exact = np.count_nonzero(exact >= 1 - 1e-12) * cell
    full_sampled = np.count_nonzero(sampled >= 1 - 1e-12) * cell
    print(f"\n[1] map: {points_per_axis} x {points_per_axis} = {grid.size // 2:,} points, "
          f"paper limits")  # fmt: skip
    print(f"  exact events (exact_limited_orientation_dexterity): {exact_s:8.2f} s")
    print(f"  orientation sampling every {step_deg:g} deg (n = {n}):     {sampled_s:8.2f} s")
    print(f"  speed-up: {sampled_s / exact_s:.1f}x (target >= 10x)")
    print(f"  sampler's error against the exact values over {np.count_nonzero(reachable):,} "
          "reachable points:")  # fmt: skip
    print(f"    max |error| = {np.abs(error).max():.3e} ({np.abs(error).max() * n:.2f} samples), "
          f"mean |error| = {np.abs(error[reachable]).mean():.3e}, "
          f"RMS = {math.sqrt(np.mean(error[reachable] ** 2)):.3e}")  # fmt: skip
    print(f"    points off by more than one sample (1/{n}): "
          f"{np.count_nonzero(np.abs(error) > 1 / n + 1e-12):,}")  # fmt: skip
    print(f"    fully dexterous area (d_z = 1): exact {full_exact:.2f}, sampled "
          f"{full_sampled:.2f} ({100 * (full_sampled - full_exact) / full_exact:+.2f} %) "
          "square units")  # fmt: skip


def compare_points(rng: np.random.Generator) -> None:
    radius = reach_radii(LINKS)[1] * np.sqrt(rng.uniform(0, 1, TASK_POINTS))
    angle = rng.uniform(-math.pi, math.pi, TASK_POINTS)
    points = np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=-1)
    exact, exact_s = timed(lambda: exact_limited_orientation_dexterity(LINKS, points, PAPER_LIMITS))
    refined, refined_s = timed(
        lambda: limited_orientation_dexterity(
            LINKS, points, PAPER_LIMITS, math.radians(1.0), refine_tol=1e-10
        )
    )
    print(f"\n[2] {TASK_POINTS:,} random reachable task points")
    print(
        f"  exact events:                              {exact_s * 1e6 / TASK_POINTS:8.2f} us/point"
    )
    print(f"  1 deg sampling + bisection to 1e-10 rad:   "
          f"{refined_s * 1e6 / TASK_POINTS:8.2f} us/point")  # fmt: skip
    print(f"  speed-up: {refined_s / exact_s:.1f}x; max |difference| = "
          f"{np.abs(exact - refined).max():.2e} (the bisection misses arcs and gaps narrower "
          "than 1 deg)")  # fmt: skip


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points-per-axis", type=int, default=2001)
    parser.add_argument("--step-deg", type=float, default=0.5)
    args = parser.parse_args(argv)
    print(f"numpy {np.__version__}; links {LINKS}; BLAS threads "
          f"{os.environ['OPENBLAS_NUM_THREADS']}; {os.cpu_count()} CPUs")  # fmt: skip
    compare_map(args.points_per_axis, args.step_deg)
    compare_points(np.random.default_rng(2012))


if __name__ == "__main__":
    main()
