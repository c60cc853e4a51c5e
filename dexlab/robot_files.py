"""Your own arm as the ``robot`` input of the serial processes, read from a file.

::

    from dexlab import Client, robot_from_file

    robot = robot_from_file("ur5.urdf", base_link="base_link", tip_link="tool0")
    with Client() as client:
        job = client.run("serial-indices", {"robot": robot, "configurations": [[0] * 6]})

Three kinds of file, told by their suffix (or by ``kind``):

- a URDF (``.urdf``, ``.xml``): sent as it is, with ``base_link`` and ``tip_link``
  (both required); the service parses it (no file or network access there either);
- a DH table (``.csv``, ``.tsv``, ``.txt``, ``.dh``): sent as the text of
  ``robot.dh_table`` with the ``convention``; the service reads it (a header row naming
  the columns ``a``, ``alpha_deg``, ``d`` and optionally ``theta_deg``, ``type``,
  ``lower``, ``upper``, then one row per joint, separated by commas, tabs or spaces;
  lines starting with ``#`` are comments) and names the line of any problem;
- JSON (``.json``): the ``robot`` object itself (or a document with a ``robot`` member,
  such as a job's inputs).

Nothing is parsed here beyond JSON: the service checks the arm and names the field of
any problem (``robot.dh[3].type``, ``robot.dh_table`` with the line).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any, Literal

__all__ = ["robot_from_file"]

_SUFFIXES = {
    ".urdf": "urdf", ".xml": "urdf", ".csv": "dh", ".tsv": "dh", ".txt": "dh", ".dh": "dh",
    ".json": "json",
}  # fmt: skip
Kind = Literal["urdf", "dh", "json"]


def robot_from_file(
    path: str | Path,
    *,
    base_link: str | None = None,
    tip_link: str | None = None,
    convention: Literal["standard", "modified"] = "standard",
    kind: Kind | None = None,
) -> dict[str, Any]:
    """The ``robot`` input of a URDF, DH-table or JSON file (see the module doc);
    ``ValueError`` says what is wrong with the file (the service checks the arm)."""
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
        return {"dh_table": text, "convention": convention}
    try:
        document = json.loads(text)
    except ValueError as exc:
        raise ValueError(f"{file.name}: not JSON ({exc})") from None
    if isinstance(document, dict) and isinstance(document.get("robot"), dict):
        document = document["robot"]
    if not isinstance(document, dict):
        raise ValueError(f"{file.name}: the JSON must be the robot object")
    return document
