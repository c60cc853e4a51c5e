"""How a design study's column is named for people: its symbol as plain text (or its
path) with its unit, for the table's headers and the scatter's axes."""

from __future__ import annotations

from worker.result_paths import plain_symbol
from worker.studies.design_table import DesignColumn

__all__ = ["column_label"]


def column_label(column: DesignColumn) -> str:
    """``min(d_z)``, ``sum(l_i) [cm]``, ``links[0] [cm]``: an objective that reduces a
    list names its reduction; no unit for a pure number."""
    name = plain_symbol(column.symbol) if column.symbol else column.path
    if column.symbol and "|" in column.path:
        name = f"{column.path.rsplit('|', 1)[1]}({name})"
    return name if column.unit in ("", "-") else f"{name} [{column.unit}]"
