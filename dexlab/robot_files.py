"""Your own arm as the ``robot`` input of the serial processes, read from a file.

::

    from dexlab import Client, robot_from_file

    robot = robot_from_file("ur5.urdf", base_link="base_link", tip_link="tool0")
    with Client() as client:
        job = client.run("serial-indices", {"robot": robot, "configurations": [[0] * 6]})

Three kinds of file, told by their suffix (or by ``kind``):

- a URDF (``.urdf``, ``.xml``): sent as it is, with ``base_link`` and ``tip_link``
  (both required); the service parses it (no file or network access there either);
- a DH table (``.csv``, ``.tsv``, ``.txt``, ``.dh``): a header row naming the columns,
  then one row per joint, separated by commas, tabs or spaces.  Columns: ``a``,
  ``alpha_deg``, ``d``, ``theta_deg`` (0 when absent), ``type`` (``revolute`` when
  absent), and the limits as ``lower`` and ``upper`` (degrees for a revolute joint,
  lengths for a prismatic one); lines starting with ``#`` are comments;
- JSON (``.json``): the ``robot`` object itself (or a document with a ``robot`` member,
  such as a job's inputs).

Nothing is validated here beyond the file's layout: the service checks the arm and
names the field of any problem (``robot.dh[3].type``).
"""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path
from typing import Any, Literal

__all__ = ["DH_COLUMNS", "robot_from_dh_table", "robot_from_file"]

#: The DH table's columns (``lower`` and ``upper`` are the joint's limits).
DH_COLUMNS = ("a", "alpha_deg", "d", "theta_deg", "type", "lower", "upper")
_NUMBERS = ("a", "alpha_deg", "d", "theta_deg")
_SUFFIXES = {
    ".urdf": "urdf", ".xml": "urdf", ".csv": "dh", ".tsv": "dh", ".txt": "dh", ".dh": "dh",
    ".json": "json",
}  # fmt: skip
Kind = Literal["urdf", "dh", "json"]


def _rows(text: str) -> list[list[str]]:
    lines = [
        line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#")
    ]
    if not lines:
        raise ValueError("the DH table is empty: a header row, then one row per joint")
    if "," in lines[0] or "\t" in lines[0]:
        delimiter = "," if "," in lines[0] else "\t"
        return [
            [cell.strip() for cell in row]
            for row in csv.reader(io.StringIO("\n".join(lines)), delimiter=delimiter)
        ]
    return [line.split() for line in lines]


def _number(value: str, column: str, row: int) -> float:
    try:
        return float(value)
    except ValueError:
        raise ValueError(f"row {row}, column {column!r}: {value!r} is not a number") from None


def robot_from_dh_table(
    text: str, convention: Literal["standard", "modified"] = "standard"
) -> dict[str, Any]:
    """The ``robot`` input of a DH table's text (see the module doc)."""
    header, *rows = _rows(text)
    names = [name.strip().lower() for name in header]
    unknown = sorted(set(names) - set(DH_COLUMNS))
    if unknown:
        raise ValueError(
            f"unknown DH column(s) {', '.join(unknown)}: the columns are {', '.join(DH_COLUMNS)}"
        )
    if "a" not in names or "d" not in names or "alpha_deg" not in names:
        raise ValueError("the DH table needs at least the columns a, alpha_deg and d")
    if ("lower" in names) != ("upper" in names):
        raise ValueError("give both limit columns, lower and upper, or neither")
    if not rows:
        raise ValueError("the DH table has a header but no joint")
    joints: list[dict[str, Any]] = []
    for number, cells in enumerate(rows, start=1):
        if len(cells) != len(names):
            raise ValueError(f"row {number} has {len(cells)} cells; the header names {len(names)}")
        values = dict(zip(names, cells, strict=True))
        joint: dict[str, Any] = {
            key: _number(values[key], key, number) for key in _NUMBERS if key in values
        }
        if "type" in values:
            joint["type"] = values["type"].lower()
        if "lower" in values and (values["lower"] or values["upper"]):
            joint["limits"] = [_number(values[k], k, number) for k in ("lower", "upper")]
        joints.append(joint)
    return {"dh": joints, "convention": convention}


def robot_from_file(
    path: str | Path,
    *,
    base_link: str | None = None,
    tip_link: str | None = None,
    convention: Literal["standard", "modified"] = "standard",
    kind: Kind | None = None,
) -> dict[str, Any]:
    """The ``robot`` input of a URDF, DH-table or JSON file (see the module doc);
    ``ValueError`` says what is wrong with the file's layout."""
    file = Path(path)
    chosen = kind or _SUFFIXES.get(file.suffix.lower())
    if chosen is None:
        raise ValueError(
            f"{file.name}: say what it holds (a URDF .urdf/.xml, a DH table "
            ".csv/.tsv/.txt/.dh, or JSON .json)"
        )
    text = file.read_text(encoding="utf-8")
    if chosen == "urdf":
        if base_link is None or tip_link is None:
            raise ValueError("a URDF arm needs its base_link and tip_link")
        return {"urdf": text, "base_link": base_link, "tip_link": tip_link}
    if chosen == "dh":
        return robot_from_dh_table(text, convention)
    document = json.loads(text)
    if isinstance(document, dict) and isinstance(document.get("robot"), dict):
        document = document["robot"]
    if not isinstance(document, dict):
        raise ValueError(f"{file.name}: the JSON must be the robot object")
    return document
