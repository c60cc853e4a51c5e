"""Orientation samples of a prescribed SPM workspace (docs/methods/spherical-parallel.md).

The paper says only "4 x 12 x 3 = 144". Read literally: psi1 at ``azimuth`` evenly
spaced azimuths from 0; psi2 at the mid-points of ``tilt`` equal-volume cells of
[0, T] (the Haar measure is proportional to sin(psi2) dpsi1 dpsi2 dpsi3, so every sample
then carries the same weight and GCI is a plain mean, eq 24); psi3 at ``torsion``
evenly spaced values over a full turn from the torsion origin, or evenly spaced values
including both ends of a limited range. Angles are in radians.
"""

from __future__ import annotations

import math
import numbers
from typing import TypedDict

import numpy as np

from worker.common.parameter_errors import bad_parameter
from worker.families.spherical_parallel.kinematics.model import (
    FloatArray,
    Workspace,
    checked_workspace,
)

__all__ = ["DEFAULT_COUNTS", "SampleLayout", "boundary_grid", "orientation_samples"]

#: (azimuth, tilt, torsion) counts of the paper's 4 x 12 x 3 = 144 samples.
DEFAULT_COUNTS = (4, 12, 3)


class SampleLayout(TypedDict):
    """How the samples of :func:`orientation_samples` were laid out (angles in rad).

    The samples are the product psi1 x psi2 x psi3 in that order (psi1 slowest).
    """

    n: int
    counts: tuple[int, int, int]
    psi1: tuple[float, ...]
    psi2: tuple[float, ...]
    psi3: tuple[float, ...]
    psi1_rule: str
    psi2_rule: str
    psi3_rule: str
    equal_weights: bool


def _count(value: object, parameter: str, function: str) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 1:
        raise bad_parameter(parameter, function, "a positive integer", value)
    return int(value)


def _torsion_values(ws: Workspace, count: int) -> tuple[FloatArray, str]:
    lo, hi = ws.torsion
    if ws.full_turn:
        values = lo + 2.0 * np.pi * np.arange(count) / count
        return values, f"{count} evenly spaced over a full turn from the torsion origin lo"
    if count == 1:
        return np.array([0.5 * (lo + hi)]), "the mid-point of [lo, hi]"
    return np.linspace(lo, hi, count), f"{count} evenly spaced over [lo, hi], both ends included"


def orientation_samples(
    ws: Workspace, azimuth: int = 4, tilt: int = 12, torsion: int = 3
) -> tuple[FloatArray, SampleLayout]:
    """The default (and denser) equal-weight samples of ``ws``.

    psi1_k = 2 pi k / azimuth; psi2_k = acos(1 - (1 - cos T)(k - 1/2) / tilt), k = 1..tilt
    (equal-volume cell mid-points, T = ``ws.tilt_max``); psi3 as in the module doc.
    Returns samples (azimuth * tilt * torsion, 3) rad ``[psi1, psi2, psi3]`` and their
    :class:`SampleLayout`. The defaults give the paper's 144 orientations.
    """
    function = "orientation_samples"
    checked_workspace(ws, function)
    n1, n2, n3 = (_count(c, p, function) for c, p in ((azimuth, "azimuth"), (tilt, "tilt"),
                                                        (torsion, "torsion")))  # fmt: skip
    psi1 = 2.0 * np.pi * np.arange(n1) / n1
    cells = (np.arange(1, n2 + 1) - 0.5) / n2
    psi2 = np.arccos(1.0 - (1.0 - math.cos(ws.tilt_max)) * cells)
    psi3, psi3_rule = _torsion_values(ws, n3)
    grid = np.stack(np.meshgrid(psi1, psi2, psi3, indexing="ij"), axis=-1).reshape(-1, 3)
    layout = SampleLayout(
        n=n1 * n2 * n3,
        counts=(n1, n2, n3),
        psi1=tuple(float(x) for x in psi1),
        psi2=tuple(float(x) for x in psi2),
        psi3=tuple(float(x) for x in psi3),
        psi1_rule=f"{n1} evenly spaced azimuths from 0",
        psi2_rule=f"mid-points of {n2} equal-volume cells: acos(1 - (1 - cos T)(k - 1/2)/{n2})",
        psi3_rule=psi3_rule,
        equal_weights=True,
    )
    return grid, layout


def boundary_grid(
    ws: Workspace, azimuth: int = 24, tilt: int = 13, torsion: int = 72
) -> FloatArray:
    """A plain grid over the closed workspace, boundary included, for extreme values.

    psi1 over one 120° period [0, 2 pi / 3) (kappa has period 120° in psi1 for every
    design, docs/methods/spherical-parallel.md), psi2 = linspace(0, T, tilt), psi3 over a
    full turn (from the torsion origin, ``torsion`` values) or linspace(lo, hi, torsion).
    Not equal-weight: use it for minima, not means. Returns (azimuth * tilt * torsion, 3)
    rad.
    """
    function = "boundary_grid"
    checked_workspace(ws, function)
    n1, n2, n3 = (_count(c, p, function) for c, p in ((azimuth, "azimuth"), (tilt, "tilt"),
                                                        (torsion, "torsion")))  # fmt: skip
    psi1 = (2.0 * np.pi / 3.0) * np.arange(n1) / n1
    psi2 = np.linspace(0.0, ws.tilt_max, n2)
    lo, hi = ws.torsion
    psi3 = lo + 2.0 * np.pi * np.arange(n3) / n3 if ws.full_turn else np.linspace(lo, hi, n3)
    return np.stack(np.meshgrid(psi1, psi2, psi3, indexing="ij"), axis=-1).reshape(-1, 3)
