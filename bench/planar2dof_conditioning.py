"""Benchmark the 2-DOF planar parallel kernels against straightforward per-point code.

    python bench/planar2dof_conditioning.py [--points-per-axis 1001] [--subset 4000]
                                            [--naive-deltas 1.7 2.2] [--region-grid 2001]

Everything printed is measured in this run:

1. conditioning_map (1/kappa, pressure angles, joints) on a square grid around the
   reach of the eq-(12) design with delta = 1.7, vs sampled_inverse_condition (IK, J,
   numpy SVD, one point at a time) looped over the grid;
2. design_sweep over delta = 1, 1.01, ..., 2.5 (the default: 101 x 101 mesh, the
   paper's printed limit 0.526, lambda = 4), at the function's default rectangle search
   and at the finer one the planar2dof-optimisation job uses (its default sweep), vs a
   straightforward sweep: for each delta
   a golden-section search over the centre H' around a bisection on h, each trial
   rectangle checked point by point with sampled_inverse_condition on its boundary
   (60 points per edge, stopping at the first failure), then the mean over the
   101 x 101 mesh point by point. Sampling the boundary misses the tangency between
   samples, so that rectangle pokes slightly out of W_kappa0; both are checked densely.

3. kappa_region_boundary (W_kappa0 with the job's 801 columns and 321 rows, every run of
   every column, columns added where it is thin or ends) on the designs of the worked
   examples of planar2dof-conditioning-map and on a thin set (two wedges of 1.5e-4 at
   corners of the reach), vs counting the nodes of a square grid over the same box.

The per-point loops over everything would take minutes to hours, so the map reference is
timed on a random subset of grid points and the straightforward sweep on a few deltas,
each scaled linearly; the printout says so.
"""

from __future__ import annotations

import argparse
import inspect
import math
import os
import time
from functools import partial

import numpy as np
from timing import best_time

from worker.families.planar_parallel.discretisation import (
    BOUNDARY_COLUMNS,
    BOUNDARY_ROWS,
    RECTANGLE_BOUNDARY_SAMPLES,
    RECTANGLE_COLUMNS,
    RECTANGLE_ROWS,
)
from worker.families.planar_parallel.examples import CONDITIONING_MAP_EXAMPLES
from worker.families.planar_parallel.jobs.architecture import architecture_from_spec
from worker.families.planar_parallel.kinematics import (
    Architecture,
    conditioning_map,
    design_sweep,
    inverse_condition,
    isotropic_architecture,
    isotropic_point,
    kappa_region_boundary,
    sampled_inverse_condition,
    workspace_area,
)
from worker.families.planar_parallel.kinematics.columns import search_box
from worker.families.planar_parallel.specs import ConditioningMapSpec

LIMIT = 0.526
ASPECT = 4.0
MESH = 101
EDGE_POINTS = 60
SWEEP_DELTAS = np.round(np.arange(1.0, 2.5 + 1e-9, 0.01), 10)
DEFAULT_COLUMNS = inspect.signature(design_sweep).parameters["columns"].default


def square_grid(arch: Architecture, points_per_axis: int) -> tuple[np.ndarray, np.ndarray]:
    reach = arch.l1 + arch.l2
    axis = np.linspace(-reach, reach, points_per_axis)
    return axis, axis.copy()


def compare_map(points_per_axis: int, subset: int, rng: np.random.Generator) -> None:
    arch = isotropic_architecture(1.7)
    x, y = square_grid(arch, points_per_axis)
    total = x.size * y.size
    fast = best_time(lambda: conditioning_map(arch, x, y), repeat=3)
    grid = np.stack(np.meshgrid(x, y), -1)  # built outside the timing
    kernel = best_time(lambda: inverse_condition(arch, grid), 3)
    flat = grid.reshape(-1, 2)
    chosen = flat[rng.choice(total, size=min(subset, total), replace=False)]
    start = time.perf_counter()
    reference = [sampled_inverse_condition(arch, (float(px), float(py))) for px, py in chosen]
    per_point = (time.perf_counter() - start) / len(chosen)
    naive = per_point * total
    ours = inverse_condition(arch, chosen)
    both = np.isfinite(ours)
    worst = float(np.max(np.abs(ours[both] - np.asarray(reference)[both])))
    same_nan = bool(np.array_equal(np.isnan(ours), np.isnan(reference)))
    print(f"\n[1] conditioning map, delta = 1.7, {x.size} x {y.size} = {total:,} points")
    print(f"  conditioning_map (1/kappa, angles, joints):  {fast:8.3f} s")
    print(f"  inverse_condition alone (eq 7, points given): {kernel:7.3f} s")
    print(
        f"  sampled_inverse_condition loop (SVD):        {naive:8.1f} s  (timed on "
        f"{len(chosen):,} random grid points, {per_point * 1e6:.1f} us/point, scaled)"
    )
    print(f"  speed-up of the map: {naive / fast:,.0f}x; of eq (7) alone: {naive / kernel:,.0f}x")
    print(f"  on the subset: max |eq 7 - SVD| = {worst:.1e}; same unreachable points: {same_nan}")


def boundary_fits(arch: Architecture, h: float, centre: float) -> bool:
    """Every one of EDGE_POINTS per edge has 1/kappa >= LIMIT (first failure stops)."""
    w = ASPECT * h / 2.0
    t = np.linspace(0.0, 1.0, EDGE_POINTS)
    edges = [(-w + 2 * w * s, centre + h / 2) for s in t] + [(-w + 2 * w * s, centre - h / 2)
             for s in t] + [(-w, centre - h / 2 + h * s) for s in t] + [
             (w, centre - h / 2 + h * s) for s in t]  # fmt: skip
    for px, py in edges:
        value = sampled_inverse_condition(arch, (px, py))
        if not value >= LIMIT:  # NaN fails too
            return False
    return True


def tallest_at(arch: Architecture, centre: float, iterations: int = 30) -> float:
    low, high = 0.0, 2.0 * (arch.l1 + arch.l2)
    for _ in range(iterations):
        mid = 0.5 * (low + high)
        low, high = (mid, high) if boundary_fits(arch, mid, centre) else (low, mid)
    return low


def straightforward_row(delta: float) -> tuple[float, float, float]:
    """(h, H', mean 1/kappa) the straightforward way."""
    arch = isotropic_architecture(delta)
    depth = -isotropic_point(arch)[1]
    a, b = 0.25 * depth, depth
    ratio = (math.sqrt(5.0) - 1.0) / 2.0
    c, d = b - ratio * (b - a), a + ratio * (b - a)
    fc, fd = tallest_at(arch, -c), tallest_at(arch, -d)
    for _ in range(25):
        if fc > fd:
            b, d, fd = d, c, fc
            c = b - ratio * (b - a)
            fc = tallest_at(arch, -c)
        else:
            a, c, fc = c, d, fd
            d = a + ratio * (b - a)
            fd = tallest_at(arch, -d)
    h, centre = (fc, c) if fc > fd else (fd, d)
    xs = np.linspace(-ASPECT * h / 2, ASPECT * h / 2, MESH)
    ys = np.linspace(-centre - h / 2, -centre + h / 2, MESH)
    mean = float(np.mean([sampled_inverse_condition(arch, (px, py)) for py in ys for px in xs]))
    return h, centre, mean


def job_sweep() -> object:
    """The sweep as the planar2dof-optimisation job runs it (its finer rectangle search)."""
    return design_sweep(
        LIMIT, SWEEP_DELTAS, ASPECT, MESH, columns=RECTANGLE_COLUMNS, rows=RECTANGLE_ROWS,
        boundary_samples=RECTANGLE_BOUNDARY_SAMPLES, chunk=16,
    )  # fmt: skip


def compare_sweep(naive_deltas: list[float]) -> None:
    fast = best_time(lambda: design_sweep(LIMIT, SWEEP_DELTAS), repeat=2)
    job = best_time(job_sweep, repeat=2)
    result = design_sweep(LIMIT, SWEEP_DELTAS)
    start = time.perf_counter()
    rows = [straightforward_row(delta) for delta in naive_deltas]
    per_delta = (time.perf_counter() - start) / len(naive_deltas)
    naive = per_delta * SWEEP_DELTAS.size
    print(f"\n[2] design sweep, delta = 1 .. 2.5 step 0.01 ({SWEEP_DELTAS.size} deltas), "
          f"1/kappa0 = {LIMIT}, lambda = {ASPECT:g}, {MESH} x {MESH} mesh")  # fmt: skip
    labels = (f"design_sweep, its defaults ({DEFAULT_COLUMNS} columns):",
              f"design_sweep as the job runs it ({RECTANGLE_COLUMNS} columns):",
              "straightforward sweep (per-point SVD):")  # fmt: skip
    width = max(len(label) for label in labels) + 1
    print(f"  {labels[0]:<{width}}{fast:8.2f} s")
    print(f"  {labels[1]:<{width}}{job:8.2f} s")
    print(
        f"  {labels[2]:<{width}}{naive:8.0f} s  (timed on delta = "
        f"{', '.join(f'{d:g}' for d in naive_deltas)}: {per_delta:.1f} s/delta, scaled)"
    )
    print(f"  speed-up: {naive / fast:,.0f}x (as the job runs it: {naive / job:,.0f}x); "
          f"{result.message}")  # fmt: skip
    for delta, (h, centre, mean) in zip(naive_deltas, rows, strict=True):
        row = result.rows[int(np.argmin(np.abs(result.deltas - delta)))]
        arch = isotropic_architecture(delta)
        naive_min = dense_boundary_minimum(arch, h, centre)
        ours_min = dense_boundary_minimum(arch, row.rectangle.h, row.rectangle.H_prime)
        print(
            f"  delta {delta:g}: straightforward h {h:.5f} H' {centre:.5f} mean {mean:.5f} "
            f"(min 1/kappa on its boundary {naive_min:.5f});\n"
            f"{' ' * (11 + len(f'{delta:g}'))}design_sweep h {row.rectangle.h:.5f} "
            f"H' {row.rectangle.H_prime:.5f} mean {row.mean_inverse_condition:.5f} "
            f"(min 1/kappa on its boundary {ours_min:.5f})"
        )
    print(f"  (boundary minima on 4 x 20,001 points; the limit is {LIMIT})")


def dense_boundary_minimum(arch: Architecture, h: float, centre: float) -> float:
    w, t = ASPECT * h / 2.0, np.linspace(0.0, 1.0, 20_001)
    xs, ys = -w + 2.0 * w * t, -centre - h / 2.0 + h * t
    top, bottom = -centre + h / 2.0, -centre - h / 2.0
    ones = np.ones_like(t)
    edges = [(xs, top * ones), (xs, bottom * ones), (-w * ones, ys), (w * ones, ys)]
    return float(min(np.min(inverse_condition(arch, np.stack(e, -1))) for e in edges))


def region_cases() -> list[tuple[str, Architecture, tuple[int, int], float]]:
    """(label, design, working mode, limit): the worked examples with a limit, and a thin
    set."""
    cases: list[tuple[str, Architecture, tuple[int, int], float]] = []
    for example in CONDITIONING_MAP_EXAMPLES:
        spec = ConditioningMapSpec.model_validate(dict(example.inputs))
        limit = spec.inverse_condition_limit
        if limit is not None:
            label = f"{spec.actuation}, l2 = {spec.l2:g}, 1/kappa0 = {limit:g}"
            cases.append((label, architecture_from_spec(spec), spec.working_mode, limit))
    thin = Architecture("proximal-arm", 2.229, 4.8702, 1.2718)
    cases.append(("thin: l1 2.229, l2 4.8702, e 1.2718, (-1, -1), 0.543", thin, (-1, -1), 0.543))
    return cases


def node_count(
    arch: Architecture, mode: tuple[int, int], limit: float, x: np.ndarray, y: np.ndarray
) -> float:
    """The area of W_kappa0 by counting grid nodes."""
    values = np.nan_to_num(conditioning_map(arch, x, y, mode).inverse_condition, nan=-1.0)
    return workspace_area(values >= limit, x, y)


def compare_region(grid_points: int) -> None:
    print(f"\n[3] W_kappa0 ({BOUNDARY_COLUMNS} columns x {BOUNDARY_ROWS} rows, columns added "
          f"where thin or ending) vs a {grid_points} x {grid_points} node count")  # fmt: skip
    for label, arch, mode, limit in region_cases():
        region = kappa_region_boundary(arch, limit, mode)
        ours = best_time(partial(kappa_region_boundary, arch, limit, mode), 3)
        span, low, high = search_box(arch, limit)
        x, y = np.linspace(-span, span, grid_points), np.linspace(low, high, grid_points)
        grid_area = node_count(arch, mode, limit, x, y)
        grid_time = best_time(partial(node_count, arch, mode, limit, x, y), 1)
        print(f"  {label}:\n    kappa_region_boundary {ours * 1e3:7.1f} ms, area "
              f"{region.whole_area:.6g} (rectangle_region_area "
              f"{region.rectangle_region_area:.6g}), {region.added_columns} columns added; "
              f"node count {grid_time * 1e3:7.1f} ms, area {grid_area:.6g}")  # fmt: skip


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points-per-axis", type=int, default=1001)
    parser.add_argument("--subset", type=int, default=4000)
    parser.add_argument("--naive-deltas", type=float, nargs="+", default=[1.7, 2.2])
    parser.add_argument("--region-grid", type=int, default=2001)
    args = parser.parse_args(argv)
    threads = {name: os.environ.get(name, "unset") for name in ("OPENBLAS_NUM_THREADS",
                                                                "OMP_NUM_THREADS")}  # fmt: skip
    print(f"numpy {np.__version__}; {os.cpu_count()} CPUs; thread settings {threads}")
    print("  (the kernels are elementwise numpy: single-threaded, no BLAS)")
    compare_map(args.points_per_axis, args.subset, np.random.default_rng(2004))
    compare_sweep(args.naive_deltas)
    compare_region(args.region_grid)


if __name__ == "__main__":
    main()
