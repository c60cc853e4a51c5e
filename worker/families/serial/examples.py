"""Worked examples of the serial processes: published arms (:mod:`.arms`) in a few
configurations, ready to POST (docs/methods/serial.md)."""

from __future__ import annotations

from types import MappingProxyType
from typing import Any

from worker.families.serial.arms import EXAMPLE_1_PLANAR, PANDA, PUMA_560, UR5, UR5_URDF
from worker.processes import ProcessExample

__all__ = ["SERIAL_INDICES_EXAMPLES"]

_UR5_POSES = [[0, -90, 90, -90, -90, 0], [30, -60, 45, -75, -90, 15], [0, 0, 0, 0, 0, 0]]


def _example(title: str, description: str, inputs: dict[str, Any]) -> ProcessExample:
    return ProcessExample(title=title, description=description,
                          inputs=MappingProxyType(inputs))  # fmt: skip


SERIAL_INDICES_EXAMPLES = (
    _example(
        "UR5 (standard DH) in three configurations",
        "A typical working pose, a turned one, and the stretched-out zero configuration "
        "(a singularity: the inverse condition number is 0).",
        {"robot": UR5, "configurations": _UR5_POSES, "length_unit": "m"},
    ),
    _example(
        "UR5 from a URDF (the same numbers as its DH table)",
        "The same arm and configurations, given as a URDF chain from base_link to tool0.",
        {"robot": UR5_URDF, "configurations": _UR5_POSES, "length_unit": "m"},
    ),
    _example(
        "Puma 560 (standard DH) at its nominal and ready poses",
        "Corke's qn (a dexterous pose) and qr (arm straight up, singular).",
        {
            "robot": PUMA_560,
            "configurations": [[0, 45, -180, 0, 45, 0], [0, 90, -90, 0, 0, 0]],
            "length_unit": "m",
            "characteristic_length": 0.5,
        },
    ),
    _example(
        "Panda (modified DH) at its ready pose",
        "A seven-joint redundant arm: manipulability sqrt(det(J Jᵀ)).",
        {
            "robot": PANDA,
            "configurations": [[0, -17.2, 0, -126.1, 0, 108.9, 45]],
            "length_unit": "m",
        },
    ),
    _example(
        "Patel & Sobh's Example 1 arm (15, 14, 8) as a planar DH chain",
        "Task space (x, y, φ): a 3 × 3 Jacobian whose determinant is l1 l2 sin θ2.",
        {
            "robot": EXAMPLE_1_PLANAR,
            "configurations": [[0, 90, -90], [30, 60, 45]],
            "length_unit": "units",
        },
    ),
)
