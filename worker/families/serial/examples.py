"""Worked examples of the serial processes: published arms (:mod:`.arms`) in a few
configurations, ready to POST (docs/methods/serial.md)."""

from __future__ import annotations

from types import MappingProxyType
from typing import Any

from worker.families.serial.arms import EXAMPLE_1_PLANAR, PANDA, PUMA_560, UR5, UR5_URDF
from worker.processes import ProcessExample

__all__ = ["SERIAL_INDICES_EXAMPLES", "SERIAL_REACH_EXAMPLES"]

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

#: Three UR5 poses (the working and turned poses of the indices examples, and a third)
#: re-typed from their forward kinematics, one point without orientation and one a
#: metre beyond the arm's reach.
_UR5_TARGETS = [
    {"position": [-0.4869, -0.1091, 0.4322], "rpy_deg": [180, 0, 90],
     "tolerance": {"position": 1e-3, "orientation_deg": 0.1}},
    {"position": [-0.5395, -0.4375, 0.4767], "rpy_deg": [180, 0, 105],
     "tolerance": {"position": 1e-3, "orientation_deg": 0.1}},
    {"position": [-0.3651, 0.2107, 0.3576], "rpy_deg": [180, 0, 45],
     "tolerance": {"position": 1e-3, "orientation_deg": 0.1}},
    {"position": [0.3, 0.4, 0.2]},
    {"position": [2.0, 0.0, 0.5]},
]  # fmt: skip
#: Patel & Sobh's Example 1 task points A-E (re-typed), and one beyond reach (37).
_EXAMPLE_1_TARGETS = [{"position": list(p)} for p in
                      [(14, 14), (12, 8), (10, -3), (9, -7), (8, -8), (40, 0)]]  # fmt: skip

SERIAL_REACH_EXAMPLES = (
    _example(
        "UR5 (standard DH): five target poses",
        "Three oriented targets the arm reaches, a position-only one, and one a metre "
        "beyond its reach: reached_share 0.8.",
        {
            "robot": UR5,
            "targets": _UR5_TARGETS,
            "seeds": 8,
            "seed": 0,
            "length_unit": "m",
            "characteristic_length": 0.5,
        },
    ),
    _example(
        "Patel & Sobh's Example 1 arm: its task points, closed form",
        "The planar 3R arm (15, 14, 8) and the paper's task points A-E (all reached, as "
        "d_z > 0 there) plus a point beyond the reach 37.",
        {"robot": EXAMPLE_1_PLANAR, "targets": _EXAMPLE_1_TARGETS, "length_unit": "units"},
    ),
    _example(
        "Example 1 arm with joint limits: task points at a tool angle",
        "Each task point with the tool at phi = 120° and joint limits of ±120°: A-D are "
        "reachable within the limits, E is not (its feasible tool angles end at 119.6°).",
        {
            "robot": {
                **EXAMPLE_1_PLANAR,
                "dh": [{**row, "limits": [-120, 120]} for row in EXAMPLE_1_PLANAR["dh"]],
            },
            "targets": [{**t, "rpy_deg": [0, 0, 120]} for t in _EXAMPLE_1_TARGETS[:5]],
            "length_unit": "units",
        },
    ),
)
