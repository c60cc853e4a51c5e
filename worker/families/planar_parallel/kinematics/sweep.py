"""The global design step of Huang et al. (2004) §III-C-2: sweep delta over the eq-(12)
family, find W_lambda for each, and rank by eta = (S / S_max) * mean 1/kappa (eq 13).

Re-exported by :mod:`worker.families.planar_parallel.kinematics`. All deltas of a chunk are
solved together (one batched column scan, one batched rectangle solve, one batched
mesh), so the default sweep (151 deltas, 101 x 101 mesh) takes about a second.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from worker.common.parameter_errors import bad_parameter
from worker.families.planar_parallel.kinematics.columns import ArchitectureBatch, isotropic_batch
from worker.families.planar_parallel.kinematics.model import (
    FloatArray,
    checked_limit,
    checked_mode,
    is_mirror_symmetric,
)
from worker.families.planar_parallel.kinematics.pressure import min_pressure_angle_in_rectangle
from worker.families.planar_parallel.kinematics.rectangle import solve_rectangles
from worker.families.planar_parallel.kinematics.workspace import Rectangle, rectangle_from_arrays

__all__ = ["DesignSweep", "SweepRow", "design_sweep"]


@dataclass(frozen=True)
class SweepRow:
    """One delta of the sweep (l1 = 1, l2 = delta, e by eq 12).

    rectangle: W_lambda; mean_inverse_condition: eq (14) on the mesh x mesh nodes;
    min_pressure_angle_deg: exact min of beta_min over W_lambda (eq 15); area_ratio:
    Delta_s = S / S_max; eta = area_ratio * mean_inverse_condition (eq 13). NaN when
    the rectangle was not found.
    """

    delta: float
    e: float
    limit: float
    rectangle: Rectangle
    mean_inverse_condition: float
    min_pressure_angle_deg: float
    area_ratio: float
    eta: float


@dataclass(frozen=True)
class DesignSweep:
    """The sweep: rows in delta order, S_max (over the swept deltas), eta (n,), the
    optimum's index (-1 if no rectangle was found), and window = (delta_lo, delta_hi), the
    contiguous run of swept deltas around the optimum whose eta is within
    ``window_tolerance`` (0.001) of the maximum. found False (NaN fields) if no delta had
    a rectangle; message sums up."""

    rows: tuple[SweepRow, ...]
    deltas: FloatArray
    S_max: float
    eta: FloatArray
    optimum: int
    window: tuple[float, float]
    found: bool
    message: str
    limit: float
    aspect_ratio: float
    mesh: int


def _checked_deltas(deltas: ArrayLike) -> FloatArray:
    requirement = "a non-empty increasing 1-D array of finite ratios l2 / l1 >= 1"
    try:
        arr = np.array(deltas, dtype=np.float64)  # a copy: the result keeps it
    except (TypeError, ValueError):
        raise bad_parameter("deltas", "design_sweep", requirement, deltas) from None
    if not (arr.ndim == 1 and arr.size > 0 and np.all(np.isfinite(arr)) and np.all(arr >= 1.0)
            and np.all(np.diff(arr) > 0.0)):  # fmt: skip
        raise bad_parameter("deltas", "design_sweep", requirement, deltas)
    return arr


def _checked_settings(aspect_ratio: float, window_tolerance: float, **counts: int) -> None:
    for name, value in (("aspect_ratio", aspect_ratio), ("window_tolerance", window_tolerance)):
        if not (isinstance(value, numbers.Real) and not isinstance(value, bool)
                and math.isfinite(float(value)) and float(value) >= 0.0
                and (name != "aspect_ratio" or float(value) > 0.0)):  # fmt: skip
            rule = "a positive ratio b/h" if name == "aspect_ratio" else "a non-negative number"
            raise bad_parameter(name, "design_sweep", rule, value)
    minimum = {"mesh": 2, "chunk": 1, "columns": 3, "rows": 3, "boundary_samples": 2}
    for name, value in counts.items():
        if not (isinstance(value, numbers.Integral) and not isinstance(value, bool)
                and int(value) >= minimum[name]):  # fmt: skip
            raise bad_parameter(name, "design_sweep", f"an integer >= {minimum[name]}", value)


def _mesh_means(
    batch: ArchitectureBatch,
    found: np.ndarray,
    rect: tuple[FloatArray, FloatArray, FloatArray],
    mesh: int,
) -> FloatArray:
    """Eq (14) per row, (B,): mean 1/kappa over the mesh x mesh nodes of the rectangles
    rect = (w, bottom, h) (each (B,)); NaN where not found. A node out of reach by a
    rounding hair (a rectangle touching the reach boundary, where 1/kappa -> 0) counts 0,
    the continuous extension the boundary search uses.

    In a mirror-symmetric mode 1/kappa(-x, y) = 1/kappa(x, y): only the node columns with
    x >= 0 are evaluated and the others counted through their mirror images.
    """
    w, bottom, h = rect
    t = np.linspace(0.0, 1.0, mesh)
    weights = np.ones(mesh)
    if is_mirror_symmetric(batch.template, batch.mode):
        t, weights = t[mesh // 2 :], np.full(mesh - mesh // 2, 2.0)
        if mesh % 2:
            weights[0] = 1.0  # the centre column x = 0 is its own mirror image
    ok = found[:, None, None]
    x = np.where(ok, (-w)[:, None, None] + (2.0 * w)[:, None, None] * t, 0.0)
    y = np.where(ok, bottom[:, None, None] + h[:, None, None] * np.linspace(0.0, 1.0, mesh)[
        :, None], -1.0)  # fmt: skip
    total = np.sum(batch.extended_inverse_condition(x, y) * weights, axis=(1, 2))
    return np.where(found, total / (mesh * mesh), np.nan)


def _window(deltas: FloatArray, eta: FloatArray, best: int, tolerance: float) -> tuple[int, int]:
    close = np.nan_to_num(eta, nan=-np.inf) >= eta[best] - tolerance
    lo = best
    while lo > 0 and close[lo - 1]:
        lo -= 1
    hi = best
    while hi < deltas.size - 1 and close[hi + 1]:
        hi += 1
    return lo, hi


def design_sweep(
    limit: float,
    deltas: ArrayLike,
    aspect_ratio: float = 4.0,
    mesh: int = 101,
    on_row: Callable[[int, int], None] | None = None,
    *,
    working_mode: tuple[int, int] = (1, -1),
    columns: int = 129,
    rows: int = 128,
    boundary_samples: int = 256,
    window_tolerance: float = 1e-3,
    chunk: int = 32,
) -> DesignSweep:
    """W_lambda, mean 1/kappa and eta for each delta of the eq-(12) proximal-arm family.

    limit: 1/kappa0 (e.g. :func:`max_condition_limit`'s, or the paper's printed 0.526);
    deltas (n,) >= 1, increasing; mesh: nodes per side for eq (14); on_row(done, n) is
    called as rows complete (in chunks of ``chunk`` deltas). Rectangle settings as
    :func:`largest_rectangle`. S_max is taken over the swept deltas (the paper's
    [1, 2.5] by default, docs/methods/planar-parallel.md).
    """
    value = checked_limit(limit, "design_sweep")
    ds = _checked_deltas(deltas)
    _checked_settings(aspect_ratio, window_tolerance, mesh=mesh, chunk=chunk, columns=columns,
                      rows=rows, boundary_samples=boundary_samples)  # fmt: skip
    mode = checked_mode(working_mode, "design_sweep")
    aspect, mesh, chunk = float(aspect_ratio), int(mesh), int(chunk)
    pieces: list[tuple[Rectangle, float, float]] = []
    for start in range(0, ds.size, chunk):
        batch = isotropic_batch(ds[start : start + chunk], value, mode)
        reach = 1.0 + batch.l2
        rects = solve_rectangles(
            batch, aspect, (reach - batch.e, -reach, reach), columns, rows, boundary_samples
        )
        w, h, centre = rects.w, rects.h, rects.centre
        means = _mesh_means(batch, rects.found, (w, centre - h / 2.0, h), mesh)
        betas = min_pressure_angle_in_rectangle(
            batch.template, batch.l2, batch.e, w, centre - h / 2.0, centre + h / 2.0
        )
        for k in range(batch.size):
            rect = rectangle_from_arrays(rects, k, value, aspect, boundary_samples)
            pieces.append((rect, float(means[k]), math.degrees(float(betas[k]))))
            if on_row is not None:
                on_row(len(pieces), ds.size)
    areas = np.array([rect.S for rect, _, _ in pieces])
    means_all = np.array([mean for _, mean, _ in pieces])
    found = bool(np.any(np.isfinite(areas)))
    s_max = float(np.nanmax(areas)) if found else math.nan
    ratio = areas / s_max if found else np.full(ds.size, np.nan)
    eta = ratio * means_all
    result_rows = tuple(
        SweepRow(float(d), math.sqrt(0.5) * (float(d) - 1.0), value, rect, mean, beta,
                 float(ratio[k]), float(eta[k]))
        for k, (d, (rect, mean, beta)) in enumerate(zip(ds, pieces, strict=True))
    )  # fmt: skip
    if not found:
        message = f"no rectangle fits W_kappa0 at 1/kappa >= {value:g} for any swept delta"
        return DesignSweep(result_rows, ds, math.nan, eta, -1, (math.nan, math.nan), False,
                           message, value, aspect, mesh)  # fmt: skip
    best = int(np.nanargmax(eta))
    lo, hi = _window(ds, eta, best, window_tolerance)
    message = (
        f"eta max {eta[best]:.4f} at delta = {ds[best]:.4g} (S = {areas[best]:.4f}, "
        f"mean 1/kappa = {means_all[best]:.4f} on {mesh} x {mesh} nodes); eta within "
        f"{window_tolerance:g} of it on delta in [{ds[lo]:.4g}, {ds[hi]:.4g}]; S_max = "
        f"{s_max:.4f} over the {ds.size} swept deltas"
    )
    return DesignSweep(result_rows, ds, s_max, eta, best, (float(ds[lo]), float(ds[hi])), True,
                       message, value, aspect, mesh)  # fmt: skip
