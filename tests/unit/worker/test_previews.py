"""Every preview of the registry: its limits, its sliders and its starting design."""

from __future__ import annotations

import pytest

from worker.errors import CostLimitExceeded, NoPreview
from worker.input_validation import validate_inputs
from worker.preview_run import preview, preview_definition
from worker.processes import ProcessDefinition
from worker.registry import default_registry

REGISTRY = default_registry()
PREVIEWED = [d for d in REGISTRY if d.preview is not None]


def test_the_three_explorers_have_a_preview() -> None:
    assert {d.id for d in PREVIEWED} >= {
        "spm-conditioning-map", "planar3r-dexterity-map", "planar2dof-conditioning-map",
    }  # fmt: skip


@pytest.mark.parametrize("definition", PREVIEWED, ids=lambda d: d.id)
def test_the_start_validates_fits_and_sits_on_its_sliders(definition: ProcessDefinition) -> None:
    spec = definition.preview
    assert spec is not None
    assert spec.cost_limit <= definition.cost_limit
    start = spec.start_inputs(definition.examples[spec.start_example].inputs)
    assert definition.cost(validate_inputs(definition, start)) <= spec.cost_limit
    for field in spec.fields:
        value = start
        for part in field.path.split("."):
            value = value[int(part)] if isinstance(value, list | tuple) else value[part]
        assert field.low <= float(value) <= field.high, field.path


def test_a_preview_above_its_limit_names_the_cost() -> None:
    definition = REGISTRY.require("planar3r-dexterity-map")
    assert definition.preview is not None
    inputs = {**definition.preview.start_inputs(definition.examples[1].inputs),
              "grid": {"points_per_axis": 301}}  # fmt: skip
    with pytest.raises(CostLimitExceeded, match="above the preview limit") as refused:
        preview(REGISTRY, definition.id, inputs)
    assert refused.value.extra["cost"] > refused.value.extra["cost_limit"]


def test_a_process_without_one_says_which_have_one() -> None:
    with pytest.raises(NoPreview, match="spm-conditioning-map"):
        preview_definition(REGISTRY, "fourbar-grashof")
