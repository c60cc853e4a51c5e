"""The design-study process: the submission's dry check of the first design, chunking,
the cost model, and a whole study run in one process."""

from __future__ import annotations

from typing import Any

import pytest

from tests.unit.families.conftest import RecordingContext
from tests.unit.worker.studies.registry import STUDY, chunk_inputs, dry_check, study_cost
from worker.registry import default_registry
from worker.studies.evaluation import evaluate_block
from worker.studies.paths import parse_result_path, reported
from worker.studies.spec import StudySpec

BASE: dict[str, Any] = {
    "process": "planar3r-dexterity-map",
    "fixed": {"links": [15, 14, 8], "task_points": [[14, 14]], "grid": {"points_per_axis": 5}},
    "vary": {"links[2]": [6, 10, 3]},
    "objectives": {"task_points[].d_z|min": "max"},
}


def spec(**change: Any) -> StudySpec:
    return StudySpec.model_validate({**BASE, **change})


def test_the_dry_check_passes_a_sound_study() -> None:
    assert dry_check(spec()) == []


def test_an_objective_the_process_never_reports_is_refused() -> None:
    problems = dry_check(spec(objectives={"task_point[].d_z|min": "max", "links|sum": "min"}))
    assert [p["field"] for p in problems] == ["inputs.objectives.task_point[].d_z|min"]
    assert "reports no number at this path" in problems[0]["message"]
    assert "result_paths" in problems[0]["message"]


def test_an_objective_must_be_a_declared_number() -> None:
    """``method`` is reported (a text): no number, so no objective, and no unit to give
    it; ``chains[3].rank.by_Q`` and ``links|sum`` read declared numbers."""
    problems = dry_check(spec(objectives={"method": "max", "discretisation.grid": "min"}))
    assert [p["field"] for p in problems] == [
        "inputs.objectives.method",
        "inputs.objectives.discretisation.grid",
    ]
    assert dry_check(spec(objectives={"links|sum": "min", "links[0]": "max",
                                      "full_dexterity_bands[]|max": "max"})) == []  # fmt: skip
    chains = StudySpec.model_validate(STUDY.examples[2].inputs)
    assert dry_check(chains) == []


def test_fixed_inputs_refused_whatever_is_varied_are_refused() -> None:
    problems = dry_check(spec(fixed={**BASE["fixed"], "grid": {"points": 5}}))
    assert [p["field"] for p in problems] == ["inputs.fixed.grid.points"]
    assert "refuses every design tried" in problems[0]["message"]


def test_a_first_design_refused_for_a_varied_value_is_no_error() -> None:
    assert dry_check(spec(vary={"links[2]": [-1, 8, 3]})) == []


def test_null_values_count_as_reported() -> None:
    result = {"indices": {"rms": None}, "trajectory": None, "rows": []}
    for path, expected in [("indices.rms", True), ("trajectory.d_z_min", True),
                           ("rows[].x|min", True), ("indices.gci", False), ("rows[3].x", False),
                           ("indices[].rms|min", False)]:  # fmt: skip
        assert reported(result, parse_result_path(path)) is expected, path


def test_chunks_cover_every_design_once_in_order() -> None:
    study = spec(vary={"links[2]": [6, 10, 11]}, chunk_size=4)
    chunks = chunk_inputs(study)
    assert [(c["start"], c["stop"]) for c in chunks] == [(0, 4), (4, 8), (8, 11)]
    planned = chunk_inputs(spec(vary={"links[2]": [6, 10, 11]}))
    assert len(planned) >= 3  # at least four chunks' worth of designs each (11 designs)
    assert planned[0]["start"] == 0 and planned[-1]["stop"] == 11


def test_the_cost_is_designs_times_the_first_designs_share_of_the_limit() -> None:
    process = default_registry().get("planar3r-dexterity-map")
    assert process is not None
    study = spec(vary={"links[2]": [6, 10, 1000]}, engine="per-design")
    share = 25 / process.cost_limit  # a 5 x 5 closed-form map
    assert study_cost(study) == pytest.approx(1000 * share * 1e6, abs=1)
    assert study_cost(study) <= STUDY.cost_limit
    # through the kernel: one task point (closed form) and the rest, 2 units a design
    batched = spec(vary={"links[2]": [6, 10, 1000]})
    assert study_cost(batched) == pytest.approx(1000 * 2 / process.cost_limit * 1e6, abs=1)


def test_the_whole_study_in_one_process() -> None:
    outcome = STUDY.run(spec(objectives={"task_points[].d_z|min": "max", "links|sum": "min"},
                             plots=False), RecordingContext())  # fmt: skip
    result = outcome.result
    assert (result["count"], result["evaluated"], result["feasible"]) == (3, 3, 3)
    assert [a.name for a in outcome.artifacts] == ["designs.csv", "designs.npz"]
    assert result["best"]["links|sum"][0]["parameters"] == {"links[2]": 6.0}


def test_a_first_design_refused_for_its_varied_values_is_no_error() -> None:
    """Bai's SPM at (30, 30) cannot reach Example I's workspace at all: the process
    refuses it on its ``workspace`` field, not on a varied one; other designs of the
    grid (60, 90) are fine, so the study is accepted and its objectives are checked on
    the first design that validates."""
    study = StudySpec.model_validate(STUDY.examples[0].inputs)
    assert study.designs.block(0, 1)[0].tolist() == [30.0, 30.0]
    assert dry_check(study) == []
    # declared (given orientations have it), but this study gives none
    wrong = study.model_copy(update={"objectives": {"orientations[0].inverse_condition": "max"}})
    (problem,) = dry_check(wrong)
    assert problem["field"] == "inputs.objectives.orientations[0].inverse_condition"
    assert "reports nothing at this path" in problem["message"]


def test_fixed_inputs_refused_at_every_tried_design_are_refused() -> None:
    study = StudySpec.model_validate(
        {**STUDY.examples[0].inputs,
         "fixed": {"beta_deg": 90, "gamma_deg": 0,
                   "workspace": {"tilt_max_deg": 60, "torsion_deg": [0, 1000]}}}
    )  # fmt: skip
    (problem,) = dry_check(study)
    assert problem["field"] == "inputs.fixed.workspace.torsion_deg"
    assert "refuses every design tried" in problem["message"]


@pytest.mark.parametrize(
    ("space", "field"),
    [
        ({"vary": {"plots": [0, 1, 2]}}, "inputs.vary.plots"),
        ({"vary": {"links[2]": [6, 10, 3], "lenghts_typo": [1, 2, 2]}}, "inputs.vary.lenghts_typo"),
        ({"vary": {"task_points[0]": [1, 2, 2]}}, "inputs.vary.task_points[0]"),
        ({"vary": None, "sample": {"count": 3, "bounds": {"grid": [1, 2]}}},
         "inputs.sample.bounds.grid"),
    ],
)  # fmt: skip
def test_a_varied_path_the_process_takes_no_number_at_is_refused(
    space: dict[str, Any], field: str
) -> None:
    fixed = {"links": [15, 14, 8], "task_points": [[14, 14]]}
    problems = dry_check(spec(fixed=fixed, **space))
    assert [p["field"] for p in problems] == [field]
    assert "planar3r-dexterity-map takes no number at" in problems[0]["message"]


def test_a_refusal_at_a_place_holding_a_varied_input_is_for_its_value() -> None:
    """Every tried design's joint 1 range is reversed by the varied upper limit: the
    process refuses the whole ``joint_limits_deg``, which holds the varied input, so
    the designs say why (the dry check does not blame ``fixed``)."""
    limits = [[-150, 150], [-150, 150], [-175, 175]]
    study = spec(fixed={**BASE["fixed"], "joint_limits_deg": limits},
                 vary={"joint_limits_deg[0][1]": [-170, -160, 3]})  # fmt: skip
    assert dry_check(study) == []
    process = default_registry().get("planar3r-dexterity-map")
    assert process is not None
    (row,) = evaluate_block(study, process, 0, 1)
    assert row.reason is not None and "inputs.joint_limits_deg" in row.reason


def test_joint_limits_in_radians_are_refused_whatever_is_varied() -> None:
    """Issue 26: a study forwarding radians to planar3r-dexterity-map is refused at
    submission, by the static check of the process's own inputs."""
    radians = [[-2.618, 2.618], [-2.618, 2.618], [-3.054, 3.054]]
    problems = dry_check(spec(fixed={**BASE["fixed"], "joint_limits_deg": radians}))
    assert [p["field"] for p in problems] == ["inputs.fixed.joint_limits_deg"]
    assert "degrees expected; these look like radians" in problems[0]["message"]
    assert dry_check(spec(fixed={**BASE["fixed"], "joint_limits_deg": [[-150, 150]] * 3})) == []


def test_a_per_design_study_is_priced_by_its_dearest_design_not_its_first() -> None:
    """The map's cost grows with its grid: a study from 5 x 5 up to 401 x 401 grids is
    priced at the dearest design tried, so it cannot pass the refusal before queuing on
    its cheap first design."""
    process = default_registry().get("planar3r-dexterity-map")
    assert process is not None
    fixed = {key: value for key, value in BASE["fixed"].items() if key != "grid"}
    study = spec(fixed=fixed, vary={"grid.points_per_axis": [5, 401, 3]}, engine="per-design")
    dearest = 401 * 401 / process.cost_limit
    assert study_cost(study) == pytest.approx(3 * dearest * 1e6, abs=1)
    cheap_first = 5 * 5 / process.cost_limit
    assert study_cost(study) > 100 * 3 * cheap_first * 1e6


def test_a_design_out_of_every_range_is_the_kernels_to_refuse_not_an_overflow() -> None:
    """A sampled chain length of 1e300 overflowed in the kernel's squares while the
    submission checked the objectives (a 500 under warnings-as-errors): the kernel
    evaluates it quietly and the design is refused later as out of range."""
    import warnings

    study = StudySpec.model_validate({
        "process": "chain-parallelism",
        "fixed": {"chains": [{"name": "a", "lengths": [15, 15, 15, 15]},
                             {"name": "b", "lengths": [20, 10, 20, 10]}]},
        "sample": {"method": "sobol", "count": 1, "seed": 0,
                   "bounds": {"chains[0].lengths[0]": [1e300, 1e300]}},
        "objectives": {"chains[0].Q": "min"},
    })  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        dry_check(study)
