"""Forward kinematics, Jacobians and manipulability of every worked-example arm, DH and
URDF, against the Robotics Toolbox for Python (the test reference only) to 1e-12."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
import roboticstoolbox as rtb
from spatialmath import SE3

from worker.families.serial.arms import EXAMPLE_1_PLANAR, PANDA, PUMA_560, UR5, UR5_URDF
from worker.families.serial.kinematics.chain import forward_kinematics, jacobian
from worker.families.serial.kinematics.indices import manipulability, task_jacobian
from worker.families.serial.robot_input import RobotSpec

TOLERANCE = 1e-12


def reference_robot(robot: dict[str, Any]) -> Any:
    """The same arm built in the Robotics Toolbox from its DH table."""
    modified = robot["convention"] == "modified"
    links = []
    for row in robot["dh"]:
        alpha = math.radians(row["alpha_deg"])
        offset = math.radians(row.get("theta_deg", 0.0))
        kind = rtb.RevoluteMDH if modified else rtb.RevoluteDH
        links.append(kind(a=row["a"], alpha=alpha, d=row["d"], offset=offset))
    tool = robot.get("tool")
    placement = SE3()
    if tool is not None:
        placement = SE3.Trans(*tool["xyz"]) * SE3.RPY(*tool["rpy_deg"], unit="deg", order="zyx")
    return rtb.DHRobot(links, tool=placement)


CASES = {"UR5": (UR5, UR5), "UR5 URDF": (UR5_URDF, UR5), "Puma 560": (PUMA_560, PUMA_560),
         "Panda": (PANDA, PANDA), "Example 1": (EXAMPLE_1_PLANAR, EXAMPLE_1_PLANAR)}  # fmt: skip


@pytest.mark.parametrize("name", list(CASES))
def test_every_worked_arm_agrees_with_the_robotics_toolbox(name: str) -> None:
    ours, theirs = CASES[name]
    arm = RobotSpec.model_validate(ours).arm("m")
    reference = reference_robot(theirs)
    q = np.random.default_rng(len(name)).uniform(-math.pi, math.pi, (25, arm.joints))
    tool, jac = forward_kinematics(arm, q), jacobian(arm, q)
    for k in range(q.shape[0]):
        assert np.abs(tool[k] - reference.fkine(q[k]).A).max() < TOLERANCE
        j0 = reference.jacob0(q[k])
        assert np.abs(jac[k] - j0).max() < TOLERANCE
        rows = task_jacobian(j0, arm.planar)
        expected = math.sqrt(max(np.linalg.det(rows @ rows.T), 0.0)) if rows.shape[0] <= \
            rows.shape[1] else math.sqrt(max(np.linalg.det(rows.T @ rows), 0.0))  # fmt: skip
        assert abs(manipulability(task_jacobian(jac[k], arm.planar)) - expected) < 1e-10


def test_a_prismatic_joint_and_a_base_agree_with_the_robotics_toolbox() -> None:
    robot = {
        "dh": [{"a": 0.3, "alpha_deg": 30.0, "d": 0.1, "theta_deg": 10.0},
               {"a": 0.2, "alpha_deg": -20.0, "d": 0.1, "theta_deg": 25.0, "type": "prismatic",
                "limits": [-1.0, 1.0]},
               {"a": 0.1, "alpha_deg": 60.0, "d": 0.05}],
        "convention": "standard",
        "base": {"xyz": [0.1, 0.2, 0.3], "rpy_deg": [10.0, 20.0, 30.0]},
    }  # fmt: skip
    arm = RobotSpec.model_validate(robot).arm("m")
    base = SE3.Trans(0.1, 0.2, 0.3) * SE3.RPY(10.0, 20.0, 30.0, unit="deg", order="zyx")
    reference = rtb.DHRobot(
        [rtb.RevoluteDH(a=0.3, alpha=math.radians(30), d=0.1, offset=math.radians(10)),
         rtb.PrismaticDH(a=0.2, alpha=math.radians(-20), theta=math.radians(25), offset=0.1),
         rtb.RevoluteDH(a=0.1, alpha=math.radians(60), d=0.05)],
        base=base,
    )  # fmt: skip
    q = np.random.default_rng(3).uniform(-1.0, 1.0, (25, 3))
    tool, jac = forward_kinematics(arm, q), jacobian(arm, q)
    for k in range(q.shape[0]):
        assert np.abs(tool[k] - reference.fkine(q[k]).A).max() < TOLERANCE
        assert np.abs(jac[k] - reference.jacob0(q[k])).max() < TOLERANCE


def test_the_urdf_and_the_dh_table_give_the_same_numbers() -> None:
    dh, urdf = (RobotSpec.model_validate(r).arm("m") for r in (UR5, UR5_URDF))
    q = np.random.default_rng(5).uniform(-math.pi, math.pi, (200, 6))
    assert np.abs(forward_kinematics(dh, q) - forward_kinematics(urdf, q)).max() < TOLERANCE
    assert np.abs(jacobian(dh, q) - jacobian(urdf, q)).max() < TOLERANCE
