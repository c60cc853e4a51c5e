"""Validated inputs of ``serial-indices``: an arm and joint configurations."""

from __future__ import annotations

import numpy as np
from pydantic import Field, model_validator

from worker.common.field_errors import field_error
from worker.families.serial.arm_inputs import ArmInputs, characteristic_length_field, plots_field
from worker.families.serial.kinematics.arm import SerialArm

__all__ = ["MAX_CONFIGURATIONS", "SerialIndicesSpec"]

#: The most joint configurations one ``serial-indices`` job evaluates.
MAX_CONFIGURATIONS = 100_000


class SerialIndicesSpec(ArmInputs):
    """Inputs of ``serial-indices``."""

    configurations: tuple[tuple[float, ...], ...] = Field(
        ...,
        min_length=1,
        max_length=MAX_CONFIGURATIONS,
        description="Joint values, one list per configuration with one value per movable "
        "joint: degrees for revolute joints, length_unit for prismatic ones.",
    )
    characteristic_length: float | None = characteristic_length_field()
    plots: bool = plots_field()

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

    def joint_values(self, arm: SerialArm) -> np.ndarray:
        """The configurations in radians / length units: (m, n)."""
        q = np.asarray(self.configurations, dtype=float).reshape(len(self.configurations), -1)
        return np.where(arm.prismatic, q, np.radians(q))
