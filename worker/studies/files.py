"""A study's data files: ``designs.csv`` (one row per design) and ``designs.npz``.

Column and array names carry units (:mod:`worker.common.data_export`): a varied input
takes its unit from the process's input schema (a length in the fixed ``length_unit``,
``*_deg`` in degrees, otherwise a pure number); an objective takes the unit the process
declares for its result path (:attr:`ProcessDefinition.result_paths`; a reduction keeps
the unit: the sum of lengths is a length), ``length`` in the fixed ``length_unit``.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.common.data_export import DIMENSIONLESS, column, columns_csv, job_metadata, npz_artifact
from worker.contract import Artifact
from worker.processes import ProcessDefinition, ResultPathInfo
from worker.result_paths import ResultPathTable, unit_text
from worker.studies.assembly import StudyTable
from worker.studies.paths import parse_input_path, parse_result_path
from worker.studies.rows import REASON_CODES
from worker.studies.spec import StudySpec

__all__ = [
    "AS_REPORTED",
    "column_names",
    "designs_csv",
    "designs_npz",
    "objective_entry",
    "objective_unit",
    "parameter_unit",
]

#: The unit written for an objective the process does not declare (only a study
#: accepted before its path was declared: submission refuses such objectives).
AS_REPORTED = "as reported"


def _resolve(node: Mapping[str, Any], defs: Mapping[str, Any]) -> Mapping[str, Any]:
    while True:
        if "$ref" in node:
            node = defs.get(str(node["$ref"]).rsplit("/", 1)[-1], {})
        elif "anyOf" in node or "oneOf" in node:
            options = [
                o for o in node.get("anyOf", node.get("oneOf", [])) if o.get("type") != "null"
            ]
            hint = {k: v for k, v in node.items() if k.startswith("x-")}
            node = {**(options[0] if options else {}), **hint}
        else:
            return node


def parameter_unit(process: ProcessDefinition, name: str, fixed: Mapping[str, Any]) -> str:
    """The unit of a varied input, from the process's published input schema."""
    schema = process.inputs_schema
    defs = schema.get("$defs", {})
    node: Mapping[str, Any] = schema
    hint = None
    for step in parse_input_path(name):
        node = _resolve(node, defs)
        if isinstance(step, str):
            node = node.get("properties", {}).get(step, {})
        else:
            prefix = node.get("prefixItems")
            node = prefix[step] if prefix and step < len(prefix) else node.get("items", {})
        node = _resolve(node, defs)
        hint = node.get("x-unit", hint)
    last = next((s for s in reversed(parse_input_path(name)) if isinstance(s, str)), "")
    if last.endswith("_deg"):
        return "deg"
    if hint == "length":
        return str(fixed.get("length_unit", "units"))
    return DIMENSIONLESS


def objective_entry(process: ProcessDefinition, name: str) -> ResultPathInfo | None:
    """The process's declaration of the numbers an objective reads: ``chains[3].Q`` is
    ``chains[].Q``; ``links|sum`` reduces ``links[]``."""
    path = parse_result_path(name)
    table = ResultPathTable(process.result_paths)
    found = table.find(path.steps)
    if found is None and path.reduction is not None:  # a reduction flattens a last list
        found = table.find((*path.steps, None))
    return found


def objective_unit(process: ProcessDefinition, name: str, fixed: Mapping[str, Any]) -> str:
    """The unit of an objective: its declaration's, a length in the fixed ``length_unit``
    (min, max, mean and sum of values keep their unit)."""
    entry = objective_entry(process, name)
    if entry is None:
        return AS_REPORTED
    return unit_text(entry.unit, str(fixed.get("length_unit", "units")))


def _quantity(name: str) -> str:
    text = re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_")
    return text if text[:1].isalpha() else f"v_{text}"


def column_names(spec: StudySpec, process: ProcessDefinition) -> tuple[list[str], list[str]]:
    """CSV column names of the parameters and of the objectives (unique)."""
    used: set[str] = {"index", "feasible"}
    names: list[list[str]] = [[], []]
    pairs = [
        (0, name, parameter_unit(process, name, spec.fixed)) for name in spec.designs.names
    ] + [(1, name, objective_unit(process, name, spec.fixed)) for name in spec.objectives]
    for group, name, unit in pairs:
        quantity = base = _quantity(name)
        n = 2
        while quantity in used:
            quantity, n = f"{base}_{n}", n + 1
        used.add(quantity)
        names[group].append(column(quantity, unit))
    return names[0], names[1]


def designs_csv(spec: StudySpec, process: ProcessDefinition, table: StudyTable) -> Artifact:
    parameter_columns, objective_columns = column_names(spec, process)
    columns: dict[str, Any] = {column("index", DIMENSIONLESS): table.index}
    for j, name in enumerate(parameter_columns):
        columns[name] = table.parameters[:, j]
    for j, name in enumerate(objective_columns):
        columns[name] = table.objectives[:, j]
    columns[column("feasible", DIMENSIONLESS)] = table.feasible.astype(np.int8)
    columns[column("reason_code", DIMENSIONLESS)] = table.codes
    return columns_csv("designs.csv", columns, "Every design: parameters and objectives (CSV)")


def designs_npz(
    spec: StudySpec, process: ProcessDefinition, table: StudyTable, front: NDArray[np.intp]
) -> Artifact:
    """Every design's arrays: reason codes (``reason_codes`` names them) and the fields
    refusals name (an index into ``reason_fields``; 0 is ``""``: none), never a message
    per design."""
    units = [parameter_unit(process, name, spec.fixed) for name in spec.designs.names]
    entries = [objective_entry(process, name) for name in spec.objectives]
    arrays = {
        "index": table.index,
        "parameters": table.parameters,
        "objectives": table.objectives,
        "feasible": table.feasible,
        "reason_code": table.codes,
        "reason_codes": np.array(REASON_CODES, dtype=str),
        "reason_field": table.fields,
        "reason_fields": np.array(table.field_names, dtype=str),
        "pareto": table.index[front],
        "parameter_names": np.array(spec.designs.names, dtype=str),
        "parameter_units": np.array(units, dtype=str),
        "objective_names": np.array(list(spec.objectives), dtype=str),
        "objective_goals": np.array(list(spec.objectives.values()), dtype=str),
        "objective_units": np.array(
            [objective_unit(process, name, spec.fixed) for name in spec.objectives], dtype=str
        ),
        "objective_symbols": np.array([e.symbol if e else "" for e in entries], dtype=str),
    }
    return npz_artifact(
        "designs.npz", arrays, "Every design (NumPy arrays)",
        units={"index": DIMENSIONLESS, "parameters": "parameter_units",
               "objectives": "objective_units", "objective_units": DIMENSIONLESS,
               "objective_symbols": DIMENSIONLESS,
               "feasible": DIMENSIONLESS, "reason_code": DIMENSIONLESS,
               "reason_codes": DIMENSIONLESS, "reason_field": DIMENSIONLESS,
               "reason_fields": DIMENSIONLESS, "pareto": DIMENSIONLESS,
               "parameter_names": DIMENSIONLESS, "parameter_units": DIMENSIONLESS,
               "objective_names": DIMENSIONLESS, "objective_goals": DIMENSIONLESS},
        axes={"index": ("design",), "parameters": ("design", "parameter"),
              "objectives": ("design", "objective"), "feasible": ("design",),
              "reason_code": ("design",), "reason_field": ("design",),
              "pareto": ("pareto_design",)},
        metadata=job_metadata("design-study", spec.model_dump(mode="json")),
    )  # fmt: skip
