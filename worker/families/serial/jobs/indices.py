"""The ``serial-indices`` job: pose, Jacobian and dexterity indices per configuration.

Forward kinematics, the geometric Jacobian about the tool point and its singular values
for every configuration at once (:mod:`..kinematics.chain`, :mod:`..kinematics.indices`);
the result lists one entry per configuration, the figure draws the arm with its
manipulability ellipsoids (docs/methods/serial.md).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from worker.common.figures import figure_artifacts
from worker.common.progress import ProgressReporter
from worker.contract import Artifact, JobContext, JobOutcome
from worker.families.serial.kinematics.arm import SerialArm
from worker.families.serial.kinematics.chain import forward_kinematics, jacobian, joint_frames
from worker.families.serial.kinematics.indices import (
    inverse_condition,
    limit_distance,
    manipulability,
    singular_values,
    task_jacobian,
)
from worker.families.serial.plots.arm import arm_figure
from worker.families.serial.specs import SerialIndicesSpec

__all__ = ["arm_description", "run_serial_indices"]

#: Configurations drawn in the figure (the first ones).
DRAWN = 6


def arm_description(spec_robot: Any, arm: SerialArm) -> dict[str, Any]:
    """What the result says of the arm: its source, joints and task space."""
    planar = arm.planar
    return {
        "source": "dh" if spec_robot.dh is not None else "urdf",
        "convention": spec_robot.convention if spec_robot.dh is not None else None,
        "joints": arm.joints,
        "joint_names": list(arm.names),
        "joint_types": ["prismatic" if p else "revolute" for p in arm.prismatic],
        "planar": planar,
        "task_space": ["x", "y", "phi"] if planar else ["x", "y", "z", "rx", "ry", "rz"],
    }


def _joint_units(arm: SerialArm, values: np.ndarray) -> np.ndarray:
    """Radians to degrees for the revolute joints (length units stay)."""
    return np.where(arm.prismatic, values, np.degrees(values))


def run_serial_indices(spec: SerialIndicesSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + figures out."""
    progress = ProgressReporter(ctx)
    progress.report(0.0, "kinematics")
    arm = spec.arm()
    q = spec.joint_values(arm)
    tool = forward_kinematics(arm, q)
    full = jacobian(arm, q)
    task = task_jacobian(full, arm.planar)
    sigma = singular_values(task, spec.characteristic_length)
    measure = manipulability(task)
    kappa = inverse_condition(task, spec.characteristic_length)
    margin = _joint_units(arm, limit_distance(q, arm.lower, arm.upper))
    poses = [
        {
            "configuration": list(spec.configurations[k]),
            "position": tool[k, :3, 3].tolist(),
            "rotation": tool[k, :3, :3].tolist(),
            **(
                {"phi_deg": float(np.degrees(np.arctan2(tool[k, 1, 0], tool[k, 0, 0])))}
                if arm.planar
                else {}
            ),
            "jacobian": task[k].tolist(),
            "singular_values": sigma[k].tolist(),
            "manipulability": float(measure[k]),
            "inverse_condition": float(kappa[k]),
            "limit_distance": margin[k].tolist(),
            "within_limits": bool(np.all(margin[k] >= 0.0)),
        }
        for k in range(q.shape[0])
    ]
    summary: dict[str, Any] = {
        "configurations": len(poses),
        "manipulability_min": float(measure.min()),
        "manipulability_max": float(measure.max()),
        "inverse_condition_min": float(kappa.min()),
        "inverse_condition_mean": float(kappa.mean()),
        "outside_limits": int(sum(not p["within_limits"] for p in poses)),
    }
    result = {
        "arm": arm_description(spec.robot, arm),
        "length_unit": spec.length_unit,
        "characteristic_length": spec.characteristic_length,
        "poses": poses,
        "summary": summary,
    }
    notes = _notes(spec, arm, summary)
    artifacts: tuple[Artifact, ...] = ()
    if spec.plots:
        progress.report(60.0, "plots")
        drawn = q[:DRAWN]
        frames = joint_frames(arm, drawn)
        figure = arm_figure(arm, frames, tool[:DRAWN], full[:DRAWN], spec.length_unit)
        artifacts = figure_artifacts(figure, "arm", "The arm and its manipulability ellipsoids")
    progress.report(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(notes))


def _notes(spec: SerialIndicesSpec, arm: SerialArm, summary: dict[str, Any]) -> list[str]:
    notes = [
        "Jacobian in the base frame about the tool point, rows "
        + ("[x, y, phi] (planar arm)" if arm.planar else "[linear; angular]")
        + ", columns per radian (revolute) or per length unit (prismatic), unscaled."
    ]
    if spec.characteristic_length is not None:
        notes.append(f"The inverse condition number and singular values divide the linear "
                     f"rows by the characteristic length {spec.characteristic_length:g} "
                     f"{spec.length_unit}.")  # fmt: skip
    if summary["outside_limits"]:
        notes.append(f"{summary['outside_limits']} configuration(s) lie outside the joint "
                     "limits (negative limit_distance).")  # fmt: skip
    if len(spec.configurations) > DRAWN:
        notes.append(f"The figure draws the first {DRAWN} configurations.")
    return notes
