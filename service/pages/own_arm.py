"""The "Your own arm" form of a process with a ``robot`` input (the serial family).

A user pastes a DH table or a URDF into a text box instead of writing it as JSON; the
page action (:mod:`service.pages.actions`) puts it into the inputs as
``robot.dh_table`` (with the ``convention``) or ``robot.urdf`` (with ``base_link`` and
``tip_link``), and the process validates it like any submission: a bad table or URDF
comes back on this form with its problem, the user's text kept.  Nothing is parsed here.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from service.pages.json_text import compact_json
from worker.processes import ProcessDefinition

__all__ = ["OWN_ARM_FIELDS", "own_arm_form", "robot_from_form"]

#: The form's fields beside ``inputs`` (the other inputs, as JSON).
OWN_ARM_FIELDS = ("robot_kind", "robot_text", "convention", "base_link", "tip_link")
_COLUMNS = ("a", "alpha_deg", "d", "theta_deg", "type", "lower", "upper")


def _table(rows: list[Mapping[str, Any]]) -> str:
    """A DH table's text of ``dh`` rows (the form's starting point); the limit columns
    only when some row has limits (a revolute joint without them: ±180°)."""
    limited = any(row.get("limits") for row in rows)
    columns = _COLUMNS if limited else _COLUMNS[:5]
    lines = ["  ".join(columns)]
    for row in rows:
        cells: list[Any] = [row.get("a", 0.0), row.get("alpha_deg", 0.0), row.get("d", 0.0),
                            row.get("theta_deg", 0.0), row.get("type", "revolute")]  # fmt: skip
        if limited:
            cells += list(row.get("limits") or (-180.0, 180.0))
        lines.append("  ".join(f"{c:g}" if isinstance(c, float | int) else str(c) for c in cells))
    return "\n".join(lines)


def _starting_example(definition: ProcessDefinition) -> Mapping[str, Any] | None:
    """The inputs of the first worked example whose arm is a DH table."""
    for example in definition.examples:
        robot = example.inputs.get("robot")
        if isinstance(robot, Mapping) and robot.get("dh"):
            return example.inputs
    return None


def own_arm_form(
    definition: ProcessDefinition,
    posted: Mapping[str, str] | None = None,
    problem: dict[str, Any] | None = None,
) -> dict[str, Any] | None:
    """The form's values: the first DH example's table and other inputs, or what the
    user ``posted`` with its ``problem``; None for a process without a ``robot`` input."""
    if "robot" not in definition.inputs_schema.get("properties", {}):
        return None
    if posted is not None:
        values = {name: posted.get(name, "") for name in (*OWN_ARM_FIELDS, "inputs")}
        return {**values, "problem": problem}
    example = _starting_example(definition)
    robot: Mapping[str, Any] = (example or {}).get("robot", {})
    others = {k: v for k, v in (example or {}).items() if k != "robot"}
    return {
        "robot_kind": "dh",
        "robot_text": _table(list(robot.get("dh", []))),
        "convention": robot.get("convention", "standard"),
        "base_link": "",
        "tip_link": "",
        "inputs": compact_json(others),
        "problem": None,
    }


def robot_from_form(form: Mapping[str, str]) -> dict[str, Any]:
    """The ``robot`` input the form's fields spell (validated by the process)."""
    text = form.get("robot_text", "")
    if form.get("robot_kind") == "urdf":
        return {"urdf": text, "base_link": form.get("base_link", "").strip() or None,
                "tip_link": form.get("tip_link", "").strip() or None}  # fmt: skip
    convention = form.get("convention", "standard")
    return {"dh_table": text, "convention": convention}
