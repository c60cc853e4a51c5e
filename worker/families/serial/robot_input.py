"""The ``robot`` input every serial process shares: a DH table or a URDF.

Validated once at the boundary into a frozen :class:`~.kinematics.arm.SerialArm`
(:meth:`RobotSpec.arm`); a bad model is a 422 naming the field (``robot.dh[3].type``,
``robot.urdf`` with the joint's name in the message).
"""

from __future__ import annotations

import math
from typing import Any, Literal

import numpy as np
from pydantic import Field, model_validator

from worker.common.field_errors import field_error
from worker.common.specs import FrozenSpec
from worker.families.serial.dh_table import MAX_DH_TABLE_CHARS, dh_rows
from worker.families.serial.kinematics.arm import DHRow, SerialArm, arm_from_dh, rpy_transform
from worker.families.serial.urdf_chain import MAX_URDF_BYTES, UrdfProblem, arm_from_urdf

__all__ = ["MAX_JOINTS", "DHJoint", "Placement", "RobotSpec"]

#: The most movable joints an arm may have.
MAX_JOINTS = 12
#: Lengths (a, d, offsets, limits of prismatic joints) are at most this in magnitude.
MAX_LENGTH = 1e6
_Length = Field(0.0, ge=-MAX_LENGTH, le=MAX_LENGTH)


class Placement(FrozenSpec):
    """A rigid transform: ``Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)``."""

    xyz: tuple[float, float, float] = Field((0.0, 0.0, 0.0), description="Translation "
                                             "(length_unit).")  # fmt: skip
    rpy_deg: tuple[float, float, float] = Field(
        (0.0, 0.0, 0.0), description="Roll, pitch, yaw about x, y, z (degrees; URDF's order)."
    )

    def matrix(self) -> np.ndarray:
        """(4, 4) homogeneous."""
        return rpy_transform(self.xyz, [math.radians(v) for v in self.rpy_deg])


class DHJoint(FrozenSpec):
    """One DH row: the joint's link parameters and its range."""

    a: float = Field(0.0, ge=-MAX_LENGTH, le=MAX_LENGTH, description="Link length a "
                     "(length_unit).")  # fmt: skip
    alpha_deg: float = Field(0.0, ge=-360.0, le=360.0, description="Link twist α (degrees).")
    d: float = Field(0.0, ge=-MAX_LENGTH, le=MAX_LENGTH, description="Link offset d "
                     "(length_unit); a prismatic joint's value adds to it.")  # fmt: skip
    theta_deg: float = Field(0.0, ge=-360.0, le=360.0, description="Joint angle offset θ "
                             "(degrees); a revolute joint's value adds to it.")  # fmt: skip
    type: Literal["revolute", "prismatic"] = "revolute"
    limits: tuple[float, float] | None = Field(
        None,
        description="[lower, upper]: degrees for a revolute joint (default [-180, 180]), "
        "length_unit for a prismatic one (required).",
    )

    @model_validator(mode="after")
    def _limits(self) -> DHJoint:
        if self.limits is None:
            if self.type == "prismatic":
                raise field_error(self, "limits", "a prismatic joint needs its limits "
                                  "[lower, upper] in length_unit", None)  # fmt: skip
            return self
        lo, hi = self.limits
        if not lo <= hi:
            raise field_error(self, "limits", f"lower {lo:g} exceeds upper {hi:g}", self.limits)
        bound = 360.0 if self.type == "revolute" else MAX_LENGTH
        if max(abs(lo), abs(hi)) > bound:
            raise field_error(self, "limits", f"limits must lie in [-{bound:g}, {bound:g}]",
                              self.limits)  # fmt: skip
        return self

    def row(self) -> DHRow:
        """The row in radians."""
        revolute = self.type == "revolute"
        lo, hi = self.limits if self.limits is not None else (-180.0, 180.0)
        to = math.radians if revolute else float
        return DHRow(a=self.a, alpha=math.radians(self.alpha_deg), d=self.d,
                     theta=math.radians(self.theta_deg), prismatic=not revolute,
                     lower=to(lo), upper=to(hi))  # fmt: skip


class RobotSpec(FrozenSpec):
    """The arm: ``{"dh": [...], "convention": ...}`` or ``{"urdf": ..., "base_link": ...,
    "tip_link": ...}``, with optional ``base`` and ``tool`` placements."""

    dh: tuple[DHJoint, ...] | None = Field(
        None, max_length=MAX_JOINTS, description=f"DH rows, one per joint (1..{MAX_JOINTS})."
    )
    dh_table: str | None = Field(
        None,
        max_length=MAX_DH_TABLE_CHARS,
        description="Instead of 'dh': the DH table as text, as copied from a paper or a "
        "spreadsheet: a header row naming the columns (a, alpha_deg, d; optional "
        "theta_deg, type, lower, upper), then one row per joint, separated by commas, "
        "tabs or spaces. Read into 'dh' rows (the stored inputs hold the rows).",
    )
    convention: Literal["standard", "modified"] = Field(
        "standard",
        description="standard: Rz(θ)·Tz(d)·Tx(a)·Rx(α) per row; modified (Craig): row i "
        "holds the a and α of the link before joint i.",
    )
    urdf: str | None = Field(
        None,
        max_length=MAX_URDF_BYTES,
        description="A URDF document (plain URDF, not xacro; at most 256 KB; meshes ignored).",
    )
    base_link: str | None = Field(None, max_length=200, description="The URDF link the "
                                  "chain starts at.")  # fmt: skip
    tip_link: str | None = Field(None, max_length=200, description="The URDF link the chain "
                                 "ends at (the tool frame before `tool`).")  # fmt: skip
    base: Placement | None = Field(None, description="Where the arm's base sits.")
    tool: Placement | None = Field(None, description="The tool point from the last frame.")

    @model_validator(mode="before")
    @classmethod
    def _table_rows(cls, data: Any) -> Any:
        """A ``dh_table`` becomes ``dh`` rows (with ``dh`` too, it is refused)."""
        if not isinstance(data, dict) or data.get("dh_table") is None:
            return data
        text = data["dh_table"]
        if not isinstance(text, str) or len(text) > MAX_DH_TABLE_CHARS:
            return data  # the field's own check says what is wrong
        if data.get("dh") is not None:
            raise field_error(cls, "dh_table", "give the DH rows as 'dh' or as 'dh_table', "
                              "not both", None)  # fmt: skip
        try:
            rows = dh_rows(text)
        except ValueError as exc:
            raise field_error(cls, "dh_table", str(exc), None) from None
        return {**{k: v for k, v in data.items() if k != "dh_table"}, "dh": rows}

    @model_validator(mode="after")
    def _one_model(self) -> RobotSpec:
        if (self.dh is None) == (self.urdf is None):
            raise field_error(self, "dh" if self.dh is not None else "urdf",
                              "give the arm either as 'dh' rows or as a 'urdf' document, "
                              "not both and not neither", None)  # fmt: skip
        if self.dh is not None:
            if not self.dh:
                raise field_error(self, "dh", "at least one joint", [])
            for key in ("base_link", "tip_link"):
                if getattr(self, key) is not None:
                    raise field_error(self, key, f"{key} belongs to a URDF arm", None)
            return self
        for key in ("base_link", "tip_link"):
            if getattr(self, key) is None:
                raise field_error(self, key, f"a URDF arm needs its {key}", None)
        try:
            arm = self._urdf_arm("units")
        except UrdfProblem as problem:
            raise field_error(self, "urdf", str(problem), None) from None
        if arm.joints == 0:
            raise field_error(self, "urdf", "the chain from base_link to tip_link has no "
                              "movable joint", None)  # fmt: skip
        if arm.joints > MAX_JOINTS:
            raise field_error(self, "urdf", f"the chain has {arm.joints} movable joints; at "
                              f"most {MAX_JOINTS}", None)  # fmt: skip
        return self

    def _urdf_arm(self, length_unit: str) -> SerialArm:
        assert self.urdf is not None and self.base_link is not None and self.tip_link is not None
        return arm_from_urdf(self.urdf, self.base_link, self.tip_link, self._base(),
                             self._tool(), length_unit)  # fmt: skip

    def _base(self) -> np.ndarray | None:
        return None if self.base is None else self.base.matrix()

    def _tool(self) -> np.ndarray | None:
        return None if self.tool is None else self.tool.matrix()

    def arm(self, length_unit: str) -> SerialArm:
        """The validated arm, labelled with ``length_unit``."""
        if self.dh is not None:
            return arm_from_dh([joint.row() for joint in self.dh], self.convention,
                               self._base(), self._tool(), length_unit=length_unit)  # fmt: skip
        return self._urdf_arm(length_unit)
