"""A serial arm as one frozen object: fixed transforms between joint motions.

Every arm dexlab studies, from a DH table (standard or modified) or a URDF, becomes the
product ``T(q) = F_0 M_1(q_1) F_1 M_2(q_2) ... M_n(q_n) F_n``: ``F_i`` are fixed
homogeneous transforms (``F_0`` holds the ``base``, ``F_n`` the ``tool``), ``M_i`` is a
rotation about (revolute) or a translation along (prismatic) the unit axis ``axes[i]``,
given in the frame after ``F_{i-1}``.  Angles are radians here; lengths in the arm's
``length_unit``.  Built once per job (validated at the boundary); the kinematics trust it.

Standard DH row (a, α, d, θ): ``M(q)`` about z, then ``Rz(θ) Tz(d) Tx(a) Rx(α)`` (the
joint's motion commutes with ``Rz(θ) Tz(d)``).  Modified DH (Craig): row i holds the a
and α of the link before joint i: ``Rx(α) Tx(a) Rz(θ) Tz(d)`` before ``M_i`` about z.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "PLANAR_TOLERANCE",
    "DHRow",
    "SerialArm",
    "arm_from_dh",
    "rot_x",
    "rot_z",
    "rpy_transform",
    "trans",
]

FloatArray = NDArray[np.float64]
#: An axis counts as parallel to z (a planar arm) within this sine of the angle.
PLANAR_TOLERANCE = 1e-12


def rot_x(angle: float) -> FloatArray:
    """Homogeneous rotation about x by ``angle`` (rad), (4, 4)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]], dtype=float)


def rot_z(angle: float) -> FloatArray:
    """Homogeneous rotation about z by ``angle`` (rad), (4, 4)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], dtype=float)


def trans(x: float, y: float, z: float) -> FloatArray:
    """Homogeneous translation, (4, 4)."""
    out = np.eye(4)
    out[:3, 3] = (x, y, z)
    return out


def rpy_transform(xyz: Sequence[float], rpy: Sequence[float]) -> FloatArray:
    """``Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)`` (URDF's origin convention), rpy in rad."""
    roll, pitch, yaw = rpy
    cr, sr, cp, sp, cy, sy = (np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch),
                              np.cos(yaw), np.sin(yaw))  # fmt: skip
    out = np.eye(4)
    out[:3, :3] = [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
    out[:3, 3] = xyz
    return out


@dataclass(frozen=True)
class DHRow:
    """One DH row: lengths in the arm's unit, angles in rad; ``theta``/``d`` offsets."""

    a: float
    alpha: float
    d: float
    theta: float
    prismatic: bool
    lower: float
    upper: float


@dataclass(frozen=True, eq=False)
class SerialArm:
    """A serial arm: ``fixed`` (n+1, 4, 4), ``axes`` (n, 3) unit vectors, ``prismatic``
    (n,) bool, joint limits ``lower``/``upper`` (n,) (rad or length), joint ``names``."""

    fixed: FloatArray
    axes: FloatArray
    prismatic: NDArray[np.bool_]
    lower: FloatArray
    upper: FloatArray
    names: tuple[str, ...]
    length_unit: str = "units"

    @property
    def joints(self) -> int:
        """The number of movable joints, n."""
        return int(self.axes.shape[0])

    @property
    def planar(self) -> bool:
        """Every revolute axis parallel to the base z and every prismatic one normal to
        it, with every fixed transform keeping z: the task space is (x, y, φ)."""
        frame = np.eye(4)
        for i in range(self.joints):
            frame = frame @ self.fixed[i]
            rotation = frame[:3, :3]
            if abs(abs(rotation[2, 2]) - 1.0) > PLANAR_TOLERANCE:
                return False
            axis = rotation @ self.axes[i]
            along_z = abs(axis[2])
            if self.prismatic[i] and along_z > PLANAR_TOLERANCE:
                return False
            if not self.prismatic[i] and abs(along_z - 1.0) > PLANAR_TOLERANCE:
                return False
        final = frame @ self.fixed[-1]
        return bool(abs(abs(final[2, 2]) - 1.0) <= PLANAR_TOLERANCE)


def arm_from_dh(
    rows: Sequence[DHRow],
    convention: Literal["standard", "modified"],
    base: FloatArray | None = None,
    tool: FloatArray | None = None,
    names: Sequence[str] | None = None,
    length_unit: str = "units",
) -> SerialArm:
    """The arm of a DH table (see the module doc for both conventions)."""
    n = len(rows)
    fixed = np.empty((n + 1, 4, 4))
    fixed[0] = np.eye(4) if base is None else base
    for i in range(1, n + 1):
        fixed[i] = np.eye(4)
    for i, row in enumerate(rows):
        offset = rot_z(row.theta) @ trans(0.0, 0.0, row.d)
        if convention == "standard":
            fixed[i + 1] = offset @ trans(row.a, 0.0, 0.0) @ rot_x(row.alpha) @ fixed[i + 1]
        else:
            fixed[i] = fixed[i] @ rot_x(row.alpha) @ trans(row.a, 0.0, 0.0) @ offset
    if tool is not None:
        fixed[n] = fixed[n] @ tool
    return SerialArm(
        fixed=fixed,
        axes=np.tile([0.0, 0.0, 1.0], (n, 1)),
        prismatic=np.array([row.prismatic for row in rows], dtype=bool),
        lower=np.array([row.lower for row in rows], dtype=float),
        upper=np.array([row.upper for row in rows], dtype=float),
        names=tuple(names) if names is not None else tuple(f"q{i + 1}" for i in range(n)),
        length_unit=length_unit,
    )
