"""Forward kinematics, task Jacobian and dexterity indices for the workspace map: the
same numbers as :mod:`.chain` and :mod:`.indices`, specialised for millions of samples.

Every joint axis is first turned into z (:func:`z_axis_form`: a constant rotation P with
``P e_z = u`` folded into the fixed transforms around the joint, ``Rot(u, q) = P Rz(q)
Pᵀ``), so a joint's motion touches two columns of the running rotation (revolute) or
the position (prismatic).  Rotations are (B, 3, 3) arrays and a fixed transform is one
(3B, 3) @ (3, 3) product.  The indices come from the eigenvalues of the smaller Gram
matrix (J Jᵀ when n >= m, else Jᵀ J), built as a sum of outer products: σ_i = sqrt(λ_i),
so manipulability = prod σ_i and the inverse condition number = σ_min / σ_max (the
squares lose half the digits of a tiny σ_min: about 1e-8 relative to σ_max, far below
a map's resolution).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from worker.families.serial.kinematics.arm import SerialArm
from worker.families.serial.kinematics.indices import PLANAR_ROWS

__all__ = ["MapPoses", "ZAxisArm", "gram_indices", "map_poses", "z_axis_form"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class ZAxisArm:
    """An arm whose joints all move about/along z: ``fixed`` (n+1, 4, 4), ``prismatic``
    (n,) bool; ``T(q) = F_0 Mz(q_1) F_1 ... Mz(q_n) F_n``."""

    fixed: FloatArray
    prismatic: NDArray[np.bool_]


def _z_to(axis: FloatArray) -> FloatArray:
    """A rotation (3, 3) taking e_z to the unit ``axis``."""
    z = np.array([0.0, 0.0, 1.0])
    v, c = np.cross(z, axis), float(np.dot(z, axis))
    if c < -1.0 + 1e-12:
        return np.diag([1.0, -1.0, -1.0])
    skew = np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
    turn: FloatArray = np.eye(3) + skew + skew @ skew / (1.0 + c)
    return turn


def z_axis_form(arm: SerialArm) -> ZAxisArm:
    """The same arm with every joint axis z (module docstring)."""
    fixed = arm.fixed.copy()
    for i in range(arm.joints):
        turn = np.eye(4)
        turn[:3, :3] = _z_to(arm.axes[i] / np.linalg.norm(arm.axes[i]))
        fixed[i] = fixed[i] @ turn
        fixed[i + 1] = turn.T @ fixed[i + 1]
    return ZAxisArm(fixed=fixed, prismatic=arm.prismatic.copy())


@dataclass(frozen=True, eq=False)
class MapPoses:
    """Tool ``rotation`` (B, 3, 3), ``position`` (B, 3) and full geometric ``jacobian``
    (B, 6, n) about the tool point in the base frame."""

    rotation: FloatArray
    position: FloatArray
    jacobian: FloatArray


def _cross(u: FloatArray, v: FloatArray) -> FloatArray:
    """u x v for (3, ...) component-first arrays."""
    return np.stack([u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                     u[0] * v[1] - u[1] * v[0]])  # fmt: skip


def map_poses(arm: ZAxisArm, q: FloatArray) -> MapPoses:
    """Tool poses and Jacobians of joint values q (B, n) (rad / length units).

    Computed component-first ((3, 3, B) rotations, contiguous per entry) and returned
    as (B, ...) views."""
    b, n = q.shape
    rotation = np.repeat(arm.fixed[0][:3, :3, None], b, axis=2)  # (3, 3, B): [row, col]
    position = np.repeat(arm.fixed[0][:3, 3, None], b, axis=1)  # (3, B)
    axes = np.empty((n, 3, b))
    origins = np.empty((n, 3, b))
    for i in range(n):
        axes[i] = rotation[:, 2]
        origins[i] = position
        if arm.prismatic[i]:
            position = position + q[:, i] * rotation[:, 2]
        else:
            c, s = np.cos(q[:, i]), np.sin(q[:, i])
            col0, col1 = (
                rotation[:, 0] * c + rotation[:, 1] * s,
                rotation[:, 1] * c - rotation[:, 0] * s,
            )
            rotation[:, 0], rotation[:, 1] = col0, col1
        fixed = arm.fixed[i + 1]
        t = fixed[:3, 3]
        position = position + rotation[:, 0] * t[0] + rotation[:, 1] * t[1] + rotation[:, 2] * t[2]
        rotation = np.matmul(fixed[:3, :3].T, rotation)
    jac = np.empty((6, n, b))
    for i in range(n):
        if arm.prismatic[i]:
            jac[:3, i], jac[3:, i] = axes[i], 0.0
        else:
            jac[:3, i], jac[3:, i] = _cross(axes[i], position - origins[i]), axes[i]
    return MapPoses(rotation=np.moveaxis(rotation, -1, 0), position=position.T,
                    jacobian=np.moveaxis(jac, -1, 0))  # fmt: skip


def _gram(jac: FloatArray) -> FloatArray:
    """The smaller Gram matrix of (B, m, n): J Jᵀ (m x m) if n >= m, else Jᵀ J; entry by
    entry over (B,) vectors (contiguous when ``jac`` is :func:`map_poses`' view)."""
    m, n = jac.shape[-2:]
    size, inner = min(m, n), max(m, n)
    vectors = [[jac[:, a, k] if n >= m else jac[:, k, a] for k in range(inner)]
               for a in range(size)]  # fmt: skip
    gram = np.empty((size, size, jac.shape[0]))
    for a in range(size):
        for b in range(a + 1):
            entry = vectors[a][0] * vectors[b][0]
            for k in range(1, inner):
                entry += vectors[a][k] * vectors[b][k]
            gram[a, b] = gram[b, a] = entry
    return np.moveaxis(gram, -1, 0)


def gram_indices(
    jac: FloatArray, planar: bool, characteristic_length: float | None
) -> tuple[FloatArray, FloatArray]:
    """(manipulability (B,), inverse condition (B,)) of full Jacobians (B, 6, n), in the
    task space (rows x, y, φ for a planar arm); the inverse condition with the linear
    rows divided by ``characteristic_length`` when given."""
    task = jac[:, PLANAR_ROWS, :] if planar else jac
    sigma = np.sqrt(np.maximum(np.linalg.eigvalsh(_gram(task)), 0.0))  # ascending
    measure: FloatArray = np.prod(sigma, axis=-1)
    if characteristic_length is not None:
        linear = 2 if planar else 3
        scaled = task.copy()
        scaled[:, :linear] /= characteristic_length
        sigma = np.sqrt(np.maximum(np.linalg.eigvalsh(_gram(scaled)), 0.0))
    top = sigma[:, -1]
    kappa = np.divide(sigma[:, 0], top, out=np.zeros_like(top), where=top > 0.0)
    return measure, kappa
