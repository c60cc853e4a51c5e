"""Forward kinematics and the Jacobian of a :class:`~.arm.SerialArm`, batched.

Joint values ``q`` have shape (..., n): radians for revolute joints, the arm's length
unit for prismatic ones.  Frames are homogeneous (..., 4, 4) in the base frame (after
``base``).  The Jacobian is about the tool point (after ``tool``), rows
[linear (3); angular (3)], one column per joint, unscaled: per radian for a revolute
joint, per length unit for a prismatic one (docs/methods/serial.md).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from worker.families.serial.kinematics.arm import SerialArm

__all__ = ["forward_kinematics", "jacobian", "joint_frames", "joint_motions"]

FloatArray = NDArray[np.float64]


def joint_motions(arm: SerialArm, q: ArrayLike) -> FloatArray:
    """``M_i(q_i)`` for every joint: (..., n, 4, 4) (Rodrigues' formula for a rotation
    about the unit axis; a translation along it for a prismatic joint)."""
    values = np.asarray(q, dtype=float)
    shape = values.shape
    out = np.zeros((*shape, 4, 4))
    out[..., 3, 3] = 1.0
    u = arm.axes  # (n, 3)
    revolute = ~arm.prismatic
    angle = np.where(revolute, values, 0.0)
    c, s = np.cos(angle)[..., None, None], np.sin(angle)[..., None, None]
    skew = np.zeros((u.shape[0], 3, 3))
    skew[:, 0, 1], skew[:, 0, 2], skew[:, 1, 2] = -u[:, 2], u[:, 1], -u[:, 0]
    skew[:, 1, 0], skew[:, 2, 0], skew[:, 2, 1] = u[:, 2], -u[:, 1], u[:, 0]
    out[..., :3, :3] = np.eye(3) + s * skew + (1.0 - c) * (skew @ skew)
    out[..., :3, 3] = np.where(arm.prismatic[:, None], values[..., None] * u, 0.0)
    return out


def _frames(arm: SerialArm, q: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """(joint frames (..., n, 4, 4), tool frame (..., 4, 4))."""
    motions = joint_motions(arm, q)
    batch = motions.shape[:-3]
    n = arm.joints
    frames = np.empty((*batch, n, 4, 4))
    current = np.broadcast_to(arm.fixed[0], (*batch, 4, 4))
    for i in range(n):
        frames[..., i, :, :] = current
        current = current @ motions[..., i, :, :] @ arm.fixed[i + 1]
    if n == 0:
        current = current @ arm.fixed[-1]
    return frames, np.asarray(current)


def joint_frames(arm: SerialArm, q: ArrayLike) -> FloatArray:
    """The frame each joint moves in (``F_0 M_1 ... F_{i-1}``): (..., n, 4, 4); joint i's
    axis is ``frame[:3, :3] @ axes[i]`` through ``frame[:3, 3]``."""
    return _frames(arm, q)[0]


def forward_kinematics(arm: SerialArm, q: ArrayLike) -> FloatArray:
    """The tool frame in the base frame: (..., 4, 4)."""
    return _frames(arm, q)[1]


def jacobian(arm: SerialArm, q: ArrayLike) -> FloatArray:
    """The geometric Jacobian (..., 6, n) about the tool point, in the base frame."""
    frames, tool = _frames(arm, q)
    axes = np.einsum("...ij,...j->...i", frames[..., :3, :3], arm.axes)  # (..., n, 3)
    reach = tool[..., None, :3, 3] - frames[..., :3, 3]  # (..., n, 3)
    linear = np.where(arm.prismatic[:, None], axes, np.cross(axes, reach))
    angular = np.where(arm.prismatic[:, None], 0.0, axes)
    return np.concatenate([linear, angular], axis=-1).swapaxes(-1, -2)
