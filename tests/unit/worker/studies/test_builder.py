"""What the study builder offers from the registry, and the study its choices spell
(validated by the study's own inputs model)."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from worker.processes import ProcessDefinition
from worker.registry import default_registry
from worker.studies.builder import (
    MAX_OFFERED_INPUTS,
    ObjectiveChoice,
    VariedInput,
    builder_options,
    numeric_inputs,
    studied_processes,
    study_inputs,
)
from worker.studies.paths import parse_result_path
from worker.studies.spec import NOT_STUDIED

REGISTRY = default_registry()


def test_every_process_but_the_study_itself_is_offered() -> None:
    offered = [d.id for d in studied_processes(REGISTRY)]
    assert offered == [pid for pid in REGISTRY.ids() if pid not in NOT_STUDIED]
    assert builder_options(REGISTRY, "design-study") is None
    assert builder_options(REGISTRY, "no-such-process") is None


def test_numbers_of_an_example_are_offered_with_units_in_document_order() -> None:
    options = builder_options(REGISTRY, "planar3r-dexterity-map", 1)
    assert options is not None
    numbers = {n.path: n for n in options.examples[1].numeric}
    assert [p for p in numbers][:3] == ["links[0]", "links[1]", "links[2]"]
    assert numbers["links[0]"].value == 15
    assert numbers["joint_limits_deg[2][1]"].unit == "deg"
    assert numbers["grid.points_per_axis"].unit == "-"


def test_flags_and_texts_are_not_offered() -> None:
    definition = REGISTRY.require("chain-parallelism")
    inputs = {"chains": [{"name": "a", "lengths": [1, 2, 3, 4]}], "length_unit": "cm"}
    paths = [n.path for n in numeric_inputs(definition, inputs)]
    assert paths == [f"chains[0].lengths[{i}]" for i in range(4)]
    assert {n.unit for n in numeric_inputs(definition, inputs)} == {"cm"}


def test_a_long_list_is_cut_at_the_offer_limit() -> None:
    definition = REGISTRY.require("chain-parallelism")
    chains = [{"name": f"c{i}", "lengths": [1, 2, 3, 4]} for i in range(40)]
    assert len(numeric_inputs(definition, {"chains": chains})) == MAX_OFFERED_INPUTS


@pytest.mark.parametrize("definition", studied_processes(REGISTRY), ids=lambda d: d.id)
def test_every_offered_objective_is_a_result_path_a_study_takes(
    definition: ProcessDefinition,
) -> None:
    options = builder_options(REGISTRY, definition.id)
    assert options is not None
    for objective in options.objectives:
        reduction = "min" if objective.listed else ""
        parse_result_path(ObjectiveChoice(objective.path, reduction, "max").name)


def test_a_grid_study_validates_with_the_varied_key_left_out_of_fixed() -> None:
    options = builder_options(REGISTRY, "spm-conditioning-map", 0)
    assert options is not None
    fixed = options.examples[0].inputs
    inputs = study_inputs(
        "spm-conditioning-map", fixed,
        [VariedInput("alpha1_deg", 50, 70, 3), VariedInput("workspace.torsion_deg[1]", 90, 360, 2)],
        [ObjectiveChoice("indices.rms_inverse_condition", "", "max")],
    )  # fmt: skip
    assert "alpha1_deg" not in inputs["fixed"] and "alpha1_deg" in fixed
    assert inputs["fixed"]["workspace"]["torsion_deg"] == [0, 360]  # a list element stays
    spec = REGISTRY.require("design-study").inputs_model.model_validate(inputs)
    assert spec.designs.count == 6


def test_a_sample_study_takes_the_ranges_as_bounds() -> None:
    inputs = study_inputs(
        "planar3r-dexterity-map", {"links": [15, 14, 8]},
        [VariedInput("links[0]", 10, 20, "ignored")],
        [ObjectiveChoice("task_points[].d_z", "min", "max")],
        sample={"method": "sobol", "count": 4, "seed": 0},
    )  # fmt: skip
    assert inputs["sample"]["bounds"] == {"links[0]": [10, 20]}
    assert inputs["objectives"] == {"task_points[].d_z|min": "max"}
    assert "vary" not in inputs


@given(st.floats(-1e6, 1e6), st.floats(-1e6, 1e6))
def test_a_range_is_kept_as_given_for_the_study_to_judge(low: float, high: float) -> None:
    inputs = study_inputs("spm-conditioning-map", {}, [VariedInput("alpha1_deg", low, high, 2)], [])
    assert inputs["vary"] == {"alpha1_deg": [low, high, 2]}
    model = REGISTRY.require("design-study").inputs_model
    if low > high:
        with pytest.raises(ValueError, match="exceeds hi"):
            model.model_validate({**inputs, "objectives": {"indices.rms_inverse_condition": "max"}})
