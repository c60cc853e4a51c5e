"""Closed-form inverse kinematics of planar 3R arms, used instead of the numerical
solver (docs/methods/serial.md).

A planar 3R arm here is a :class:`~.arm.SerialArm` with three revolute joints whose
axes are all the base's +z and whose fixed transforms keep +z (no flip): each ``F_i``
is a turn ``ψ_i`` about z, a shift ``t_i`` in the plane and a height.  Link k's vector
``t_k`` (length ``l_k``, angle ``β_k`` in its frame) turns with the absolute angle
``A_k = ψ_0 + q_1 + ψ_1 + ... + ψ_{k-1} + q_k``; the tool angle is ``φ = A_3 + ψ_3``.
For a DH table with α = 0 these are the a lengths l1..l3 (β = 0) and the θ offsets.

Given (x, y, φ): the wrist ``w = p − t_0 − l_3 (cos(A_3 + β_3), sin(A_3 + β_3))``,
``cos γ_2 = (|w|² − l_1² − l_2²) / (2 l_1 l_2)``, elbow ``γ_2 = ±acos`` (both
branches), ``γ_1 = atan2(w) − atan2(l_2 sin γ_2, l_1 + l_2 cos γ_2)``; then the joint
angles, each moved by whole turns into its limits if it can be (a branch outside
them is refused).  A position-only target scans φ in ``PHI_STEPS`` equal steps over a
turn and keeps the feasible branch of largest manipulability ``l_1 l_2 |sin γ_2|``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from worker.families.serial.kinematics.arm import PLANAR_TOLERANCE, SerialArm
from worker.families.serial.kinematics.chain import forward_kinematics
from worker.families.serial.kinematics.inverse import IKSolution, PoseTargets, pose_residuals

__all__ = ["PHI_STEPS", "Planar3R", "planar_3r_geometry", "solve_planar_3r"]

FloatArray = NDArray[np.float64]
#: φ values a position-only target scans (0.2° apart).
PHI_STEPS = 1800
#: Targets solved at once in a φ scan (memory: about 50 kB per target).
_SCAN_CHUNK = 256
_TURN = 2.0 * np.pi


@dataclass(frozen=True)
class Planar3R:
    """The planar geometry of a 3R arm (module doc): ``origin`` (2,) = t_0, ``lengths``
    (3,), ``link_angles`` β (3,), ``turns`` ψ_0..ψ_3 (4,) (rad), the joint limits."""

    origin: FloatArray
    lengths: FloatArray
    link_angles: FloatArray
    turns: FloatArray
    lower: FloatArray
    upper: FloatArray


def planar_3r_geometry(arm: SerialArm) -> Planar3R | None:
    """The arm's planar 3R geometry, or None when it is not such an arm (or l1 or l2
    is 0, where the closed form degenerates)."""
    if arm.joints != 3 or bool(arm.prismatic.any()):
        return None
    if np.any(np.abs(arm.axes[:, 2] - 1.0) > PLANAR_TOLERANCE):
        return None
    if np.any(np.abs(arm.fixed[:, 2, 2] - 1.0) > PLANAR_TOLERANCE):
        return None
    shifts = arm.fixed[1:, :2, 3]
    lengths = np.linalg.norm(shifts, axis=-1)
    if lengths[0] <= 0.0 or lengths[1] <= 0.0:
        return None
    return Planar3R(
        origin=arm.fixed[0, :2, 3].copy(),
        lengths=lengths,
        link_angles=np.arctan2(shifts[:, 1], shifts[:, 0]),
        turns=np.arctan2(arm.fixed[:, 1, 0], arm.fixed[:, 0, 0]),
        lower=arm.lower.copy(),
        upper=arm.upper.copy(),
    )


def _branches(geom: Planar3R, points: FloatArray, phi: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Both elbow branches for points (..., 2) and tool angles (...): joint angles
    (..., 2, 3) moved into the limits where they can be, and whether each branch
    exists and lies within the limits (..., 2)."""
    l1, l2, l3 = geom.lengths
    b1, b2, b3 = geom.link_angles
    p0, p1, p2, p3 = geom.turns
    a3 = phi - p3
    wx = points[..., 0] - geom.origin[0] - l3 * np.cos(a3 + b3)
    wy = points[..., 1] - geom.origin[1] - l3 * np.sin(a3 + b3)
    c2 = (wx**2 + wy**2 - l1**2 - l2**2) / (2.0 * l1 * l2)
    exists = np.abs(c2) <= 1.0 + 1e-12
    g2 = np.stack([1.0, -1.0]) * np.arccos(np.clip(c2, -1.0, 1.0))[..., None]  # (..., 2)
    g1 = np.arctan2(wy, wx)[..., None] - np.arctan2(l2 * np.sin(g2), l1 + l2 * np.cos(g2))
    q1 = g1 - b1 - p0
    q2 = g1 + g2 - b2 - p0 - p1 - q1
    q3 = a3[..., None] - p0 - p1 - p2 - q1 - q2
    raw = np.stack([q1, q2, q3], axis=-1)
    moved = geom.lower + np.mod(raw - geom.lower, _TURN)
    inside = np.all(moved <= geom.upper + 1e-12, axis=-1)
    q = np.where(inside[..., None], np.minimum(moved, geom.upper), np.clip(raw, geom.lower,
                 geom.upper))  # fmt: skip
    return q, exists[..., None] & inside


def _pick(q: FloatArray, ok: FloatArray, elbow: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Per target (axis 0), the feasible candidate (flattened trailing axes) of largest
    ``|sin γ_2|``, else the first: (t, 3) and its count of feasible candidates."""
    t = q.shape[0]
    flat_q = q.reshape(t, -1, 3)
    flat_ok = ok.reshape(t, -1)
    score = np.where(flat_ok, np.abs(np.sin(elbow.reshape(t, -1))), -1.0)
    best = np.argmax(score, axis=1)
    return flat_q[np.arange(t), best], flat_ok.sum(axis=1)


def solve_planar_3r(arm: SerialArm, geom: Planar3R, targets: PoseTargets) -> IKSolution:
    """Closed-form solutions of every target (module doc); ``reached`` also asks the
    solution's pose to lie within the target's tolerances (the target's height too)."""
    t = targets.count
    q = np.zeros((t, 3))
    solutions = np.zeros(t, dtype=np.int64)
    points = targets.positions[:, :2]
    phi = np.arctan2(targets.rotations[:, 1, 0], targets.rotations[:, 0, 0])
    oriented = np.flatnonzero(targets.oriented)
    if oriented.size:
        branch_q, ok = _branches(geom, points[oriented], phi[oriented])
        elbow = branch_q[..., 1] + geom.turns[1] + geom.link_angles[1] - geom.link_angles[0]
        q[oriented], counts = _pick(branch_q, ok, elbow)
        solutions[oriented] = counts
    scan = np.linspace(0.0, _TURN, PHI_STEPS, endpoint=False)
    free = np.flatnonzero(~targets.oriented)
    for start in range(0, free.size, _SCAN_CHUNK):
        chunk = free[start : start + _SCAN_CHUNK]
        grid_points = np.broadcast_to(points[chunk, None, :], (chunk.size, PHI_STEPS, 2))
        branch_q, ok = _branches(geom, grid_points, np.broadcast_to(scan, (chunk.size,
                                 PHI_STEPS)))  # fmt: skip
        elbow = branch_q[..., 1] + geom.turns[1] + geom.link_angles[1] - geom.link_angles[0]
        q[chunk], _ = _pick(branch_q, ok, elbow)
        solutions[chunk] = ok.reshape(chunk.size, -1).any(axis=1)
    tool = forward_kinematics(arm, q)
    distance, angle = pose_residuals(arm, tool, targets, np.arange(t))
    reached = (solutions > 0) & (distance <= targets.position_tolerance)
    reached &= angle <= targets.orientation_tolerance
    return IKSolution(q=q, reached=reached, position_residual=distance,
                      orientation_residual=angle, solutions=solutions)  # fmt: skip
