"""Input normalisation of the three-link planar arm's figures, once at the public entry.

Each check returns its argument as plain floats or arrays, or raises a ValueError
naming the parameter and the figure function; :class:`DexterityMap` and
:class:`Overlay` carry the checked data to the panels of
:mod:`worker.families.planar_serial.plots.panels`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from worker.common.figures import bad_figure_argument

__all__ = [
    "DexterityMap",
    "FloatArray",
    "Overlay",
    "checked_bands",
    "checked_labels",
    "checked_lengths",
    "checked_map",
    "checked_overlay",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class DexterityMap:
    """A validated map: ascending ``x`` (nx,), ``y`` (ny,), ``d_z`` (ny, nx), circles."""

    x: FloatArray
    y: FloatArray
    d_z: FloatArray
    region_radii: tuple[float, ...]
    bands: tuple[tuple[float, float], ...]
    base: tuple[float, float] = (0.0, 0.0)


@dataclass(frozen=True)
class Overlay:
    """Drawn over every map: task points (k, 2) with their labels, a trajectory (m, 2)."""

    points: FloatArray
    labels: tuple[str, ...]
    trajectory: FloatArray | None


def checked_map(
    x: ArrayLike, y: ArrayLike, d_z: ArrayLike, region_radii: Sequence[float],
    bands: Sequence[tuple[float, float]], where: str, base: Sequence[float] = (0.0, 0.0),
) -> DexterityMap:  # fmt: skip
    xs, ys, dz = (np.asarray(v, dtype=float) for v in (x, y, d_z))
    for name, v in (("x", xs), ("y", ys)):
        step = np.diff(v) if v.ndim == 1 else np.array([np.nan])
        if v.size < 2 or not np.isfinite(v).all() or not (all(step > 0) or all(step < 0)):
            raise bad_figure_argument(
                name,
                where,
                "a strictly monotonic finite array of shape (n,), n >= 2",
                f"shape {v.shape}",
            )
    if dz.shape != (ys.size, xs.size):
        raise bad_figure_argument(
            "d_z", where, f"an array of shape (ny, nx) = {(ys.size, xs.size)}", f"shape {dz.shape}"
        )
    if xs[0] > xs[-1]:
        xs, dz = xs[::-1], dz[:, ::-1]
    if ys[0] > ys[-1]:
        ys, dz = ys[::-1], dz[::-1, :]
    radii = checked_lengths(
        region_radii, "region_radii", where, 3 if len(region_radii) else 0, signed=True
    )  # l1 + l2 - l3 < 0 just means an empty region 2
    bx, by = checked_lengths(base, "base", where, 2, signed=True)
    return DexterityMap(xs, ys, dz, radii, checked_bands(bands, where), (bx, by))


def checked_lengths(
    value: Sequence[float], name: str, where: str, count: int | None, *, signed: bool = False
) -> tuple[float, ...]:
    arr = np.asarray(value, dtype=float)
    wrong_size = arr.ndim != 1 or (count is not None and arr.size != count)
    if wrong_size or not np.isfinite(arr).all() or (not signed and (arr < 0).any()):
        kind = "finite" if signed else "finite non-negative"
        expected = f"{'a list of' if count is None else count} {kind} lengths"
        raise bad_figure_argument(name, where, expected, repr(value))
    return tuple(float(v) for v in arr)


def checked_bands(
    value: Sequence[tuple[float, float]], where: str
) -> tuple[tuple[float, float], ...]:
    arr = np.asarray(value, dtype=float)
    arr = arr.reshape(0, 2) if arr.size == 0 else arr
    if (
        arr.ndim != 2
        or arr.shape[1] != 2
        or not np.isfinite(arr).all()
        or ((arr[:, 0] < 0).any() or (arr[:, 0] > arr[:, 1]).any())
    ):
        raise bad_figure_argument(
            "bands", where, "a list of (lo, hi) radius pairs with 0 <= lo <= hi", repr(value)
        )
    return tuple((float(lo), float(hi)) for lo, hi in arr)


def checked_labels(labels: Sequence[str] | None, count: int, where: str) -> tuple[str, ...]:
    """The given labels, or A, B, C, … when there are none."""
    if labels is None:
        return tuple(chr(ord("A") + i) if i < 26 else f"P{i + 1}" for i in range(count))
    if isinstance(labels, str) or len(labels) != count:
        raise bad_figure_argument(
            "task_labels", where, f"a list of {count} labels, one per point", repr(labels)
        )
    return tuple(str(label) for label in labels)


def checked_overlay(
    task_points: ArrayLike | None, task_labels: Sequence[str] | None,
    trajectory: ArrayLike | None, where: str,
) -> Overlay:  # fmt: skip
    pts = np.asarray([] if task_points is None else task_points, dtype=float)
    pts = pts.reshape(0, 2) if pts.size == 0 else pts
    if pts.ndim != 2 or pts.shape[1] != 2 or not np.isfinite(pts).all():
        raise bad_figure_argument(
            "task_points", where, "a finite array of shape (k, 2)", f"shape {pts.shape}"
        )
    path = None if trajectory is None else np.asarray(trajectory, dtype=float)
    if path is not None and (path.ndim != 2 or path.shape[1] != 2 or len(path) < 2):
        raise bad_figure_argument(
            "trajectory", where, "an array of shape (m, 2), m >= 2", f"shape {path.shape}"
        )
    return Overlay(pts, checked_labels(task_labels, len(pts), where), path)
