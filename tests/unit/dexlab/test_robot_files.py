"""``dexlab.robot_from_file``: a DH table, a URDF or a JSON robot read into the
``robot`` input, checked by the service's own model of the arm."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from dexlab import robot_from_file
from worker.families.serial.arms import UR5, UR5_URDF
from worker.families.serial.robot_input import RobotSpec

UR5_CSV = """# UR5, standard DH (metres, degrees)
a,alpha_deg,d
0,90,0.089459
-0.425,0,0
-0.39225,0,0
0,90,0.10915
0,-90,0.09465
0,0,0.0823
"""


def fixed(robot: dict[str, object]) -> np.ndarray:
    return RobotSpec.model_validate(robot).arm("m").fixed


def test_a_csv_dh_table_is_sent_as_text_and_read_as_the_worked_example_arm(
    tmp_path: Path,
) -> None:
    path = tmp_path / "ur5.csv"
    path.write_text(UR5_CSV)
    robot = robot_from_file(path)
    assert robot == {"dh_table": UR5_CSV, "convention": "standard"}
    assert fixed(robot) == pytest.approx(fixed(UR5), abs=1e-15)
    modified = robot_from_file(path, convention="modified")
    assert modified["convention"] == "modified"


def test_a_urdf_needs_its_links_and_is_sent_as_it_is(tmp_path: Path) -> None:
    path = tmp_path / "ur5.urdf"
    path.write_text(UR5_URDF["urdf"])
    with pytest.raises(ValueError, match="base_link and tip_link"):
        robot_from_file(path)
    robot = robot_from_file(path, base_link="base_link", tip_link="tool0")
    assert robot == UR5_URDF


def test_json_is_the_robot_or_a_document_holding_it(tmp_path: Path) -> None:
    path = tmp_path / "arm.json"
    path.write_text(json.dumps({"robot": UR5, "configurations": [[0] * 6]}))
    assert robot_from_file(path) == UR5
    path.write_text("[1, 2]")
    with pytest.raises(ValueError, match="the robot object"):
        robot_from_file(path)
    path.write_text("{")
    with pytest.raises(ValueError, match="not JSON"):
        robot_from_file(path)


def test_an_unknown_suffix_asks_what_the_file_holds(tmp_path: Path) -> None:
    path = tmp_path / "arm.bin"
    path.write_text("x")
    with pytest.raises(ValueError, match="say what it holds"):
        robot_from_file(path)
    assert robot_from_file(path, kind="urdf", base_link="b", tip_link="t")["urdf"] == "x"
