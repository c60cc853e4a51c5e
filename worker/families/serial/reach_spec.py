"""Validated inputs of ``serial-reach``: an arm and target poses.

A target is ``{"position": [x, y, z], "rpy_deg": [roll, pitch, yaw], "tolerance":
{"position": ..., "orientation_deg": ...}}``: the tool point in the base frame, an
optional tool orientation as URDF's roll-pitch-yaw (``Rz(yaw) Ry(pitch) Rx(roll)``,
degrees, the form of ``base`` and ``tool``) and optional tolerances.  A planar arm
takes ``[x, y]`` (the arm's own plane) or ``[x, y, z]``, and only a yaw (the tool angle
φ about z; roll and pitch 0).
"""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import BeforeValidator, Field, model_validator

from worker.common.field_errors import field_error
from worker.common.specs import FrozenSpec
from worker.families.serial.arm_inputs import ArmInputs, characteristic_length_field, plots_field
from worker.families.serial.kinematics.arm import SerialArm, rpy_transform
from worker.families.serial.kinematics.chain import forward_kinematics
from worker.families.serial.kinematics.inverse import PoseTargets, arm_scale
from worker.families.serial.robot_input import MAX_LENGTH

__all__ = [
    "DEFAULT_ORIENTATION_TOLERANCE_DEG",
    "DEFAULT_POSITION_TOLERANCE",
    "MAX_ITERATIONS",
    "MAX_SEEDS",
    "MAX_TARGETS",
    "ReachTarget",
    "SerialReachSpec",
    "TargetTolerance",
]

#: The most targets one ``serial-reach`` job solves.
MAX_TARGETS = 10_000
#: The most starting configurations per target.
MAX_SEEDS = 64
#: The most damped least-squares iterations per seed.
MAX_ITERATIONS = 2_000
#: The default position tolerance, as a fraction of the arm's size (its fixed
#: translations' lengths plus its prismatic travel).
DEFAULT_POSITION_TOLERANCE = 1e-6
#: The default orientation tolerance (degrees).
DEFAULT_ORIENTATION_TOLERANCE_DEG = 1e-3


def _not_empty(value: Any) -> Any:
    if isinstance(value, list | tuple) and not value:
        raise ValueError("give at least one target")
    return value


class TargetTolerance(FrozenSpec):
    """How close the tool must come to a target to reach it."""

    position: float | None = Field(
        None, gt=0.0, le=MAX_LENGTH, description="Distance of the tool point (length_unit); "
        f"default {DEFAULT_POSITION_TOLERANCE:g} x the arm's size."
    )  # fmt: skip
    orientation_deg: float = Field(
        DEFAULT_ORIENTATION_TOLERANCE_DEG, gt=0.0, le=180.0,
        description="Angle between the tool's and the target's rotations (degrees).",
    )  # fmt: skip


class ReachTarget(FrozenSpec):
    """One target pose of the tool."""

    position: tuple[float, ...] = Field(
        ..., min_length=2, max_length=3, description="The tool point in the base frame "
        "(length_unit): [x, y, z], or [x, y] for a planar arm (in its plane)."
    )  # fmt: skip
    rpy_deg: tuple[float, float, float] | None = Field(
        None, description="The tool orientation as roll, pitch, yaw (degrees; "
        "Rz(yaw) Ry(pitch) Rx(roll), as 'base' and 'tool'); a planar arm takes a yaw only "
        "(its tool angle phi). null: position only."
    )  # fmt: skip
    tolerance: TargetTolerance = Field(TargetTolerance(), description="Tolerances.")


class SerialReachSpec(ArmInputs):
    """Inputs of ``serial-reach``."""

    # no min_length: pydantic would add "at least 1 item" whenever an item is refused;
    # an empty list is refused before the items instead (the schema keeps minItems)
    targets: Annotated[tuple[ReachTarget, ...], BeforeValidator(_not_empty)] = Field(
        ..., max_length=MAX_TARGETS, json_schema_extra={"minItems": 1},
        description="Target poses of the tool.",
    )  # fmt: skip
    seeds: int = Field(8, ge=1, le=MAX_SEEDS, description="Starting configurations per "
                       "target, uniform inside the joint limits.")  # fmt: skip
    seed: int = Field(0, ge=0, le=2**32 - 1, description="Seed of the starting "
                      "configurations: same seed, same result.")  # fmt: skip
    max_iterations: int = Field(
        200, ge=1, le=MAX_ITERATIONS,
        description="Damped least-squares iterations per target (all seeds at once).",
    )  # fmt: skip
    solver: Literal["auto", "numerical"] = Field(
        "auto", description="auto: closed form for a planar 3R arm, damped least squares "
        "otherwise; numerical: damped least squares always."
    )  # fmt: skip
    characteristic_length: float | None = characteristic_length_field()
    plots: bool = plots_field()

    @model_validator(mode="after")
    def _targets_fit_the_arm(self) -> SerialReachSpec:
        planar = self.arm().planar
        for k, target in enumerate(self.targets):
            if any(abs(v) > MAX_LENGTH for v in target.position):
                raise field_error(self, ("targets", k, "position"), f"coordinates must lie "
                                  f"in [-{MAX_LENGTH:g}, {MAX_LENGTH:g}]",
                                  list(target.position))  # fmt: skip
            if len(target.position) == 2 and not planar:
                raise field_error(self, ("targets", k, "position"), "a spatial arm's target "
                                  "needs [x, y, z]", list(target.position))  # fmt: skip
            rpy = target.rpy_deg
            if rpy is not None and any(abs(v) > 360.0 for v in rpy):
                raise field_error(self, ("targets", k, "rpy_deg"), "angles must lie in "
                                  "[-360, 360] degrees", list(rpy))  # fmt: skip
            if planar and rpy is not None and (rpy[0] != 0.0 or rpy[1] != 0.0):
                raise field_error(self, ("targets", k, "rpy_deg"), "a planar arm's tool "
                                  "turns about z only: give [0, 0, phi]", list(rpy))  # fmt: skip
        return self

    def pose_targets(self, arm: SerialArm) -> PoseTargets:
        """The targets as arrays (a planar target's missing z: the arm's plane)."""
        plane = float(forward_kinematics(arm, np.zeros(arm.joints))[2, 3])
        positions = np.array([(*t.position, plane)[:3] for t in self.targets], dtype=float)
        rotations = np.array([
            rpy_transform((0.0, 0.0, 0.0), [math.radians(v) for v in t.rpy_deg])[:3, :3]
            if t.rpy_deg is not None else np.eye(3)
            for t in self.targets
        ])  # fmt: skip
        size = arm_scale(arm)
        given = [t.tolerance.position for t in self.targets]
        position_tolerance = [DEFAULT_POSITION_TOLERANCE * size if g is None else g for g in given]
        return PoseTargets(
            positions=positions,
            rotations=rotations,
            oriented=np.array([t.rpy_deg is not None for t in self.targets], dtype=bool),
            position_tolerance=np.array(position_tolerance, dtype=float),
            orientation_tolerance=np.radians([t.tolerance.orientation_deg for t in self.targets]),
        )
