"""Every figure of every worked example, and of a few random valid inputs per process,
passes the figure check (tests/figure_check.py): no overlapping or clipped text, colour
bars beside their axes, every axis labelled with its unit, mathtext for every symbol,
no unexplained constant field."""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from matplotlib.figure import Figure

from tests.figure_check import figure_defects
from tests.unit.families.conftest import RecordingContext
from tests.unit.families.test_data_files import SMALL
from worker.contract import Artifact
from worker.processes import ProcessDefinition
from worker.registry import default_registry, family_packages

FAMILIES = tuple(package.FAMILY.name for package in family_packages())
DEFINITIONS = list(default_registry())
EXAMPLES = [
    pytest.param(d, i, id=f"{d.id}[{i}]") for d in DEFINITIONS for i in range(len(d.examples))
]
#: Inputs beyond the worked examples (other options, other shapes), per process.
VARIANTS: dict[str, list[dict[str, Any]]] = {
    "planar3r-dexterity-map": [
        {"links": [5, 9, 2.5], "grid": {"points_per_axis": 61}, "length_unit": "cm",
         "task_points": [[3, 4], [-8, 1]]},
        {"links": [1, 1, 1], "joint_limits_deg": [[-90, 90], [-120, 120], [-170, 170]],
         "grid": {"points_per_axis": 41}, "orientation_step_deg": 5},
    ],
    "planar3r-design": [
        {"task_points": [[3, 4], [-8, 1]], "total_length_max": 20, "objective": "min_length",
         "dz_target": 0.9, "max_generations": 10, "grid": {"points_per_axis": 41},
         "trajectory": {"points": [[3, 4], [6, 0]], "samples": 10}, "length_unit": "mm"},
        {"task_points": [[3, 4], [-8, 1]], "total_length_max": 20, "base_box": [-3, 3, -2, 2],
         "joint_limits_deg": [[-90, 90], [-120, 120], [-170, 170]], "max_generations": 10,
         "grid": {"points_per_axis": 41}},
    ],
    "planar2dof-conditioning-map": [
        {"actuation": "linear-drive", "l2": 2.0, "grid": {"points_per_axis": 61},
         "inverse_condition_limit": 0.4},
        {"l1": 2, "l2": 1, "e": 0.5, "working_mode": [1, 1], "grid": {"points_per_axis": 61}},
    ],
    "fourbar-grashof": [{"lengths": [4, 4, 4, 4], "ground": 0}],
    "design-study": [  # three varied inputs: small multiples, 7 of 9 slices shown as 6
        {"process": "chain-parallelism",
         "fixed": {"chains": [{"name": "A", "lengths": [15, 15, 15, 15]},
                              {"name": "B", "lengths": [18, 15, 10, 17]}]},
         "vary": {"chains[1].lengths[0]": [10, 20, 6], "chains[1].lengths[1]": [10, 20, 6],
                  "chains[1].lengths[2]": [6, 14, 9]},
         "objectives": {"chains[1].Q_normalized": "min", "chains[1].P_normalized": "max"}},
        {"process": "spm-conditioning-map",  # Table 1's optimum on the beta = 90 slice
         "fixed": {"gamma_deg": 0, "workspace": {"tilt_max_deg": 60, "torsion_deg": [0, 360],
                   "samples": {"azimuth": 4, "tilt": 2, "torsion": 2}}},
         "vary": {"alpha1_deg": [50, 70, 3], "alpha2_deg": [80, 100, 3],
                  "beta_deg": [80, 90, 2]},
         "objectives": {"indices.rms_inverse_condition": "max"}},
    ],
}  # fmt: skip


@pytest.fixture
def figures(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[tuple[str, Figure]]]:
    """Every figure the jobs hand to figure_artifacts, built and not rendered."""
    captured: list[tuple[str, Figure]] = []

    def capture(fig: Figure, stem: str, title: str) -> tuple[Artifact, Artifact]:
        captured.append((stem, fig))
        return (
            Artifact(f"{stem}.png", "image/png", b"", title),
            Artifact(f"{stem}.svg", "image/svg+xml", b"", title),
        )

    for family in FAMILIES:
        jobs = importlib.import_module(f"worker.families.{family}.jobs")
        for info in pkgutil.iter_modules(jobs.__path__):
            module = importlib.import_module(f"{jobs.__name__}.{info.name}")
            if hasattr(module, "figure_artifacts"):
                monkeypatch.setattr(module, "figure_artifacts", capture)
    monkeypatch.setattr(
        importlib.import_module("worker.studies.outcome"), "figure_artifacts", capture
    )
    yield captured


def check(definition: ProcessDefinition, inputs: dict[str, Any], figures: list[Any]) -> None:
    spec = definition.inputs_model.model_validate(inputs)
    definition.run(spec, RecordingContext())
    assert figures, f"{definition.id} drew no figure"
    problems = {stem: figure_defects(fig) for stem, fig in figures}
    assert not any(problems.values()), {k: v for k, v in problems.items() if v}


@pytest.mark.parametrize(("definition", "index"), EXAMPLES)
def test_the_figures_of_every_worked_example_pass(
    definition: ProcessDefinition, index: int, figures: list[tuple[str, Figure]]
) -> None:
    check(definition, dict(definition.examples[index].inputs), figures)


@pytest.mark.parametrize(
    ("process_id", "inputs"),
    [
        *((pid, inputs) for pid, inputs in SMALL.items()),
        *((pid, inputs) for pid, many in VARIANTS.items() for inputs in many),
    ],
    ids=lambda v: v if isinstance(v, str) else "",
)
def test_the_figures_of_other_inputs_pass(
    process_id: str, inputs: dict[str, Any], figures: list[tuple[str, Figure]]
) -> None:
    definition = next(d for d in DEFINITIONS if d.id == process_id)
    check(definition, {**inputs, "plots": True}, figures)


def test_docs_show_one_figure_per_process() -> None:
    docs = Path(__file__).resolve().parents[3] / "docs"
    page = (docs / "figures.md").read_text()
    for definition in DEFINITIONS:
        image = docs / "figures" / f"{definition.id}.png"
        assert image.is_file() and image.read_bytes().startswith(b"\x89PNG"), image
        assert f"(figures/{definition.id}.png)" in page
