"""Every process declares every number it reports (``result_paths``): each numeric
place of the result of every worked example (list indices read as ``[]``) has a
declaration, and every declaration is reported by some worked example, or by one of
the extra runs below, which reach what no worked example does (a declaration only
they reach says when, in ``optional``).  Units come from the closed set, symbols are
mathtext that matplotlib draws and that reads as plain text.

A field added to a result fails here, naming its path, until it is declared in the
family's ``result_paths.py``; a case no example reaches is one more entry of
:data:`EXTRA_RUNS`.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any

import pytest
from matplotlib.mathtext import MathTextParser

from tests.unit.families.conftest import RecordingContext
from worker.processes import ProcessDefinition
from worker.registry import default_registry
from worker.result_paths import (
    RESULT_UNITS,
    ResultPathTable,
    declared_steps,
    plain_symbol,
)

DEFINITIONS = list(default_registry())

#: Small inputs reaching result paths no worked example reports, per process.
EXTRA_RUNS: dict[str, list[dict[str, Any]]] = {
    "serial-workspace-map": [
        {"robot": {"dh": [{"a": 1.0}, {"a": 1.0}]}, "samples": 2000, "voxel_size": 0.5,
         "orientation_bins": 8, "characteristic_length": 2.0, "length_unit": "m"},
    ],
    "planar3r-synthesis": [
        {"task_points": [[10, 0], [15, 5]], "l3": 5, "grid": {"points_per_axis": 11},
         "joint_limits_deg": [[-150, 150], [-150, 150], [-175, 175]],
         "method": "orientation-sampling", "orientation_step_deg": 5},
    ],
    "planar2dof-conditioning-map": [
        {"actuation": "telescopic-leg", "l1": 1, "e": 0.5, "grid": {"points_per_axis": 11},
         "points": [[0, -0.8]]},
    ],
    "spm-conditioning-map": [
        {"alpha1_deg": 60, "alpha2_deg": 60, "beta_deg": 90,
         "workspace": {"tilt_max_deg": 60, "torsion_deg": [0, 360],
                       "samples": {"azimuth": 4, "tilt": 2, "torsion": 2}},
         "orientations": [[0, 10, 0]], "map_grid": {"azimuth": 5, "tilt": 3}},
    ],
    "spm-design-space": [
        {"workspace": {"tilt_max_deg": 45, "torsion_deg": [-180, 180]},
         "beta_deg": [30, 80], "gamma_deg": 60},
    ],
    "spm-optimisation": [
        {"workspace": {"tilt_max_deg": 45, "torsion_deg": [-180, 180]},
         "free": ["alpha2", "beta", "gamma"], "alpha1_deg": 60, "starts": 1,
         "max_evaluations_per_start": 10, "singularity_tolerance": 0.01},
        {"workspace": {"tilt_max_deg": 45, "torsion_deg": [-180, 180]},
         "free": ["alpha1", "beta"], "alpha2_deg": 90, "starts": 1,
         "max_evaluations_per_start": 10},
    ],
}  # fmt: skip


def numeric_places(node: Any, steps: tuple[str | None, ...] = ()) -> Iterator[tuple[Any, ...]]:
    """The steps of every number in a result: keys, and None for a list element."""
    if isinstance(node, Mapping):
        for key, value in node.items():
            yield from numeric_places(value, (*steps, str(key)))
    elif isinstance(node, list):
        for value in node:
            yield from numeric_places(value, (*steps, None))
    elif isinstance(node, int | float) and not isinstance(node, bool):
        yield steps


def shown(steps: tuple[str | None, ...]) -> str:
    return ".".join(s if s is not None else "[]" for s in steps).replace(".[]", "[]")


#: Inputs that make a run cheaper without changing which numbers its result reports
#: (the search's length, not its shape), per process.
CHEAPER: dict[str, dict[str, Any]] = {
    "planar3r-design": {"starts": 2, "max_generations": 3},
}


def run(definition: ProcessDefinition, inputs: Mapping[str, Any]) -> dict[str, Any]:
    raw = {**inputs, **CHEAPER.get(definition.id, {}), "plots": False}
    spec = definition.inputs_model.model_validate(raw)
    return dict(definition.run(spec, RecordingContext()).result)


@pytest.mark.parametrize("definition", DEFINITIONS, ids=lambda d: d.id)
def test_declarations_are_well_formed(definition: ProcessDefinition) -> None:
    assert definition.result_paths, f"{definition.id} declares no result paths"
    paths = [entry.path for entry in definition.result_paths]
    assert len(set(paths)) == len(paths), sorted(p for p in paths if paths.count(p) > 1)
    parser = MathTextParser("path")
    for entry in definition.result_paths:
        declared_steps(entry.path)  # raises for an index, a reduction or a stray character
        assert entry.unit in RESULT_UNITS, (entry.path, entry.unit)
        assert entry.description.endswith("."), entry.path
        if entry.symbol:
            assert entry.symbol.startswith("$") and entry.symbol.endswith("$"), entry.symbol
            parser.parse(entry.symbol)  # matplotlib draws it
            text = plain_symbol(entry.symbol)
            assert text and not set(text) & set("\\{}$"), (entry.symbol, text)
    described = definition.describe()["result_paths"]
    covered = set(definition.study_kernel.covers) if definition.study_kernel else set()
    assert covered <= set(paths), sorted(covered - set(paths))  # a kernel covers declarations
    assert described == [
        {"path": e.path, "unit": e.unit, "symbol": e.symbol, "description": e.description,
         **({"kernel": True} if e.path in covered else {})}
        for e in definition.result_paths
    ]  # fmt: skip


@pytest.mark.slow
@pytest.mark.parametrize("definition", DEFINITIONS, ids=lambda d: d.id)
def test_every_number_reported_is_declared_and_every_declaration_is_reported(
    definition: ProcessDefinition,
) -> None:
    table = ResultPathTable(definition.result_paths)
    found_by: dict[str, str] = {}
    runs = [(f"example {n}", dict(e.inputs)) for n, e in enumerate(definition.examples)]
    runs += [(f"extra run {n}", i) for n, i in enumerate(EXTRA_RUNS.get(definition.id, []))]
    undeclared: set[str] = set()
    for name, inputs in runs:
        for steps in numeric_places(run(definition, inputs)):
            entry = table.find(steps)
            if entry is None:
                undeclared.add(shown(steps))
            else:
                found_by.setdefault(entry.path, name)
    assert not undeclared, f"{definition.id} reports undeclared numbers: {sorted(undeclared)}"
    unreported = [e.path for e in definition.result_paths if e.path not in found_by]
    assert not unreported, f"{definition.id}: no run reports {unreported}"
    only_extra = [
        e.path
        for e in definition.result_paths
        if found_by[e.path].startswith("extra") and not e.optional
    ]
    assert not only_extra, f"{definition.id}: say when these are reported (optional=...)"


def test_plain_symbols_read_as_text() -> None:
    assert plain_symbol(r"$\alpha_1$") == "α₁"
    assert plain_symbol("$d_z$") == "d_z"
    assert plain_symbol(r"$\beta_{\min}$") == "β_min"
    assert plain_symbol(r"$\mathrm{mean}(1/\kappa^2)$") == "mean(1/κ²)"
    assert plain_symbol(r"$\min\,|\det A|$") == "min |det A|"
    assert plain_symbol("$H'$") == "H′"
    with pytest.raises(ValueError, match="frac"):
        plain_symbol(r"$\frac{1}{2}$")
