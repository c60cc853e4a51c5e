"""Kinematics of spherical parallel manipulators: axes, inverse kinematics, Jacobian, kappa.

Bai (2010) eqs 2-12 and 21-22, restated in docs/methods/spherical-parallel.md. Legs i = 1, 2, 3
sit at eta_i = 2 (i - 1) pi / 3. Unit-vector arrays have shape (..., 3, 3): axis -2 is the leg,
axis -1 is (x, y, z). Everything is batched on the leading axes of ``psi`` / ``theta``
(broadcast together); angles are in radians.

The middle axis turns about the base axis: ``w_i = cos(a1) u_i + sin(a1) (cos(th_i) e1_i +
sin(th_i) e2_i)`` with ``e2_i = u_i x e1_i`` — the expansion of eq 5 — so that
``dw_i/dth_i = u_i x w_i``. The closure w_i . v_i = cos(a2) (eq 8) then reads
``P_i + Qc_i cos(th_i) + R_i sin(th_i) = 0``, the tan-half quadratic of eq 11 with
``A_i = P_i - Qc_i``, ``B_i = R_i``, ``C_i = P_i + Qc_i``; it is solved here in the
equivalent closed form ``th_i = atan2(R_i, Qc_i) - branch * acos(-P_i / rho_i)``,
``rho_i = hypot(Qc_i, R_i)``, real iff ``B_i^2 - A_i C_i = rho_i^2 - P_i^2 >= 0`` (eq 12).
On that root ``(u_i x w_i) . v_i = d(w_i . v_i)/d(th_i) = branch * sqrt(rho_i^2 - P_i^2)``,
so ``branch`` is the sign the paper constrains in eq 29 (-1 there).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from worker.common.arrays import checked_array
from worker.common.parameter_errors import bad_parameter
from worker.families.spherical_parallel.kinematics.model import (
    BoolArray,
    FloatArray,
    SpmDesign,
    checked_branch,
    checked_design,
    checked_orientations,
)

__all__ = [
    "REAL_TOLERANCE",
    "LegFrames",
    "condition_number",
    "inverse_condition_number",
    "inverse_condition_rows",
    "inverse_kinematics",
    "jacobian",
    "leg_frames",
    "middle_axes",
    "platform_axes",
    "rotation",
    "solve_legs",
    "unit_vectors",
]

#: A leg closes when |P_i| <= rho_i + REAL_TOLERANCE: the discriminant of eq 12 may come
#: out a rounding error below zero exactly on the edge of the design space.
REAL_TOLERANCE = 1e-12

_ETA = 2.0 * np.pi * np.arange(3) / 3.0


class LegFrames(NamedTuple):
    """Per-leg constant axes of a design, each (3, 3) with rows i = 1, 2, 3.

    u: base axes (eq 3); e1, e2: the orthonormal pair turning w about u (e2 = u x e1);
    v_star: platform axes in the reference orientation (eq 7).
    """

    u: FloatArray
    e1: FloatArray
    e2: FloatArray
    v_star: FloatArray


class LegSolution(NamedTuple):
    """Inverse kinematics of the three legs, each (..., 3): th_i (nan where a leg does not
    close), whether it closes, and b_i = (u_i x w_i) . v_i on the chosen branch."""

    theta: FloatArray
    real: BoolArray
    b: FloatArray


def leg_frames(design: SpmDesign) -> LegFrames:
    """The constant per-leg axes of ``design`` (eqs 3, 5 and 7)."""
    se, ce = np.sin(_ETA), np.cos(_ETA)
    sg, cg = math.sin(design.gamma), math.cos(design.gamma)
    sb, cb = math.sin(design.beta), math.cos(design.beta)
    ones, zeros = np.ones(3), np.zeros(3)
    u = np.stack([-se * sg, ce * sg, -cg * ones], axis=-1)
    e1 = np.stack([-se * cg, ce * cg, sg * ones], axis=-1)
    e2 = np.stack([ce, se, zeros], axis=-1)
    v_star = np.stack([-se * sb, ce * sb, cb * ones], axis=-1)
    return LegFrames(u, e1, e2, v_star)


def _rotation(psi: FloatArray) -> FloatArray:
    # rot(e_psi, psi2) rot(e3, psi3) = Rz(psi1) Ry(psi2) Rz(psi3 - psi1).
    a, b, c = psi[..., 0], psi[..., 1], psi[..., 2] - psi[..., 0]
    sa, ca, sb, cb, sc, cc = np.sin(a), np.cos(a), np.sin(b), np.cos(b), np.sin(c), np.cos(c)
    rows = [
        [ca * cb * cc - sa * sc, -ca * cb * sc - sa * cc, ca * sb],
        [sa * cb * cc + ca * sc, -sa * cb * sc + ca * cc, sa * sb],
        [-sb * cc, sb * sc, cb],
    ]
    return np.stack([np.stack(row, axis=-1) for row in rows], axis=-2)


def rotation(psi: ArrayLike) -> FloatArray:
    """Platform orientation Q = rot(e_psi, psi2) rot(e3, psi3) (eq 2).

    psi: (..., 3) rad ``(psi1, psi2, psi3)``, e_psi = [-sin psi1, cos psi1, 0]: a torsion
    psi3 about z, then a tilt psi2 about the horizontal axis e_psi, so the platform axis
    leans toward azimuth psi1. Returns (..., 3, 3).
    """
    return _rotation(checked_orientations(psi, "psi", "rotation"))


def platform_axes(q_mat: FloatArray, v_star: FloatArray) -> FloatArray:
    """v_i = Q v_i* (eq 6): (..., 3, 3) orientations -> (..., 3, 3) rows v_i."""
    return np.asarray(np.einsum("...jk,ik->...ij", q_mat, v_star), dtype=np.float64)


def middle_axes(design: SpmDesign, frames: LegFrames, theta: FloatArray) -> FloatArray:
    """w_i (eq 5) from input angles (..., 3): (..., 3, 3)."""
    c, s = np.cos(theta)[..., None], np.sin(theta)[..., None]
    return math.cos(design.alpha1) * frames.u + math.sin(design.alpha1) * (
        c * frames.e1 + s * frames.e2
    )


def solve_legs(design: SpmDesign, frames: LegFrames, v: FloatArray, branch: int) -> LegSolution:
    """Closed-form eqs 11-12 for platform axes v (..., 3, 3) on one branch (see module doc)."""
    sa1 = math.sin(design.alpha1)
    p = math.cos(design.alpha1) * np.einsum("...ij,ij->...i", v, frames.u) - math.cos(design.alpha2)
    qc = sa1 * np.einsum("...ij,ij->...i", v, frames.e1)
    r = sa1 * np.einsum("...ij,ij->...i", v, frames.e2)
    rho = np.hypot(qc, r)
    real = np.abs(p) <= rho + REAL_TOLERANCE
    cos_delta = np.divide(-p, rho, out=np.zeros_like(p), where=rho > 0.0)
    delta = np.arccos(np.clip(cos_delta, -1.0, 1.0))
    theta = np.mod(np.arctan2(r, qc) - branch * delta + np.pi, 2.0 * np.pi) - np.pi
    b = branch * np.sqrt(np.maximum(rho * rho - p * p, 0.0))
    return LegSolution(np.where(real, theta, np.nan), real, np.where(real, b, np.nan))


def inverse_condition_rows(a: FloatArray, b: FloatArray) -> tuple[FloatArray, FloatArray]:
    """1/kappa of J = diag(b)^-1 A (eqs 9, 21-22) without forming J, and det(A).

    a: (..., 3, 3) rows a_i = w_i x v_i; b: (..., 3). With c_i = a_j x a_k (i, j, k
    cyclic), ``1/kappa = 3 |det A| |b1 b2 b3| / (sqrt(sum_i (b_j b_k)^2 |a_i|^2)
    sqrt(sum_i b_i^2 |c_i|^2))`` — ||J|| ||J^-1|| with W = I/3 written through the
    adjugate, so it is finite everywhere and 0 exactly when det A = 0 (type II) or some
    b_i = 0 (a leg stretched or folded, type I). Returns (1/kappa in [0, 1], det A).
    """
    c = np.cross(a[..., [1, 2, 0], :], a[..., [2, 0, 1], :])
    det_a = np.einsum("...k,...k->...", a[..., 0, :], c[..., 0, :])
    pair = b[..., [1, 2, 0]] * b[..., [2, 0, 1]]
    rows = np.einsum("...ik,...ik->...i", a, a)
    cofactors = np.einsum("...ik,...ik->...i", c, c)
    norms = np.sqrt(np.sum(pair * pair * rows, axis=-1) * np.sum(b * b * cofactors, axis=-1))
    numerator = 3.0 * np.abs(det_a * np.prod(b, axis=-1))
    inverse = np.divide(numerator, norms, out=np.zeros_like(numerator), where=norms > 0.0)
    return np.clip(inverse, 0.0, 1.0), det_a


def _broadcast_pose(
    design: SpmDesign, theta: ArrayLike, psi: ArrayLike, function: str
) -> tuple[FloatArray, FloatArray]:
    checked_design(design, function)
    th = checked_array(
        theta,
        "theta",
        function,
        "finite input angles (rad) of shape (..., 3)",
        lambda a: a.ndim >= 1 and a.shape[-1] == 3,
    )
    ps = checked_orientations(psi, "psi", function)
    try:
        shape = np.broadcast_shapes(th.shape[:-1], ps.shape[:-1])
    except ValueError:
        raise bad_parameter(
            "psi", function, f"broadcastable with theta of shape {th.shape}", psi
        ) from None
    return np.broadcast_to(th, (*shape, 3)), np.broadcast_to(ps, (*shape, 3))


def unit_vectors(
    design: SpmDesign, theta: ArrayLike, psi: ArrayLike
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Joint axes (eqs 3, 5, 6): theta (..., 3) rad, psi (..., 3) rad, broadcast together.

    Returns u, w, v, each (..., 3, 3) (leg, xyz). Closure (eq 8) holds only when theta
    solves the inverse kinematics of psi.
    """
    th, ps = _broadcast_pose(design, theta, psi, "unit_vectors")
    frames = leg_frames(design)
    u = np.broadcast_to(frames.u, (*th.shape[:-1], 3, 3)).copy()
    return u, middle_axes(design, frames, th), platform_axes(_rotation(ps), frames.v_star)


def inverse_kinematics(
    design: SpmDesign, psi: ArrayLike, branch: int = -1
) -> tuple[FloatArray, BoolArray]:
    """Input angles for orientations psi (..., 3) rad on one branch (eqs 8, 11, 12, 29).

    branch: the sign of (u_i x w_i) . v_i kept on every leg (the paper's eq 29: -1).
    Returns theta (..., 3) rad in [-pi, pi) (nan on a leg that does not close) and
    real (...): whether all three legs close (eq 12). No real solution is data, not an
    error.
    """
    checked_design(design, "inverse_kinematics")
    sign = checked_branch(branch, "inverse_kinematics")
    ps = checked_orientations(psi, "psi", "inverse_kinematics")
    frames = leg_frames(design)
    legs = solve_legs(design, frames, platform_axes(_rotation(ps), frames.v_star), sign)
    return legs.theta, np.all(legs.real, axis=-1)


def jacobian(
    design: SpmDesign, theta: ArrayLike, psi: ArrayLike
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Eq 9: A omega = B theta_dot, theta_dot = J omega.

    theta, psi: (..., 3) rad, broadcast together. Returns A (..., 3, 3) with rows
    (w_i x v_i)^T, B (..., 3, 3) = diag((u_i x w_i) . v_i) and J = B^-1 A (rows with
    b_i = 0, a leg stretched or folded, come out inf/nan: use
    :func:`inverse_condition_rows` for a finite 1/kappa there).
    """
    u, w, v = unit_vectors(design, theta, psi)
    a = np.cross(w, v)
    b = np.einsum("...ik,...ik->...i", np.cross(u, w), v)
    with np.errstate(divide="ignore", invalid="ignore"):
        j = a / b[..., None]
    return a, b[..., None] * np.eye(3), j


def _checked_jacobian(j: ArrayLike, function: str) -> FloatArray:
    try:
        arr = np.asarray(j, dtype=np.float64)
    except (TypeError, ValueError):
        arr = np.empty(0)
    if arr.ndim < 2 or arr.shape[-2:] != (3, 3):
        raise bad_parameter("J", function, "an array of shape (..., 3, 3)", j)
    return arr


def inverse_condition_number(j: ArrayLike) -> FloatArray:
    """1/kappa of J (..., 3, 3) (eqs 21-22, W = I/3), in [0, 1]; 0 where J is singular
    or has non-finite entries (a type-I singularity of :func:`jacobian`)."""
    arr = _checked_jacobian(j, "inverse_condition_number")
    finite = np.all(np.isfinite(arr), axis=(-2, -1))
    safe = np.where(finite[..., None, None], arr, 0.0)
    # kappa is scale-free: bring the largest entry to 1 so no product over- or underflows
    peak = np.max(np.abs(safe), axis=(-2, -1), keepdims=True)
    safe = np.divide(safe, peak, out=np.zeros_like(safe), where=peak > 0.0)
    inverse, _ = inverse_condition_rows(safe, np.ones(safe.shape[:-1]))
    return np.where(finite, inverse, 0.0)


def condition_number(j: ArrayLike) -> FloatArray:
    """kappa = ||J|| ||J^-1||, ||M|| = sqrt(tr(M^T W M)), W = I/3 (eqs 21-22).

    J: (..., 3, 3). Returns kappa (...) >= 1, inf where J is singular or non-finite.
    """
    inverse = inverse_condition_number(j)
    with np.errstate(over="ignore"):  # 1/kappa below ~1e-308: kappa is inf
        return np.divide(1.0, inverse, out=np.full_like(inverse, np.inf), where=inverse > 0.0)
