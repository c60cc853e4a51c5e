"""``robot.dh_table``: a DH table as text, read into the ``dh`` rows (a 422 naming
``robot.dh_table`` and the line when it cannot be read)."""

from __future__ import annotations

import pytest
from pydantic import ValidationError

from worker.families.serial.arms import PUMA_560
from worker.families.serial.dh_table import dh_rows
from worker.families.serial.robot_input import RobotSpec


def puma_table(separator: str) -> str:
    rows = PUMA_560["dh"]
    assert isinstance(rows, list)
    header = ["a", "alpha_deg", "d", "theta_deg", "type", "lower", "upper"]
    lines = [separator.join(header)]
    for r in rows:
        cells = [r["a"], r["alpha_deg"], r["d"], 0, "Revolute", *r["limits"]]
        lines.append(separator.join(str(c) for c in cells))
    return "# Puma 560\n\n" + "\n".join(lines)


@pytest.mark.parametrize("separator", [",", "\t", "  "])
def test_a_table_is_the_rows_it_spells(separator: str) -> None:
    spec = RobotSpec.model_validate({"dh_table": puma_table(separator)})
    reference = RobotSpec.model_validate(PUMA_560)
    assert spec.dh == reference.dh
    assert "dh_table" not in spec.model_dump(exclude_none=True)
    assert spec.arm("m").fixed == pytest.approx(reference.arm("m").fixed, abs=1e-15)


def test_optional_columns_default_and_empty_limits_are_the_defaults() -> None:
    rows = dh_rows("a, alpha_deg, d, lower, upper\n1, 0, 0, , \n2, 90, 0.5, -90, 90\n")
    assert rows == [{"a": 1.0, "alpha_deg": 0.0, "d": 0.0},
                    {"a": 2.0, "alpha_deg": 90.0, "d": 0.5, "limits": [-90.0, 90.0]}]  # fmt: skip


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "empty"),
        ("# only a comment\n", "empty"),
        ("a,alpha_deg,d\n", "no joint"),
        ("a,alpha,d\n1,2,3\n", "unknown column"),
        ("a,a,alpha_deg,d\n1,1,2,3\n", "named twice"),
        ("a,alpha_deg,d\n1,2\n", "line 2 has 2 cells"),
        ("a,alpha_deg,d\n\n1,x,3\n", "line 3, column alpha_deg: 'x' is not a number"),
        ("a,alpha_deg,d\n1,nan,3\n", "not a finite number"),
        ("a,alpha_deg,d,lower\n1,2,3,4\n", "lower and upper"),
        ("a d\n1 2\n", "lacks the column"),
        ("a,alpha_deg,d\n" + "1,2,3\n" * 5000, "longer than"),
    ],
)
def test_a_bad_table_says_what_is_wrong(text: str, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        dh_rows(text)


def test_a_bad_table_is_an_error_at_robot_dh_table() -> None:
    with pytest.raises(ValidationError) as caught:
        RobotSpec.model_validate({"dh_table": "a,alpha_deg,d\n1,x,3\n"})
    (error,) = caught.value.errors()
    assert error["loc"] == ("dh_table",) and "line 2" in error["msg"]
    with pytest.raises(ValidationError) as both:
        RobotSpec.model_validate({"dh_table": "a,alpha_deg,d\n1,0,0\n", "dh": [{"a": 1}]})
    assert both.value.errors()[0]["loc"] == ("dh_table",)
    with pytest.raises(ValidationError) as typed:
        RobotSpec.model_validate({"dh_table": "a,alpha_deg,d,type\n1,0,0,screw\n"})
    assert typed.value.errors()[0]["loc"][:3] == ("dh", 0, "type")
