"""Orientation dexterity of three-link planar arms with joint limits, by sampling.

The vectorised kernel behind :func:`limited_orientation_dexterity` (docs/methods/planar-serial.md,
"Joint limits: orientation sampling"): every joint-limit test at a sample phi_k is linear
in the point features [px, py, 1, |p|^2], so a whole block of points x orientations is
one matrix product, and changes of feasibility can be bisected (``refine_tol``).
Conventions as in :mod:`worker.families.planar_serial.kinematics`.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from worker.common.parameter_errors import bad_parameter
from worker.families.planar_serial.kinematics.inputs import (
    BoolArray,
    FloatArray,
    LinkLengths,
    Links,
    checked_joint_limits,
    checked_links,
    checked_points,
    sample_count,
)

__all__ = ["feasible_orientations", "limited_orientation_dexterity", "orientation_samples"]

#: Elements (points x orientations) evaluated at once inside a chunk: small enough that
#: the kernel's ~110 bytes per element stay in cache, which runs 2-3x faster than
#: streaming multi-megabyte temporaries through memory.
_CACHE_BLOCK_ELEMENTS = 2**14


def orientation_samples(step: float) -> tuple[int, float]:
    """Orientation grid for a requested step (rad): n = max(1, round(2 pi / step)).

    The samples are ``phi_k = k (2 pi / n)``, k = 0..n-1. Returns (n, 2 pi / n).
    """
    n = sample_count(step, "orientation_samples")
    return n, 2.0 * math.pi / n


def _point_features(px: FloatArray, py: FloatArray) -> FloatArray:
    """(4, m) features [px, py, 1, |p|^2] of m points."""
    return np.stack([px, py, np.ones_like(px), px * px + py * py])


def _linear_weights(
    links: Links, limits: FloatArray, cos_phi: FloatArray, sin_phi: FloatArray
) -> FloatArray:
    """(7, k, 4) weights on the point features of the quantities linear in them at phi_k.

    Joint j lies in its limit arc [lo, hi] (mid m_j, half-width h_j, C_j = cos h_j) iff
    its direction vector z_j satisfies z_j . u(m_j) >= C_j |z_j| — the same as
    lo <= wrap(th_j) <= hi up to the measure-zero point -pi. With the wrist
    w = p - l3 u(phi), c2 = cos th2 = (|w|^2 - l1^2 - l2^2) / (2 l1 l2), s2 = |sin th2| and
    the elbow sign ±: z1 = w (k1 ∓ i l2 s2), k1 = l1 + l2 c2 (two-link IK);
    z1 z2 = w (l1 c2 + l2 ± i l1 s2); z3 = e^{i phi} conj(z1 z2); |z1| = |z3| = |w|^2.
    Rotating w into each arc's mid frame, every test becomes
    ``c2 E_j + F_j ± s2 G_j >= 0`` with E_j, F_j, G_j linear in [px, py, 1, |p|^2]:
    rows c2, E1, F1, G1, E3, F3, G3 (th2 needs only c2).
    """
    l1, l2, l3 = links
    mid = 0.5 * (limits[:, 0] + limits[:, 1])
    cos_half = np.cos(0.5 * (limits[:, 1] - limits[:, 0]))
    cm1, cm3 = math.cos(mid[0]), math.cos(mid[2])
    sm1, sm3 = math.sin(mid[0]), math.sin(mid[2])
    ch1, ch3 = float(cos_half[0]), float(cos_half[2])
    inv, norm = 0.5 / (l1 * l2), l1 * l1 + l2 * l2
    one = np.ones_like(cos_phi)
    zero = np.zeros_like(cos_phi)
    # w . u(m1) = px cm1 + py sm1 - l3 cos(phi - m1); w x u(m1) = py cm1 - px sm1 - l3 sin(phi - m1)
    cos1 = cos_phi * cm1 + sin_phi * sm1
    sin1 = sin_phi * cm1 - cos_phi * sm1
    # v = e^{i(phi - m3)}: w . v = px vx + py vy - l3 cm3; w x v = py vx - px vy - l3 sm3
    vx = cos_phi * cm3 + sin_phi * sm3
    vy = sin_phi * cm3 - cos_phi * sm3
    rows = [
        (
            -2.0 * l3 * inv * cos_phi,
            -2.0 * l3 * inv * sin_phi,
            (l3 * l3 - norm) * inv * one,
            inv * one,
        ),
        (l2 * cm1 * one, l2 * sm1 * one, -l2 * l3 * cos1 - 2.0 * ch1 * l1 * l2, zero),
        (l1 * cm1 * one, l1 * sm1 * one, -l1 * l3 * cos1 - ch1 * norm, zero),
        (-l2 * sm1 * one, l2 * cm1 * one, -l2 * l3 * sin1, zero),
        (l1 * vx, l1 * vy, (-l1 * l3 * cm3 - 2.0 * ch3 * l1 * l2) * one, zero),
        (l2 * vx, l2 * vy, (-l2 * l3 * cm3 - ch3 * norm) * one, zero),
        (l1 * vy, -l1 * vx, l1 * l3 * sm3 * one, zero),
    ]
    return np.stack([np.stack(row, axis=-1) for row in rows])


def _require(plus: BoolArray, minus: BoolArray, base: FloatArray, branch: FloatArray) -> None:
    """plus &= base + branch >= 0; minus &= base - branch >= 0 (overwrites ``branch``)."""
    minus &= base >= branch
    np.negative(branch, out=branch)
    plus &= base >= branch


def _feasible(linear: FloatArray, limits: FloatArray) -> BoolArray:
    """Feasibility (...) from the (7, ...) linear quantities; consumes ``linear``."""
    c2, e1, f1, g1, e3, f3, g3 = linear
    s2 = c2 * c2
    np.subtract(1.0, s2, out=s2)
    plus: BoolArray = s2 >= 0.0  # the wrist is within the two-link annulus: |c2| <= 1
    np.maximum(s2, 0.0, out=s2)
    np.sqrt(s2, out=s2)
    minus = plus.copy()
    full = limits[:, 1] - limits[:, 0] >= 2.0 * np.pi
    if not full[1]:
        mid, half = 0.5 * (limits[1, 0] + limits[1, 1]), 0.5 * (limits[1, 1] - limits[1, 0])
        base = c2 * math.cos(mid)
        base -= math.cos(half)
        _require(plus, minus, base, np.multiply(s2, math.sin(mid)))
    for joint, (e, f, g) in ((0, (e1, f1, g1)), (2, (e3, f3, g3))):
        if not full[joint]:
            e *= c2
            e += f
            g *= s2
            _require(plus, minus, e, g)
    plus |= minus
    return plus


def _pair_quantities(
    links: LinkLengths, limits: FloatArray, px: FloatArray, py: FloatArray, phi: FloatArray
) -> FloatArray:
    """(7, k) quantities of :func:`_linear_weights` at k (point, orientation) pairs.

    The same rows, evaluated directly at each pair instead of as weights on the point
    features (which pays off only when many points share the orientations).
    """
    l1, l2, l3 = links
    mid = 0.5 * (limits[:, 0] + limits[:, 1])
    ch1, ch3 = (math.cos(0.5 * float(limits[j, 1] - limits[j, 0])) for j in (0, 2))
    cm1, sm1, cm3, sm3 = math.cos(mid[0]), math.sin(mid[0]), math.cos(mid[2]), math.sin(mid[2])
    inv, norm = 0.5 / (l1 * l2), l1 * l1 + l2 * l2
    cos_phi, sin_phi = np.cos(phi), np.sin(phi)
    # the wrist relative to the mid frame of joint 1, and p in the frame of e^{i(phi - m3)}
    wx = px - l3 * cos_phi
    wy = py - l3 * sin_phi
    along1, across1 = wx * cm1 + wy * sm1, wy * cm1 - wx * sm1
    vx, vy = cos_phi * cm3 + sin_phi * sm3, sin_phi * cm3 - cos_phi * sm3
    along3, across3 = px * vx + py * vy - l3 * cm3, px * vy - py * vx + l3 * sm3
    return np.stack(
        [
            (wx * wx + wy * wy - norm) * inv,
            l2 * along1 - 2.0 * ch1 * l1 * l2,
            l1 * along1 - ch1 * norm,
            l2 * across1,
            l1 * along3 - 2.0 * ch3 * l1 * l2,
            l2 * along3 - ch3 * norm,
            l1 * across3,
        ]
    )


def feasible_orientations(
    links: LinkLengths, limits: FloatArray, px: FloatArray, py: FloatArray, phi: FloatArray
) -> BoolArray:
    """Feasibility of (point, orientation) pairs: px, py, phi (k,) -> (k,) bool.

    links (three numbers, or three (k,) columns, one design per pair) and limits
    already checked. A pair is feasible when an elbow branch has all
    three joints within their limits (the test of :func:`limited_orientation_dexterity`).
    """
    return _feasible(_pair_quantities(links, limits, px, py, phi), limits)


def _refined_measure(
    feasible: BoolArray,
    features: FloatArray,
    links: Links,
    limits: FloatArray,
    refine_tol: float,
) -> FloatArray:
    """Feasible measure (rad) per column of an (n, m) sample mask, transitions bisected."""
    n, m = feasible.shape
    step = 2.0 * np.pi / n
    following = np.roll(feasible, -1, axis=0)
    measure: FloatArray = step * np.count_nonzero(feasible & following, axis=0).astype(np.float64)
    samples, columns = np.nonzero(feasible != following)
    start = samples * step
    lo, hi = start.copy(), start + step
    lo_ok = feasible[samples, columns]
    px, py = features[0, columns], features[1, columns]
    for _ in range(max(0, math.ceil(math.log2(step / refine_tol)))):
        mid = 0.5 * (lo + hi)
        same = feasible_orientations(links, limits, px, py, mid) == lo_ok
        lo = np.where(same, mid, lo)
        hi = np.where(same, hi, mid)
    edge = 0.5 * (lo + hi)
    piece = np.where(lo_ok, edge - start, start + step - edge)
    measure += np.bincount(columns, weights=piece, minlength=m)
    return measure


def limited_orientation_dexterity(
    links: ArrayLike,
    points: ArrayLike,
    joint_limits: ArrayLike,
    step: float,
    *,
    refine_tol: float | None = None,
    max_chunk_elements: int = 2**22,
    on_chunk: Callable[[int, int], None] | None = None,
) -> FloatArray:
    """d_z with joint limits by orientation sampling (docs/methods/planar-serial.md).

    links: (3,); points: (..., 2); joint_limits: (3, 2) rad ``[[lo, hi], ...]`` with
    -pi <= lo <= hi <= pi, joint angles wrapped to (-pi, pi]; step: requested sample
    spacing in rad (see :func:`orientation_samples`). Returns d_z (...) in [0, 1].

    At each sample phi_k the wrist w = p - l3 u(phi_k) is solved on both elbow branches;
    the sample counts if either branch has all three joints within limits, and
    ``d_z = (#feasible samples) / n``. With ``refine_tol`` (rad), every change of
    feasibility between cyclically consecutive samples is located by bisection to within
    ``refine_tol`` and d_z = (measure of the feasible set) / (2 pi). Either way, feasible
    or infeasible features narrower than one step can be missed.

    Work is vectorised over points x orientations, in chunks of points with
    ``chunk_points * n <= max_chunk_elements``; ``on_chunk(done_points, total_points)``
    is called after each chunk. Inside a chunk the kernel runs on cache-sized blocks of
    at most ``min(max_chunk_elements, 2**14)`` elements (about 110 bytes each), so the
    peak memory is that block plus the (...) result, whatever the grid size. The
    per-block matrix product uses BLAS (and its threads, if any).
    """
    function = "limited_orientation_dexterity"
    lengths = checked_links(links, function)
    p = checked_points(points, function)
    limits = checked_joint_limits(joint_limits, function)
    n = sample_count(step, function)
    if refine_tol is not None and not (math.isfinite(refine_tol) and refine_tol > 0):
        raise bad_parameter(
            "refine_tol", function, "a finite positive angle in radians or None", refine_tol
        )
    if not (isinstance(max_chunk_elements, numbers.Integral) and max_chunk_elements >= n):
        raise bad_parameter(
            "max_chunk_elements", function, f"an integer >= n = {n} samples", max_chunk_elements
        )
    flat = p.reshape(-1, 2)
    total = flat.shape[0]
    phi = np.arange(n) * (2.0 * np.pi / n)
    weights = _linear_weights(lengths, limits, np.cos(phi), np.sin(phi)).reshape(7 * n, 4)
    chunk = int(max_chunk_elements) // n
    block = max(1, min(chunk * n, _CACHE_BLOCK_ELEMENTS) // n)
    dz = np.empty(total, dtype=np.float64)
    for chunk_start in range(0, total, chunk):
        chunk_stop = min(chunk_start + chunk, total)
        for start in range(chunk_start, chunk_stop, block):
            stop = min(start + block, chunk_stop)
            features = _point_features(flat[start:stop, 0], flat[start:stop, 1])
            linear = (weights @ features).reshape(7, n, stop - start)
            feasible = _feasible(linear, limits)  # (n, points)
            if refine_tol is None:
                dz[start:stop] = np.count_nonzero(feasible, axis=0) / n
            else:
                measure = _refined_measure(feasible, features, lengths, limits, refine_tol)
                dz[start:stop] = np.clip(measure / (2.0 * np.pi), 0.0, 1.0)
        if on_chunk is not None:
            on_chunk(chunk_stop, total)
    return dz.reshape(p.shape[:-1])
