"""Validated inputs of ``serial-indices``: an arm and joint configurations."""

from __future__ import annotations

from typing import Any

import numpy as np
from pydantic import Field, model_validator

from worker.common.field_errors import field_error
from worker.common.specs import FrozenSpec
from worker.families.serial.kinematics.arm import SerialArm
from worker.families.serial.robot_input import RobotSpec

__all__ = ["MAX_CONFIGURATIONS", "SerialIndicesSpec", "length_unit_field"]

#: The most joint configurations one ``serial-indices`` job evaluates.
MAX_CONFIGURATIONS = 100_000


def length_unit_field() -> Any:
    """The ``length_unit`` input (a label for lengths; URDFs are in metres)."""
    return Field("m", min_length=1, max_length=16, pattern=r"^[\w .°/-]+$",
                 description="Name of the length unit of the arm's lengths, used in plots "
                 "and reported back (a URDF's lengths are metres).")  # fmt: skip


class SerialIndicesSpec(FrozenSpec):
    """Inputs of ``serial-indices``."""

    robot: RobotSpec = Field(..., description="The arm: a DH table or a URDF chain.")
    configurations: tuple[tuple[float, ...], ...] = Field(
        ...,
        min_length=1,
        max_length=MAX_CONFIGURATIONS,
        description="Joint values, one list per configuration with one value per movable "
        "joint: degrees for revolute joints, length_unit for prismatic ones.",
    )
    characteristic_length: float | None = Field(
        None, gt=0.0, le=1e6, description="Divides the Jacobian's linear rows before the "
        "inverse condition number (length_unit); null: unscaled."
    )  # fmt: skip
    length_unit: str = length_unit_field()
    plots: bool = Field(True, description="Render the PNG/SVG plots. false: the result only.")

    @model_validator(mode="after")
    def _one_value_per_joint(self) -> SerialIndicesSpec:
        n = self.arm().joints
        for k, values in enumerate(self.configurations):
            if len(values) != n:
                raise field_error(self, ("configurations", k), f"the arm has {n} movable "
                                  f"joints; this configuration gives {len(values)} values",
                                  list(values))  # fmt: skip
            if any(abs(v) > 1e6 for v in values):
                raise field_error(self, ("configurations", k), "joint values must lie in "
                                  "[-1e6, 1e6]", list(values))  # fmt: skip
        return self

    def arm(self) -> SerialArm:
        """The validated arm."""
        return self.robot.arm(self.length_unit)

    def joint_values(self, arm: SerialArm) -> np.ndarray:
        """The configurations in radians / length units: (m, n)."""
        q = np.asarray(self.configurations, dtype=float).reshape(len(self.configurations), -1)
        return np.where(arm.prismatic, q, np.radians(q))
