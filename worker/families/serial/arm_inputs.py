"""The inputs every serial process shares: the arm (``robot``, first), the length
unit, the optional characteristic length and ``plots``, declared once."""

from __future__ import annotations

from typing import Any

from pydantic import Field

from worker.common.specs import FrozenSpec
from worker.families.serial.kinematics.arm import SerialArm
from worker.families.serial.robot_input import RobotSpec

__all__ = ["ArmInputs", "characteristic_length_field", "length_unit_field", "plots_field"]


def length_unit_field() -> Any:
    """The ``length_unit`` input (a label for lengths; URDFs are in metres)."""
    return Field("m", min_length=1, max_length=16, pattern=r"^[\w .°/-]+$",
                 description="Name of the length unit of the arm's lengths, used in plots "
                 "and reported back (a URDF's lengths are metres).")  # fmt: skip


def characteristic_length_field() -> Any:
    """The optional length dividing the Jacobian's linear rows."""
    return Field(None, gt=0.0, le=1e6, description="Divides the Jacobian's linear rows "
                 "before the inverse condition number (length_unit); null: unscaled.")  # fmt: skip


def plots_field() -> Any:
    """The ``plots`` switch."""
    return Field(True, description="Render the PNG/SVG plots. false: the result only.")


class ArmInputs(FrozenSpec):
    """A serial process's inputs: the ``robot`` first, then the process's own."""

    robot: RobotSpec = Field(..., description="The arm: a DH table or a URDF chain.")
    length_unit: str = length_unit_field()

    def arm(self) -> SerialArm:
        """The validated arm, in ``length_unit``."""
        return self.robot.arm(self.length_unit)
