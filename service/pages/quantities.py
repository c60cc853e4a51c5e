"""What the numbers of a job's result are, for its page: the process's declarations
(``result_paths``) with the job's length unit, as :class:`Quantity` values the result
view shows beside keys and values (plain-text symbols, units such as ``cm²``)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from service.pages.result_view import Quantities, Quantity, Steps
from worker.processes import ProcessDefinition
from worker.result_paths import ResultPathTable, display_unit, plain_symbol

__all__ = ["job_quantities", "length_unit_of"]


def length_unit_of(result: Mapping[str, Any], inputs: Mapping[str, Any]) -> str:
    """The unit ``length`` stands for in a job: its result's ``length_unit``, else its
    inputs', else ``units`` (every process's default)."""
    for source in (result, inputs):
        unit = source.get("length_unit")
        if isinstance(unit, str) and unit:
            return unit
    return "units"


def job_quantities(
    definition: ProcessDefinition | None, result: Mapping[str, Any], inputs: Mapping[str, Any]
) -> Quantities:
    """The quantity at each place of this job's result, from its process's declarations."""
    table = ResultPathTable(definition.result_paths if definition is not None else ())
    length_unit = length_unit_of(result, inputs)

    def quantity(steps: Steps) -> Quantity | None:
        entry = table.find(steps)
        if entry is None:
            return None
        symbol = plain_symbol(entry.symbol) if entry.symbol else ""
        return Quantity(symbol, display_unit(entry.unit, length_unit), entry.description)

    return quantity
