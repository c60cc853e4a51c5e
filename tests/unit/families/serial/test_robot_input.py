"""Every bad arm is a 422 naming its field (``robot.dh[3].type``, ``robot.urdf`` with the
joint's name in the message); URDF defaults are honoured."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from worker.errors import InvalidInputs
from worker.families.serial.arms import UR5, UR5_URDF
from worker.registry import default_registry
from worker.submission import validate_inputs

PROCESS = default_registry().get("serial-indices")


def problems(robot: dict[str, Any], configurations: list[list[float]] | None = None) -> list[Any]:
    assert PROCESS is not None
    body = {"robot": robot, "configurations": configurations or [[0.0] * 6]}
    with pytest.raises(InvalidInputs) as caught:
        validate_inputs(PROCESS, body)
    return [(e["field"], e["message"]) for e in caught.value.errors]


def urdf(joints: str, links: str = "abc") -> str:
    return "<robot name='r'>" + "".join(f"<link name='{k}'/>" for k in links) + joints + "</robot>"


def joint(name: str, kind: str, parent: str, child: str, extra: str = "") -> str:
    return (f"<joint name='{name}' type='{kind}'><parent link='{parent}'/>"
            f"<child link='{child}'/>{extra}</joint>")  # fmt: skip


def test_a_bad_dh_row_is_named_by_its_place() -> None:
    rows = [dict(r) for r in UR5["dh"]]
    rows[3] = {**rows[3], "type": "spherical"}
    [(field, message)] = problems({"dh": rows})
    assert field == "inputs.robot.dh[3].type"
    assert "revolute" in message


def test_a_prismatic_joint_needs_limits_and_a_configuration_one_value_a_joint() -> None:
    rows = [{"a": 1.0}, {"a": 1.0, "type": "prismatic"}]
    [(field, message)] = problems({"dh": rows}, [[0.0, 0.0]])
    assert field == "inputs.robot.dh[1].limits" and "prismatic" in message
    [(field, message)] = problems(UR5, [[0.0] * 6, [0.0] * 5])
    assert field == "inputs.configurations[1]" and "6 movable joints" in message


@pytest.mark.parametrize(
    ("document", "words"),
    [
        (
            urdf(joint("float", "floating", "a", "b") + joint("j", "revolute", "b", "c")),
            ["'float'", "floating"],
        ),
        (
            urdf(joint("slide", "planar", "a", "b") + joint("j", "revolute", "b", "c")),
            ["'slide'", "planar"],
        ),
        (
            urdf(
                joint("j1", "revolute", "a", "b")
                + joint("j2", "revolute", "b", "c", "<mimic joint='j1'/>")
            ),
            ["'j2'", "mimic"],
        ),
        ("<robot xmlns:xacro='http://www.ros.org/wiki/xacro' name='r'/>", ["xacro"]),
        ("<!DOCTYPE r [<!ENTITY x SYSTEM 'file:///etc/passwd'>]><robot name='&x;'/>", ["DTD"]),
        ("not xml at all", ["not a URDF"]),
    ],
)
def test_a_bad_urdf_names_the_joint(document: str, words: list[str]) -> None:
    [(field, message)] = problems({"urdf": document, "base_link": "a", "tip_link": "c"})
    assert field == "inputs.robot.urdf"
    assert all(word in message for word in words), message


def test_an_oversized_urdf_and_a_missing_link_are_refused() -> None:
    [(field, _)] = problems({**UR5_URDF, "urdf": UR5_URDF["urdf"] + " " * 300_000})
    assert field == "inputs.robot.urdf"
    [(field, message)] = problems({**UR5_URDF, "tip_link": "flange"})
    assert field == "inputs.robot.urdf" and "'flange'" in message


def test_dh_and_urdf_together_are_refused() -> None:
    found = problems({**UR5, **UR5_URDF})
    assert found and found[0][0].startswith("inputs.robot")


def test_urdf_defaults_axis_x_limits_zero_continuous_full_turn() -> None:
    assert PROCESS is not None
    document = urdf(joint("j1", "revolute", "a", "b", "<origin xyz='0 0 1'/>")
                    + joint("j2", "continuous", "b", "c", "<origin xyz='1 0 0'/>"))  # fmt: skip
    robot = {"urdf": document, "base_link": "a", "tip_link": "c"}
    spec = validate_inputs(PROCESS, {"robot": robot, "configurations": [[0, 0]]})
    arm = spec.arm()  # type: ignore[attr-defined]
    assert np.array_equal(arm.axes, [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    assert arm.lower.tolist() == [0.0, -np.pi] and arm.upper.tolist() == [0.0, np.pi]
