"""A DH table as text (``robot.dh_table``): what a user copies from a paper or a
spreadsheet, read into the ``dh`` rows of the ``robot`` input.

A header row names the columns, then one row per joint, separated by commas, tabs or
spaces; lines starting with ``#`` are comments.  Columns: ``a``, ``alpha_deg`` and ``d``
(required), ``theta_deg`` (0 when absent), ``type`` (``revolute`` when absent), and the
limits as ``lower`` and ``upper`` (degrees for a revolute joint, length_unit for a
prismatic one; both or neither; an empty pair: the default limits).  Problems are
``ValueError`` naming the row and column; the rows are then checked as any ``dh`` rows.
"""

from __future__ import annotations

import csv
import io
from typing import Any

__all__ = ["DH_COLUMNS", "MAX_DH_TABLE_CHARS", "dh_rows"]

#: The columns a DH table may have.
DH_COLUMNS = ("a", "alpha_deg", "d", "theta_deg", "type", "lower", "upper")
#: The longest DH table accepted (characters).
MAX_DH_TABLE_CHARS = 16_384
_NUMBERS = ("a", "alpha_deg", "d", "theta_deg")
_REQUIRED = ("a", "alpha_deg", "d")


def _cells(text: str) -> list[tuple[int, list[str]]]:
    """(line number, cells) of each row that is not blank or a comment."""
    lines = [(n, line) for n, line in enumerate(text.splitlines(), start=1)
             if line.strip() and not line.lstrip().startswith("#")]  # fmt: skip
    if not lines:
        return []
    first = lines[0][1]
    if "," in first or "\t" in first:
        delimiter = "," if "," in first else "\t"
        parsed = csv.reader(io.StringIO("\n".join(line for _, line in lines)), delimiter=delimiter)
        return [
            (n, [cell.strip() for cell in row]) for (n, _), row in zip(lines, parsed, strict=True)
        ]
    return [(n, line.split()) for n, line in lines]


def _number(value: str, column: str, line: int) -> float:
    try:
        number = float(value)
    except ValueError:
        raise ValueError(f"line {line}, column {column}: {value!r} is not a number") from None
    if number != number or number in (float("inf"), float("-inf")):
        raise ValueError(f"line {line}, column {column}: {value!r} is not a finite number")
    return number


def _header(cells: list[str]) -> list[str]:
    names = [name.lower() for name in cells]
    unknown = [name for name in names if name not in DH_COLUMNS]
    if unknown:
        raise ValueError(f"unknown column(s) {', '.join(unknown)} in the header; the "
                         f"columns are {', '.join(DH_COLUMNS)}")  # fmt: skip
    if len(set(names)) != len(names):
        raise ValueError("a column is named twice in the header")
    missing = [name for name in _REQUIRED if name not in names]
    if missing:
        raise ValueError(f"the header lacks the column(s) {', '.join(missing)} (a header row "
                         "first, e.g. 'a alpha_deg d theta_deg type lower upper')")  # fmt: skip
    if ("lower" in names) != ("upper" in names):
        raise ValueError("give both limit columns, lower and upper, or neither")
    return names


def dh_rows(text: str) -> list[dict[str, Any]]:
    """The ``dh`` rows of a DH table's text (see the module doc)."""
    if len(text) > MAX_DH_TABLE_CHARS:
        raise ValueError(f"the table is longer than {MAX_DH_TABLE_CHARS:,} characters")
    rows = _cells(text)
    if not rows:
        raise ValueError("the table is empty: a header row naming the columns, then one "
                         "row per joint")  # fmt: skip
    (_, header), *joints = rows
    names = _header(header)
    if not joints:
        raise ValueError("the table has a header but no joint")
    out: list[dict[str, Any]] = []
    for line, cells in joints:
        if len(cells) != len(names):
            raise ValueError(f"line {line} has {len(cells)} cells; the header names {len(names)}")
        values = dict(zip(names, cells, strict=True))
        joint: dict[str, Any] = {key: _number(values[key], key, line)
                                 for key in _NUMBERS if key in values}  # fmt: skip
        if "type" in values:
            joint["type"] = values["type"].lower()
        if "lower" in values and (values["lower"] or values["upper"]):
            joint["limits"] = [_number(values[k], k, line) for k in ("lower", "upper")]
        out.append(joint)
    return out
