"""Numerical inverse kinematics of a :class:`~.arm.SerialArm`: damped least squares
(Levenberg–Marquardt) from several seeds at once, within the joint limits.

Every target gets ``seeds`` starting configurations drawn uniformly inside the joint
limits from a seeded numpy ``Generator`` (reproducible: the same seed, the same
answer); all targets x seeds iterate together as one batch.  One step solves

    Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e

on the weighted task error ``e`` = [(p_t − p) / L; rotation vector of R_t Rᵀ] (for a
planar arm [(x_t − x) / L, (y_t − y) / L, φ_t − φ wrapped]), ``J`` the task Jacobian
with the same row weights, ``L`` the length scale (the arm's size, so a length error
of L weighs as one radian).  Position-only targets weigh the angular rows 0.  The step
drops the columns of joints held at a limit it pushes against and is projected onto
the limits (:func:`project_to_limits`: clamped, or wrapped for a revolute joint free
over a full turn); it is kept when the error drops (λ halves, down to
``MIN_DAMPING``), refused otherwise (λ triples).  A seed stops once within both
tolerances (position in length units, orientation in rad), when λ passes
``MAX_DAMPING`` (stuck), or after ``max_iterations``; with a ``restarts`` generator a
stuck seed of a target no seed has reached starts again from a fresh draw.  Per
target, among the seeds that converged the one with the largest manipulability is the
solution; if none did, the closest configuration any seed found (``reached`` False).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from worker.families.serial.kinematics.arm import SerialArm
from worker.families.serial.kinematics.chain import forward_kinematics, jacobian
from worker.families.serial.kinematics.indices import manipulability, task_jacobian
from worker.families.serial.kinematics.rotations import orientation_error, rotation_angle

__all__ = [
    "INITIAL_DAMPING",
    "MAX_DAMPING",
    "MIN_DAMPING",
    "IKSolution",
    "PoseTargets",
    "arm_scale",
    "pose_residuals",
    "project_to_limits",
    "seed_configurations",
    "solve_damped_least_squares",
]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]
#: λ at the start of every seed (on the weighted, dimensionless task error).
INITIAL_DAMPING = 1e-2
#: λ never falls below this (J Jᵀ + λ² I stays invertible where rows are 0).
MIN_DAMPING = 1e-6
#: A seed whose λ grows past this makes no progress: it stops.
MAX_DAMPING = 1e6


@dataclass(frozen=True, eq=False)
class PoseTargets:
    """Target poses in the base frame: ``positions`` (t, 3) (length units),
    ``rotations`` (t, 3, 3) (ignored where ``oriented`` (t,) is False),
    ``position_tolerance`` (t,) (length units), ``orientation_tolerance`` (t,) (rad)."""

    positions: FloatArray
    rotations: FloatArray
    oriented: BoolArray
    position_tolerance: FloatArray
    orientation_tolerance: FloatArray

    @property
    def count(self) -> int:
        """The number of targets, t."""
        return int(self.positions.shape[0])

    def take(self, which: NDArray[np.intp]) -> PoseTargets:
        """The targets ``which`` (k,), in that order."""
        return PoseTargets(self.positions[which], self.rotations[which], self.oriented[which],
                           self.position_tolerance[which],
                           self.orientation_tolerance[which])  # fmt: skip


@dataclass(frozen=True, eq=False)
class IKSolution:
    """One solution per target: ``q`` (t, n) (rad / length units), ``reached`` (t,),
    ``position_residual`` (t,) (length units), ``orientation_residual`` (t,) (rad),
    ``solutions`` (t,) (how many seeds, or closed-form branches, reached the target)."""

    q: FloatArray
    reached: BoolArray
    position_residual: FloatArray
    orientation_residual: FloatArray
    solutions: NDArray[np.int64]

    def replaced(self, which: NDArray[np.intp], other: IKSolution) -> IKSolution:
        """This solution with targets ``which`` (k,) answered by ``other`` (k targets)."""
        fields = ("q", "reached", "position_residual", "orientation_residual", "solutions")
        merged = {name: getattr(self, name).copy() for name in fields}
        for name, values in merged.items():
            values[which] = getattr(other, name)
        return IKSolution(**merged)


def arm_scale(arm: SerialArm) -> float:
    """The arm's size (length units): the lengths of its fixed translations plus each
    prismatic joint's largest travel; 1 for an arm of no length."""
    size = float(np.linalg.norm(arm.fixed[:, :3, 3], axis=-1).sum())
    travel = np.maximum(np.abs(arm.lower), np.abs(arm.upper))
    size += float(np.where(arm.prismatic, travel, 0.0).sum())
    return size if size > 0.0 else 1.0


def seed_configurations(
    arm: SerialArm, targets: int, seeds: int, rng: np.random.Generator
) -> FloatArray:
    """Starting configurations (targets, seeds, n), uniform inside the joint limits, from
    generator ``rng`` (``numpy.random.default_rng(seed)``: reproducible)."""
    unit = rng.random((targets, seeds, arm.joints))
    out: FloatArray = arm.lower + unit * (arm.upper - arm.lower)
    return out


def project_to_limits(arm: SerialArm, q: FloatArray) -> FloatArray:
    """Configurations (..., n) moved inside the joint limits: a revolute joint whose range
    spans a full turn is wrapped into ``[lower, lower + 2π)``, any other joint clamped."""
    turn = 2.0 * np.pi
    full = ~arm.prismatic & (arm.upper - arm.lower >= turn)
    wrapped = arm.lower + np.mod(q - arm.lower, turn)
    out: FloatArray = np.where(full, wrapped, np.clip(q, arm.lower, arm.upper))
    return out


def _wrapped(angle: FloatArray) -> FloatArray:
    """Angles wrapped to [−π, π)."""
    out: FloatArray = (angle + np.pi) % (2.0 * np.pi) - np.pi
    return out


def _phi(tool: FloatArray) -> FloatArray:
    """A planar arm's tool angle about z (...,) (rad)."""
    out: FloatArray = np.arctan2(tool[..., 1, 0], tool[..., 0, 0])
    return out


def pose_residuals(
    arm: SerialArm, tool: FloatArray, targets: PoseTargets, which: NDArray[np.intp]
) -> tuple[FloatArray, FloatArray]:
    """(position distance (b,), orientation angle (b,) rad) of tool frames (b, 4, 4)
    against the targets ``which`` (b,) (the angle is 0 for position-only targets)."""
    distance = np.linalg.norm(targets.positions[which] - tool[:, :3, 3], axis=-1)
    if arm.planar:
        angle = np.abs(_wrapped(_phi(targets.rotations[which]) - _phi(tool)))
    else:
        angle = rotation_angle(targets.rotations[which] @ np.swapaxes(tool[:, :3, :3], -1, -2))
    return distance, np.where(targets.oriented[which], angle, 0.0)


def _weighted_error(
    arm: SerialArm, tool: FloatArray, targets: PoseTargets, which: NDArray[np.intp], scale: float
) -> FloatArray:
    """The weighted task error (b, m) (module doc)."""
    linear = (targets.positions[which] - tool[:, :3, 3]) / scale
    turn = targets.oriented[which][:, None]
    if arm.planar:
        dphi = _wrapped(_phi(targets.rotations[which]) - _phi(tool))
        return np.concatenate([linear[:, :2], np.where(turn, dphi[:, None], 0.0)], axis=-1)
    angular = orientation_error(targets.rotations[which], tool[:, :3, :3])
    return np.concatenate([linear, np.where(turn, angular, 0.0)], axis=-1)


def _weighted_jacobian(
    arm: SerialArm, q: FloatArray, oriented: BoolArray, scale: float
) -> FloatArray:
    """The task Jacobian (b, m, n) with the error's row weights."""
    task = task_jacobian(jacobian(arm, q), arm.planar)
    linear = 2 if arm.planar else 3
    weights = np.ones((q.shape[0], task.shape[-2]))
    weights[:, :linear] = 1.0 / scale
    weights[:, linear:] = oriented[:, None]
    out: FloatArray = task * weights[..., None]
    return out


def _damped_step(jac: FloatArray, error: FloatArray, damping: FloatArray) -> FloatArray:
    """``Jᵀ (J Jᵀ + λ² I)⁻¹ e`` (b, n) for Jacobians (b, m, n), errors (b, m), λ (b,)."""
    normal = jac @ np.swapaxes(jac, -1, -2)
    normal += (damping**2)[:, None, None] * np.eye(jac.shape[-2])
    step = np.swapaxes(jac, -1, -2) @ np.linalg.solve(normal, error[..., None])
    out: FloatArray = step[..., 0]
    return out


def _converged(
    distance: FloatArray, angle: FloatArray, targets: PoseTargets, which: NDArray[np.intp]
) -> BoolArray:
    return np.asarray(
        (distance <= targets.position_tolerance[which])
        & (angle <= targets.orientation_tolerance[which])
    )


def solve_damped_least_squares(
    arm: SerialArm,
    targets: PoseTargets,
    starts: FloatArray,
    max_iterations: int,
    scale: float | None = None,
    restarts: np.random.Generator | None = None,
) -> IKSolution:
    """Solve every target from its starting configurations ``starts`` (t, s, n) (see
    the module doc); ``scale`` defaults to :func:`arm_scale`.  With ``restarts``, a
    seed that gets stuck while its target has no solution yet starts again from a
    configuration drawn from that generator (uniform in the limits) while iterations
    remain; each seed's closest configuration is kept for the closest answer."""
    length = arm_scale(arm) if scale is None else scale
    t, s, n = starts.shape
    which = np.repeat(np.arange(t), s)  # the target of each flattened seed
    q = project_to_limits(arm, starts.reshape(t * s, n))
    tool = forward_kinematics(arm, q)
    error = _weighted_error(arm, tool, targets, which, length)
    norm = np.linalg.norm(error, axis=-1)
    damping = np.full(t * s, INITIAL_DAMPING)
    done = _converged(*pose_residuals(arm, tool, targets, which), targets, which)
    best_q, best_tool, best_norm = q.copy(), tool.copy(), norm.copy()
    free = ~arm.prismatic & (arm.upper - arm.lower >= 2.0 * np.pi)  # wrapped, never held
    for _ in range(max_iterations):
        if restarts is not None:
            solved = np.asarray(done.reshape(t, s).any(axis=1))[which]
            stuck = np.flatnonzero(~done & (damping > MAX_DAMPING) & ~solved)
            if stuck.size:
                unit = restarts.random((stuck.size, n))
                q[stuck] = project_to_limits(arm, arm.lower + unit * (arm.upper - arm.lower))
                tool[stuck] = forward_kinematics(arm, q[stuck])
                error[stuck] = _weighted_error(arm, tool[stuck], targets, which[stuck], length)
                norm[stuck] = np.linalg.norm(error[stuck], axis=-1)
                damping[stuck] = INITIAL_DAMPING
        idx = np.flatnonzero(~done & (damping <= MAX_DAMPING))
        if idx.size == 0:
            break
        jac = _weighted_jacobian(arm, q[idx], targets.oriented[which[idx]], length)
        step = _damped_step(jac, error[idx], damping[idx])
        # joints at a limit the step pushes against are held: their columns drop out
        held = ((q[idx] <= arm.lower) & (step < 0.0)) | ((q[idx] >= arm.upper) & (step > 0.0))
        held &= ~free
        step = np.where(
            held.any(axis=-1, keepdims=True),
            _damped_step(jac * ~held[:, None, :], error[idx], damping[idx]),
            step,
        )
        trial = project_to_limits(arm, q[idx] + step)
        trial_tool = forward_kinematics(arm, trial)
        trial_error = _weighted_error(arm, trial_tool, targets, which[idx], length)
        trial_norm = np.linalg.norm(trial_error, axis=-1)
        better = trial_norm < norm[idx]
        kept = idx[better]
        q[kept], tool[kept], error[kept], norm[kept] = (
            trial[better], trial_tool[better], trial_error[better], trial_norm[better])  # fmt: skip
        damping[idx] = np.where(
            better, np.maximum(damping[idx] * 0.5, MIN_DAMPING), damping[idx] * 3.0
        )
        done[kept] = _converged(*pose_residuals(arm, tool[kept], targets, which[kept]),
                                targets, which[kept])  # fmt: skip
        closer = kept[(norm[kept] < best_norm[kept]) | done[kept]]
        best_q[closer], best_tool[closer], best_norm[closer] = q[closer], tool[closer], norm[closer]
    return _best_per_target(arm, targets, best_q.reshape(t, s, n), best_tool,
                            done.reshape(t, s), best_norm)  # fmt: skip


def _best_per_target(
    arm: SerialArm,
    targets: PoseTargets,
    q: FloatArray,
    tool: FloatArray,
    done: BoolArray,
    norm: FloatArray,
) -> IKSolution:
    """The converged seed of largest manipulability per target, else the closest."""
    t, s, _ = q.shape
    measure = manipulability(task_jacobian(jacobian(arm, q), arm.planar))  # (t, s)
    score = np.where(done, -measure, np.inf)
    closest = np.argmin(norm.reshape(t, s), axis=1)
    best = np.where(done.any(axis=1), np.argmin(score, axis=1), closest)
    rows = np.arange(t)
    chosen_tool = tool.reshape(t, s, 4, 4)[rows, best]
    distance, angle = pose_residuals(arm, chosen_tool, targets, rows)
    return IKSolution(
        q=q[rows, best],
        reached=done[rows, best],
        position_residual=distance,
        orientation_residual=angle,
        solutions=done.sum(axis=1).astype(np.int64),
    )
