"""Published arms as ``robot`` inputs (facts re-typed from their DH tables), and a
URDF of our own writing for the UR5 (docs/methods/serial.md).

- UR5: Universal Robots' standard DH parameters (metres).
- Puma 560: standard DH as in Corke's Robotics Toolbox model (d1 holds the shoulder's
  height above the floor, 0.6718 m), with its joint limits.
- Panda: Franka Emika's modified (Craig) DH parameters, the flange's 0.107 m in the
  last row and the hand's 0.1034 m and -45° about z as the tool, with its joint limits.
- Patel & Sobh's Example 1 arm, (l1, l2, l3) = (15, 14, 8), as a planar DH chain.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["EXAMPLE_1_PLANAR", "PANDA", "PUMA_560", "UR5", "UR5_URDF"]


def _rows(
    table: list[tuple[float, float, float]], limits: list[tuple[float, float]] | None = None
) -> list[dict[str, Any]]:
    """(a, alpha_deg, d) per joint, with optional limits in degrees."""
    rows: list[dict[str, Any]] = [{"a": a, "alpha_deg": alpha, "d": d} for a, alpha, d in table]
    for row, limit in zip(rows, limits or [], strict=False):
        row["limits"] = list(limit)
    return rows


_UR5_TABLE = [(0.0, 90.0, 0.089459), (-0.425, 0.0, 0.0), (-0.39225, 0.0, 0.0),
              (0.0, 90.0, 0.10915), (0.0, -90.0, 0.09465), (0.0, 0.0, 0.0823)]  # fmt: skip
UR5: dict[str, Any] = {"dh": _rows(_UR5_TABLE), "convention": "standard"}

PUMA_560: dict[str, Any] = {
    "dh": _rows(
        [
            (0.0, 90.0, 0.67183),
            (0.4318, 0.0, 0.0),
            (0.0203, -90.0, 0.15005),
            (0.0, 90.0, 0.4318),
            (0.0, -90.0, 0.0),
            (0.0, 0.0, 0.0),
        ],
        [(-160, 160), (-45, 225), (-225, 45), (-110, 170), (-100, 100), (-266, 266)],
    ),
    "convention": "standard",
}

PANDA: dict[str, Any] = {
    "dh": _rows(
        [
            (0.0, 0.0, 0.333),
            (0.0, -90.0, 0.0),
            (0.0, 90.0, 0.316),
            (0.0825, 90.0, 0.0),
            (-0.0825, -90.0, 0.384),
            (0.0, 90.0, 0.0),
            (0.088, 90.0, 0.107),
        ],
        [
            (-166.0031, 166.0031),
            (-101.0010, 101.0010),
            (-166.0031, 166.0031),
            (-176.0012, -3.9992),
            (-166.0031, 166.0031),
            (-1.0027, 215.0024),
            (-166.0031, 166.0031),
        ],
    ),
    "convention": "modified",
    "tool": {"xyz": [0.0, 0.0, 0.1034], "rpy_deg": [0.0, 0.0, -45.0]},
}

EXAMPLE_1_PLANAR: dict[str, Any] = {
    "dh": _rows([(15.0, 0.0, 0.0), (14.0, 0.0, 0.0), (8.0, 0.0, 0.0)]),
    "convention": "standard",
}


def _ur5_urdf() -> str:
    """The UR5 as a URDF: joint i's origin is DH row i-1's Tz(d) Tx(a) Rx(α) (the first
    at the base), every axis z, the last row as a fixed joint to ``tool0``."""
    links = ["base_link", "shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link",
             "wrist_2_link", "wrist_3_link", "tool0"]  # fmt: skip
    origins = [(0.0, 0.0, 0.0), *_UR5_TABLE]
    names = ["shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3"]
    parts = [f'<link name="{name}"/>' for name in links]
    for i, (a, alpha, d) in enumerate(origins):
        kind = "fixed" if i == 6 else "revolute"
        limit = (
            ""
            if i == 6
            else (f'<limit lower="{-math.pi!r}" upper="{math.pi!r}" effort="150" velocity="3.15"/>')
        )
        axis = "" if i == 6 else '<axis xyz="0 0 1"/>'
        name = "wrist_3_tool0" if i == 6 else f"{names[i]}_joint"
        parts.append(
            f'<joint name="{name}" type="{kind}"><parent link="{links[i]}"/>'
            f'<child link="{links[i + 1]}"/><origin xyz="{a!r} 0 {d!r}" '
            f'rpy="{math.radians(alpha)!r} 0 0"/>{axis}{limit}</joint>'
        )
    return '<?xml version="1.0"?>\n<robot name="ur5">\n  ' + "\n  ".join(parts) + "\n</robot>\n"


UR5_URDF: dict[str, Any] = {"urdf": _ur5_urdf(), "base_link": "base_link", "tip_link": "tool0"}
