"""Arrays as the plain JSON values a preview answers (:mod:`worker.previews`)."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["axis_values", "grid_values", "map_entry"]

#: Significant digits kept: a heat map and its hover need no more, and the answer
#: stays small (a 101 x 101 map is ~80 kB of JSON).
DIGITS = 6


def axis_values(values: ArrayLike) -> list[float]:
    """An axis (n,) as a list of floats, rounded to :data:`DIGITS` significant digits."""
    array = np.asarray(values, dtype=float)
    return [float(f"{v:.{DIGITS}g}") for v in array.tolist()]


def grid_values(values: ArrayLike) -> list[list[float | None]]:
    """A map (ny, nx) as ny rows of nx values, NaN and infinities as None, rounded to
    :data:`DIGITS` significant digits."""
    array = np.asarray(values, dtype=float)
    if array.ndim != 2:
        raise ValueError(f"a map is (ny, nx); got shape {array.shape}")
    finite = np.isfinite(array)
    scale = np.where(finite & (array != 0.0), np.abs(array), 1.0)
    decimals = np.minimum(DIGITS - 1 - np.floor(np.log10(scale)), 300.0)  # 10**300 is finite
    factor = 10.0**decimals
    rounded = np.where(finite, np.round(array * factor) / factor, np.nan)
    return [[None if v != v else v for v in row] for row in rounded.tolist()]


def map_entry(
    title: str,
    x: tuple[ArrayLike, str, str],
    y: tuple[ArrayLike, str, str],
    z: tuple[ArrayLike, str, str],
) -> dict[str, Any]:
    """One heat map of a preview: ``x``, ``y`` (values (nx,), (ny,); label; unit) and
    ``z`` (values (ny, nx); label; unit)."""
    return {
        "title": title,
        "x": axis_values(x[0]), "x_label": x[1], "x_unit": x[2],
        "y": axis_values(y[0]), "y_label": y[1], "y_unit": y[2],
        "z": grid_values(z[0]), "z_label": z[1], "z_unit": z[2],
    }  # fmt: skip
