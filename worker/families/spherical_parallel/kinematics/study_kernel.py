"""Many SPM designs over one set of orientations at once (design studies).

The arithmetic of :meth:`~.indices.SampleSet.evaluate`, batched over designs: the
single-design functions (:func:`~.indices.workspace_indices`,
:func:`~.indices.workspace_minimum`, the conditioning map's reach check) call these
with one design, so a study's batched numbers and a job's are the same bits.

Designs are angles ``(m, 4)`` rad (alpha1, alpha2, beta, gamma); orientations are a
sample set's ``frame_terms`` ``(6, 3, n)`` (:class:`~.indices.SampleSet`). Work arrays
are ``(leg, m, n)``; :func:`design_tiles` cuts m so that m x n stays near
:data:`TILE_POSES` and temporaries stay bounded (about 40 arrays of that size).
Trigonometry of the design angles is taken one design at a time with :mod:`math`, as
the single-design code always did.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import NamedTuple

import numpy as np

from worker.families.spherical_parallel.kinematics.legs import REAL_TOLERANCE
from worker.families.spherical_parallel.kinematics.model import BoolArray, FloatArray

__all__ = [
    "TILE_POSES",
    "DesignTrig",
    "IndexArrays",
    "PoseArrays",
    "closing_orientations",
    "design_tiles",
    "design_trig",
    "evaluate_poses",
    "least_inverse_condition",
    "summarise",
]

#: Designs x orientations per tile of work arrays (32 kB each: the fastest on a 2-core
#: test machine, which keeps a tile's ~40 arrays in its caches).
TILE_POSES = 1 << 12

_ETA = 2.0 * np.pi * np.arange(3) / 3.0
_COS_ETA = np.cos(_ETA)[:, None, None]
_SIN_ETA = np.sin(_ETA)[:, None, None]
_TINY = 1e-300


class DesignTrig(NamedTuple):
    """Sines and cosines of m designs' angles, each ``(m, 1)``."""

    sa1: FloatArray
    ca1: FloatArray
    ca2: FloatArray
    sb: FloatArray
    cb: FloatArray
    sg: FloatArray
    cg: FloatArray


def design_trig(angles: FloatArray) -> DesignTrig:
    """:class:`DesignTrig` of designs ``(m, 4)`` rad (alpha1, alpha2, beta, gamma)."""
    rows = [
        (math.sin(a1), math.cos(a1), math.cos(a2), math.sin(b), math.cos(b), math.sin(g),
         math.cos(g))
        for a1, a2, b, g in np.asarray(angles, dtype=np.float64).reshape(-1, 4).tolist()
    ]  # fmt: skip
    table = np.array(rows, dtype=np.float64).reshape(-1, 7)
    return DesignTrig(*(table[:, k : k + 1] for k in range(7)))


def design_tiles(count: int, orientations: int) -> Iterator[slice]:
    """Slices of ``count`` designs, each with about :data:`TILE_POSES` poses."""
    size = max(1, TILE_POSES // max(orientations, 1))
    for start in range(0, count, size):
        yield slice(start, min(start + size, count))


def _leg_terms(
    frame_terms: FloatArray, trig: DesignTrig
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Platform axes v in the leg frames and P, Qc, R, rho^2 of the closure (eq 11),
    each ``(leg, m, n)``."""
    hk, hh, hz, zk, zh, zz = frame_terms[:, :, None, :]
    sb, cb = trig.sb, trig.cb
    vk, vh, vz = sb * hk + cb * zk, sb * hh + cb * zh, sb * hz + cb * zz
    p = (trig.ca1 * trig.sg) * vh - (trig.ca1 * trig.cg) * vz - trig.ca2
    qc = (trig.sa1 * trig.cg) * vh + (trig.sa1 * trig.sg) * vz
    r = trig.sa1 * vk
    return vk, vh, vz, p, qc, r, qc * qc + r * r


def closing_orientations(frame_terms: FloatArray, trig: DesignTrig) -> BoolArray:
    """``(m, n)``: whether all three legs close (eq 12) at each orientation; closure does
    not depend on the branch."""
    *_, p, _, _, rho2 = _leg_terms(frame_terms, trig)
    return np.asarray((np.abs(p) <= np.sqrt(rho2) + REAL_TOLERANCE).all(axis=0))


class PoseArrays(NamedTuple):
    """Per design and orientation, ``(m, n)``: 1/kappa (nan where a leg does not close),
    whether all legs close, det(A) (eq 30, nan likewise); input angles ``(m, n, 3)`` rad
    when asked for (None otherwise)."""

    inverse_condition: FloatArray
    real: BoolArray
    theta: FloatArray | None
    det_a: FloatArray


def _inverse_condition_legs_first(a: FloatArray, b: FloatArray) -> tuple[FloatArray, FloatArray]:
    """:func:`~.legs.inverse_condition_rows` for a ``(xyz, leg, ...)`` and b ``(leg, ...)``."""
    aj, ak = a[:, [1, 2, 0]], a[:, [2, 0, 1]]
    c = np.stack([aj[1] * ak[2] - aj[2] * ak[1], aj[2] * ak[0] - aj[0] * ak[2],
                  aj[0] * ak[1] - aj[1] * ak[0]])  # fmt: skip
    det_a = (a[:, 0] * c[:, 0]).sum(axis=0)
    pair = b[[1, 2, 0]] * b[[2, 0, 1]]
    norms = np.sqrt(((pair * pair) * (a * a).sum(axis=0)).sum(axis=0)
                    * ((b * b) * (c * c).sum(axis=0)).sum(axis=0))  # fmt: skip
    numerator = 3.0 * np.abs(det_a * b[0] * b[1] * b[2])
    inverse = np.divide(numerator, norms, out=np.zeros_like(numerator), where=norms > 0.0)
    return np.minimum(inverse, 1.0), det_a


def evaluate_poses(
    frame_terms: FloatArray, trig: DesignTrig, branch: int, *, theta: bool = True
) -> PoseArrays:
    """1/kappa, closure, det(A) (and theta) of m designs at n orientations.

    The closed form of :func:`~.legs.solve_legs` in the leg frames (see
    :class:`~.indices.SampleSet`), cos/sin th_i from the root without trigonometry.
    """
    vk, vh, vz, p, qc, r, rho2 = _leg_terms(frame_terms, trig)
    real_legs = np.abs(p) <= np.sqrt(rho2) + REAL_TOLERANCE
    root = np.sqrt(np.maximum(rho2 - p * p, 0.0))
    # th = atan2(R, Qc) - branch * acos(-P / rho), expanded; rho = 0 gives w = cos(a1) u.
    scale = 1.0 / np.maximum(rho2, _TINY)
    cos_th = (branch * r * root - p * qc) * scale
    sin_th = (-branch * qc * root - p * r) * scale
    sa1 = trig.sa1
    wk = sa1 * sin_th
    wh = (sa1 * trig.cg) * cos_th + trig.ca1 * trig.sg
    wz = (sa1 * trig.sg) * cos_th - trig.ca1 * trig.cg
    ak, ah = wh * vz - wz * vh, wz * vk - wk * vz
    a = np.stack([ak * _COS_ETA - ah * _SIN_ETA, ak * _SIN_ETA + ah * _COS_ETA,
                  wk * vh - wh * vk])  # fmt: skip
    inverse, det_a = _inverse_condition_legs_first(a, branch * root)
    real = np.asarray(real_legs.all(axis=0))
    angles = None
    if theta:
        angles = np.moveaxis(np.where(real_legs, np.arctan2(sin_th, cos_th), np.nan), 0, -1)
    return PoseArrays(np.where(real, inverse, np.nan), real, angles, np.where(real, det_a, np.nan))


class IndexArrays(NamedTuple):
    """The indices of m designs over equal-weight samples, each ``(m,)``: C_n (eq 25),
    mean(1/kappa^2) (eq 28), GCI (eq 24), min/max 1/kappa and min |det A|, nan unless
    ``all_real``; ``real_samples`` counts the samples where every leg closes."""

    rms_inverse_condition: FloatArray
    mean_square_inverse_condition: FloatArray
    gci: FloatArray
    min_inverse_condition: FloatArray
    max_inverse_condition: FloatArray
    min_abs_det_a: FloatArray
    all_real: BoolArray
    real_samples: FloatArray


def summarise(poses: PoseArrays) -> IndexArrays:
    """The :class:`IndexArrays` of :class:`PoseArrays` over equal-weight samples."""
    q = poses.inverse_condition
    all_real = np.asarray(poses.real.all(axis=-1))
    with np.errstate(invalid="ignore"):
        mean_square = np.mean(q * q, axis=-1)
        values = (
            np.sqrt(mean_square),
            mean_square,
            np.mean(q, axis=-1),
            np.min(q, axis=-1),
            np.max(q, axis=-1),
            np.min(np.abs(poses.det_a), axis=-1),
        )
    rms, mean_sq, gci, least, most, det_a = (np.where(all_real, v, np.nan) for v in values)
    real = poses.real.sum(axis=-1).astype(np.float64)
    return IndexArrays(rms, mean_sq, gci, least, most, det_a, all_real, real)


def least_inverse_condition(poses: PoseArrays) -> tuple[FloatArray, np.ndarray]:
    """Least 1/kappa over the closing orientations of each design ``(m,)`` (nan where
    none closes) and where: the first orientation index reaching it ``(m,)``."""
    q = np.where(poses.real, poses.inverse_condition, np.inf)
    at = np.argmin(q, axis=-1)
    least = np.take_along_axis(q, at[:, None], axis=-1)[:, 0]
    return np.where(np.isfinite(least), least, np.nan), at
