"""The per-orientation reference for SPM conditioning indices: a plain loop.

Kept independent of the vectorised kernels for property tests and the benchmark: each
orientation builds Q by Rodrigues' formula (eq 2), the axes straight from eqs 3, 5 and 7,
solves the tan-half quadratic of eq 11 for each leg (the root with the asked sign of
(u_i x w_i) . v_i, eq 29), forms J = B^-1 A (eq 9) and its inverse with numpy.linalg,
and kappa = ||J|| ||J^-1|| with W = I/3 (eqs 21-22). Angles are in radians.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from worker.common.parameter_errors import bad_parameter
from worker.families.spherical_parallel.kinematics.indices import (
    Indices,
    PoseBatch,
    indices_from_batch,
)
from worker.families.spherical_parallel.kinematics.model import (
    FloatArray,
    SpmDesign,
    checked_branch,
    checked_design,
    checked_orientations,
)

__all__ = ["per_orientation_reference"]

_LINEAR = 1e-12  # |A_i| below this: eq 11 is linear, one root is th = pi (t = inf)


def _axis_angle(axis: FloatArray, angle: float) -> FloatArray:
    """Rodrigues' formula: rot(axis, angle) for a unit axis."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    rotation: FloatArray = np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)
    return rotation


def _middle_axis(design: SpmDesign, eta: float, theta: float) -> FloatArray:
    """w_i of eq 5."""
    a1, g = design.alpha1, design.gamma
    se, ce, sg, cg = math.sin(eta), math.cos(eta), math.sin(g), math.cos(g)
    st, ct, sa, ca = math.sin(theta), math.cos(theta), math.sin(a1), math.cos(a1)
    return np.array([
        -se * sg * ca + (ce * st - se * cg * ct) * sa,
        ce * sg * ca + (se * st + ce * cg * ct) * sa,
        -cg * ca + sg * ct * sa,
    ])  # fmt: skip


def _leg_roots(design: SpmDesign, eta: float, v: FloatArray) -> list[float]:
    """Real roots th of eq 11 for one leg (empty when eq 12 fails)."""
    w0 = _middle_axis(design, eta, math.pi / 2.0) + _middle_axis(design, eta, -math.pi / 2.0)
    w0 /= 2.0  # cos(a1) u_i: the part of w_i that does not turn
    wc = _middle_axis(design, eta, 0.0) - w0
    ws = _middle_axis(design, eta, math.pi / 2.0) - w0
    p = float(w0 @ v) - math.cos(design.alpha2)
    qc, r = float(wc @ v), float(ws @ v)
    a, b, c = p - qc, r, p + qc  # eq 11: a t^2 + 2 b t + c = 0
    disc = b * b - a * c
    if disc < -1e-12:
        return []
    root = math.sqrt(max(disc, 0.0))
    if abs(a) < _LINEAR:
        return [math.pi, -2.0 * math.atan(c / (2.0 * b))] if b else [math.pi]
    return [2.0 * math.atan((-b + root) / a), 2.0 * math.atan((-b - root) / a)]


def _one_orientation(
    design: SpmDesign, psi: FloatArray, branch: int
) -> tuple[float, bool, list[float], float]:
    psi1, psi2, psi3 = (float(x) for x in psi)
    q = _axis_angle(np.array([-math.sin(psi1), math.cos(psi1), 0.0]), psi2) @ _axis_angle(
        np.array([0.0, 0.0, 1.0]), psi3
    )
    sb, cb, sg, cg = (math.sin(design.beta), math.cos(design.beta), math.sin(design.gamma),
                      math.cos(design.gamma))  # fmt: skip
    thetas, rows, diag = [], [], []
    for i in range(3):
        eta = 2.0 * math.pi * i / 3.0
        u = np.array([-math.sin(eta) * sg, math.cos(eta) * sg, -cg])
        v = q @ np.array([-math.sin(eta) * sb, math.cos(eta) * sb, cb])
        roots = _leg_roots(design, eta, v)
        if not roots:
            return math.nan, False, [math.nan] * 3, math.nan
        signed = [(float(np.cross(u, _middle_axis(design, eta, th)) @ v), th) for th in roots]
        b, theta = min(signed, key=lambda pair: -branch * pair[0])  # the branch-signed one
        w = _middle_axis(design, eta, theta)
        thetas.append(math.remainder(theta, 2.0 * math.pi))
        rows.append(np.cross(w, v))
        diag.append(b)
    a_mat = np.array(rows)
    try:
        j = np.linalg.inv(np.diag(diag)) @ a_mat
        j_inv = np.linalg.inv(j)
    except np.linalg.LinAlgError:
        return 0.0, True, thetas, float(np.linalg.det(a_mat))
    kappa = math.sqrt(np.trace(j.T @ j) / 3.0) * math.sqrt(np.trace(j_inv.T @ j_inv) / 3.0)
    return 1.0 / kappa, True, thetas, float(np.linalg.det(a_mat))


def per_orientation_reference(design: SpmDesign, samples: ArrayLike, branch: int = -1) -> Indices:
    """:func:`~.indices.workspace_indices`, one orientation at a
    time (see the module doc). samples: (n, 3) rad."""
    function = "per_orientation_reference"
    checked_design(design, function)
    sign = checked_branch(branch, function)
    arr = checked_orientations(samples, "samples", function)
    if arr.ndim != 2 or arr.shape[0] == 0:
        raise bad_parameter(
            "samples", function, "a non-empty array of shape (n, 3) in rad", samples
        )
    results = [_one_orientation(design, psi, sign) for psi in arr]
    batch = PoseBatch(
        np.array([r[0] for r in results]),
        np.array([r[1] for r in results]),
        np.array([r[2] for r in results]),
        np.array([r[3] for r in results]),
    )
    return indices_from_batch(batch, sign)
