"""Dexterity indices of a serial arm's Jacobian, batched on leading axes.

The task space is (x, y, z, three rotations) for a spatial arm and (x, y, φ) for a
planar one (rows 0, 1 and 5 of the geometric Jacobian).  Manipulability is
``sqrt(det(J Jᵀ))`` when the arm has at least as many joints as task dimensions, else
``sqrt(det(Jᵀ J))``: the product of the singular values either way.  The inverse
condition number is σ_min/σ_max over the task space's rank; a
``characteristic_length`` L divides the linear rows by L first (docs/methods/serial.md).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "PLANAR_ROWS",
    "inverse_condition",
    "limit_distance",
    "manipulability",
    "singular_values",
    "task_jacobian",
]

FloatArray = NDArray[np.float64]
#: The rows of the geometric Jacobian a planar arm's task space keeps: x, y, φ.
PLANAR_ROWS = (0, 1, 5)


def task_jacobian(jac: FloatArray, planar: bool) -> FloatArray:
    """The Jacobian in the task space: (..., 6, n), or (..., 3, n) for a planar arm."""
    return jac[..., PLANAR_ROWS, :] if planar else jac


def _scaled(jac: FloatArray, characteristic_length: float | None) -> FloatArray:
    if characteristic_length is None:
        return jac
    linear = 2 if jac.shape[-2] == 3 else 3
    scale = np.ones(jac.shape[-2])
    scale[:linear] = 1.0 / characteristic_length
    return jac * scale[:, None]


def singular_values(jac: FloatArray, characteristic_length: float | None = None) -> FloatArray:
    """Singular values, largest first: (..., min(m, n))."""
    sigma = np.linalg.svd(_scaled(jac, characteristic_length), compute_uv=False)
    return np.asarray(sigma, dtype=np.float64)


def manipulability(jac: FloatArray) -> FloatArray:
    """Yoshikawa's measure (...,): the product of the singular values of the task
    Jacobian (sqrt(det(J Jᵀ)) for n >= m, else sqrt(det(Jᵀ J)))."""
    product: FloatArray = np.prod(singular_values(jac), axis=-1)
    return product


def inverse_condition(jac: FloatArray, characteristic_length: float | None = None) -> FloatArray:
    """σ_min/σ_max of the task Jacobian (...,), in [0, 1]; 0 at a singularity (or
    where σ_max is 0)."""
    sigma = singular_values(jac, characteristic_length)
    top = sigma[..., 0]
    return np.divide(sigma[..., -1], top, out=np.zeros_like(top), where=top > 0.0)


def limit_distance(q: FloatArray, lower: FloatArray, upper: FloatArray) -> FloatArray:
    """Per joint, the distance to the nearer limit (..., n) (rad or length units);
    negative outside the limits."""
    return np.minimum(q - lower, upper - q)
