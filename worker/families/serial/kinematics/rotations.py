"""Rotation errors for inverse kinematics, batched on leading axes.

The orientation error of a tool rotation ``R`` against a target ``R_t`` is the rotation
vector of ``R_t Rᵀ`` (axis times angle, rad, in the base frame): the angular velocity
that turns ``R`` into ``R_t`` in unit time, so it pairs with the Jacobian's angular rows.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["orientation_error", "rotation_angle", "rotation_vector"]

FloatArray = NDArray[np.float64]


def _quaternion(rotation: FloatArray) -> FloatArray:
    """Unit quaternions (..., 4) as (w, x, y, z) with w >= 0, by Shepperd's method (the
    largest of the four squared components is taken from the diagonal, the others from
    sums and differences, so no division is by a small number)."""
    r = rotation
    trace = r[..., 0, 0] + r[..., 1, 1] + r[..., 2, 2]
    squares = np.stack([1.0 + trace, 1.0 + 2.0 * r[..., 0, 0] - trace,
                        1.0 + 2.0 * r[..., 1, 1] - trace, 1.0 + 2.0 * r[..., 2, 2] - trace],
                       axis=-1)  # fmt: skip
    big = np.argmax(squares, axis=-1)
    root = np.sqrt(np.maximum(np.take_along_axis(squares, big[..., None], -1)[..., 0], 1e-300))
    quarter = 0.25 / (0.5 * root)  # 1 / (4 * the largest component)
    skew = (r[..., 2, 1] - r[..., 1, 2], r[..., 0, 2] - r[..., 2, 0], r[..., 1, 0] - r[..., 0, 1])
    sym = (r[..., 0, 1] + r[..., 1, 0], r[..., 0, 2] + r[..., 2, 0], r[..., 1, 2] + r[..., 2, 1])
    half = 0.5 * root
    candidates = np.stack(
        [
            np.stack([half, skew[0] * quarter, skew[1] * quarter, skew[2] * quarter], -1),
            np.stack([skew[0] * quarter, half, sym[0] * quarter, sym[1] * quarter], -1),
            np.stack([skew[1] * quarter, sym[0] * quarter, half, sym[2] * quarter], -1),
            np.stack([skew[2] * quarter, sym[1] * quarter, sym[2] * quarter, half], -1),
        ],
        axis=-2,
    )  # (..., 4 cases, 4)
    q = np.take_along_axis(candidates, big[..., None, None], -2)[..., 0, :]
    q = np.where(q[..., :1] < 0.0, -q, q)
    unit: FloatArray = q / np.linalg.norm(q, axis=-1, keepdims=True)
    return unit


def rotation_vector(rotation: FloatArray) -> FloatArray:
    """The rotation vector (..., 3) of rotation matrices (..., 3, 3): unit axis times
    the angle in [0, π] (rad)."""
    q = _quaternion(rotation)
    vector = q[..., 1:]
    norm = np.linalg.norm(vector, axis=-1)
    angle = 2.0 * np.arctan2(norm, q[..., 0])
    # angle / norm -> 2 as the angle -> 0 (sin(a/2) ≈ a/2)
    scale = np.divide(angle, norm, out=np.full_like(norm, 2.0), where=norm > 1e-12)
    out: FloatArray = vector * scale[..., None]
    return out


def rotation_angle(rotation: FloatArray) -> FloatArray:
    """The angle (...,) of rotation matrices (..., 3, 3), in [0, π] rad."""
    q = _quaternion(rotation)
    angle: FloatArray = 2.0 * np.arctan2(np.linalg.norm(q[..., 1:], axis=-1), q[..., 0])
    return angle


def orientation_error(target: FloatArray, rotation: FloatArray) -> FloatArray:
    """The rotation vector of ``target @ rotationᵀ`` (..., 3) (rad, base frame)."""
    return rotation_vector(target @ np.swapaxes(rotation, -1, -2))
