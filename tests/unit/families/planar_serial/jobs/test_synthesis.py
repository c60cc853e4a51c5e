"""The planar3r-synthesis job: the paper's Examples 1 and 2 (all three cases), end to end."""

from __future__ import annotations

import io
import json
import math
from typing import Any

import numpy as np
import pytest

from tests.unit.families.conftest import RecordingContext
from worker.contract import JobOutcome
from worker.families.planar_serial import SYNTHESIS
from worker.families.planar_serial.examples import SYNTHESIS_EXAMPLES
from worker.families.planar_serial.jobs.synthesis import run_synthesis
from worker.families.planar_serial.specs import SynthesisSpec

RESULT_KEYS = {
    "distance_source", "d_min", "d_max", "d_min_at", "d_max_at", "round_distances",
    "d_min_used", "d_max_used", "l3", "links", "grashof", "paper_conditions",
    "full_dexterity_bands", "full_dexterity_condition", "task_points", "cases",
    "discretisation", "length_unit",
}  # fmt: skip
CASE_KEYS = {
    "case", "name", "links", "joint_limits_deg", "method", "full_dexterity_bands",
    "fully_dexterous_area", "reachable_area", "fully_dexterous_fraction",
    "areas_method", "fully_dexterous_area_grid", "reachable_area_grid", "task_points", "trajectory",
    "all_task_points_fully_dexterous",
}  # fmt: skip
GRASHOF_KEYS = {
    "lengths", "names", "shortest", "longest", "s_plus_l", "p_plus_q", "is_grashof", "d",
    "end_effector_fully_rotatable",
}  # fmt: skip
#: docs/methods/planar-serial.md, Case 3 (th1, th2 in [-150, 150], th3 in [-175, 175] degrees).
EXAMPLE_1_CASE_3 = {"A": 1.0, "B": 0.8807, "C": 0.7436, "D": 0.7697, "E": 0.7273}
EXAMPLE_2_CASE_3 = {
    "F": 1.0, "G": 0.9805, "A": 0.8955, "C": 0.8630, "E": 0.7874, "D": 0.7840, "B": 0.7766,
}  # fmt: skip


def run_example(index: int) -> tuple[JobOutcome, RecordingContext]:
    ctx = RecordingContext()
    spec = SynthesisSpec.model_validate(dict(SYNTHESIS_EXAMPLES[index].inputs))
    return SYNTHESIS.run(spec, ctx), ctx


@pytest.fixture(scope="module")
def example_1() -> tuple[JobOutcome, RecordingContext]:
    return run_example(0)


@pytest.fixture(scope="module")
def example_1_exact() -> tuple[JobOutcome, RecordingContext]:
    return run_example(1)


@pytest.fixture(scope="module")
def example_2() -> tuple[JobOutcome, RecordingContext]:
    return run_example(2)


def case(outcome: JobOutcome, number: int) -> dict[str, Any]:
    return next(c for c in outcome.result["cases"] if c["case"] == number)


def d_z_by_label(entries: list[dict[str, Any]]) -> dict[str, float]:
    return {e["label"]: e["d_z"] for e in entries}


def joined_notes(outcome: JobOutcome) -> str:
    return "\n".join(outcome.all_notes)


EXAMPLES = ["example_1", "example_1_exact", "example_2"]


# -- all worked examples -------------------------------------------------------------


@pytest.mark.parametrize("example", EXAMPLES)
class TestWorkedExamples:
    def test_progress(self, example: str, request: pytest.FixtureRequest) -> None:
        _, ctx = request.getfixturevalue(example)
        assert ctx.percents == sorted(ctx.percents)
        assert ctx.percents[-1] == 100.0 and any(90 <= p < 100 for p in ctx.percents)
        assert any(m.startswith("Case 3") for _, m in ctx.reports)

    def test_result_document(self, example: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(example)
        result = outcome.result
        assert set(result) == RESULT_KEYS
        json.dumps(result, allow_nan=False)
        assert [c["case"] for c in result["cases"]] == [1, 2, 3]
        assert [c["name"] for c in result["cases"]] == ["ideal", "l2-l3-swapped", "joint-limited"]
        for entry in result["cases"]:
            assert set(entry) == CASE_KEYS
        for end in ("d_min", "d_max"):
            assert set(result["grashof"][end]) == GRASHOF_KEYS
            assert result["grashof"][end]["names"] == ["l1", "l2", "l3", "d"]
        assert result["task_points"] == case(outcome, 1)["task_points"]
        discretisation = result["discretisation"]
        assert discretisation["grid"]["points_per_axis"] == 201
        assert discretisation["orientation_samples"] is None
        assert discretisation["unused_inputs"] == ["orientation_step_deg"]
        assert discretisation["task_points"] == "exact-events"

    def test_artifacts(self, example: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(example)
        assert {a.name: a.media_type for a in outcome.artifacts} == {
            "synthesis_cases.png": "image/png",
            "synthesis_cases.svg": "image/svg+xml",
            "synthesis_cases.npz": "application/x-npz",
        }
        npz_bytes = next(a.data for a in outcome.artifacts if a.name.endswith(".npz"))
        with np.load(io.BytesIO(npz_bytes)) as npz:
            for number in (1, 2, 3):
                assert npz[f"d_z_case{number}"].shape == (201, 201)
            np.testing.assert_array_equal(npz["links_case1"], outcome.result["links"])

    def test_cases_1_and_2(self, example: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(example)
        l1, l2, l3 = outcome.result["links"]
        ideal, swapped = case(outcome, 1), case(outcome, 2)
        assert swapped["links"] == [l1, l3, l2]
        assert ideal["all_task_points_fully_dexterous"] is True
        assert all(d == 1.0 for d in d_z_by_label(ideal["task_points"]).values())
        assert swapped["all_task_points_fully_dexterous"] is False
        assert all(d < 1.0 for d in d_z_by_label(swapped["task_points"]).values())
        assert ideal["joint_limits_deg"] is None and swapped["joint_limits_deg"] is None
        assert ideal["fully_dexterous_area_grid"] == pytest.approx(
            ideal["fully_dexterous_area"], rel=0.02
        )

    def test_case_3_is_exact(self, example: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(example)
        limited = case(outcome, 3)
        assert limited["method"] == "exact-events"
        assert limited["joint_limits_deg"] == [[-150, 150], [-150, 150], [-175, 175]]
        assert limited["full_dexterity_bands"] is None
        # the joint-limited arm's own areas, counted on its map
        assert limited["fully_dexterous_area"] == limited["fully_dexterous_area_grid"]
        assert limited["reachable_area"] == limited["reachable_area_grid"]
        assert limited["areas_method"] == "grid count of exact-events d_z (joint-limited arm)"
        assert case(outcome, 1)["areas_method"] == "exact-closed-form"
        assert limited["all_task_points_fully_dexterous"] is False
        assert limited["fully_dexterous_area_grid"] < case(outcome, 1)["fully_dexterous_area_grid"]

    def test_paper_orderings_are_false_at_d_max(
        self, example: str, request: pytest.FixtureRequest
    ) -> None:
        outcome, _ = request.getfixturevalue(example)
        conditions = outcome.result["paper_conditions"]
        assert conditions["d_max"]["l1 > l2 > d > l3"] is False
        assert "'l1 > l2 > d > l3' at d_max" in joined_notes(outcome)

    def test_real_condition_holds(self, example: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(example)
        condition = outcome.result["full_dexterity_condition"]
        assert condition["l3 + |l1 - l2| <= d_min"] is True
        assert condition["d_max + l3 <= l1 + l2"] is True
        assert condition["d_range_fully_dexterous"] is True
        for end in ("d_min", "d_max"):
            assert outcome.result["grashof"][end]["is_grashof"] is True
            assert outcome.result["grashof"][end]["end_effector_fully_rotatable"] is True

    def test_case_3_shortfalls_are_noted(
        self, example: str, request: pytest.FixtureRequest
    ) -> None:
        outcome, _ = request.getfixturevalue(example)
        notes = joined_notes(outcome)
        for entry in case(outcome, 3)["task_points"]:
            named = f"Case 3 (joint-limited): task point {entry['label']} " in notes
            assert named == (entry["d_z"] < 1.0)


# -- Example 1 -------------------------------------------------------------------------


def test_example_1_exact_range(example_1: tuple[JobOutcome, RecordingContext]) -> None:
    result = example_1[0].result
    assert result["distance_source"] == "trajectory"
    assert result["d_min"] == pytest.approx(10.3923, abs=1e-4)
    assert result["d_max"] == pytest.approx(19.7673, abs=1e-4)
    assert result["d_min_at"][0] == pytest.approx(10.2044, abs=1e-4)
    assert result["d_max_at"][0] == pytest.approx(14.0)


def test_example_1_rounded_is_the_papers_design(
    example_1: tuple[JobOutcome, RecordingContext],
) -> None:
    result = example_1[0].result
    assert result["round_distances"] is True
    assert (result["d_min_used"], result["d_max_used"]) == (10.0, 20.0)
    assert result["links"] == [15.0, 14.0, 8.0]
    assert result["full_dexterity_bands"] == [[0.0, 7.0], [9.0, 21.0]]


def test_example_1_unrounded(example_1_exact: tuple[JobOutcome, RecordingContext]) -> None:
    result = example_1_exact[0].result
    assert result["round_distances"] is False
    assert result["d_min_used"] == result["d_min"]
    assert result["links"] == pytest.approx([14.8837, 13.8837, 8.0], abs=1e-4)


def test_example_1_area_fractions(example_1: tuple[JobOutcome, RecordingContext]) -> None:
    outcome = example_1[0]
    assert case(outcome, 1)["fully_dexterous_fraction"] == pytest.approx(0.298758, abs=1e-6)
    assert case(outcome, 2)["fully_dexterous_fraction"] == pytest.approx(0.035793, abs=1e-6)
    assert case(outcome, 2)["full_dexterity_bands"] == [[0.0, 7.0]]
    assert case(outcome, 1)["reachable_area"] == pytest.approx(math.pi * 37**2)


def test_example_1_case_3(example_1: tuple[JobOutcome, RecordingContext]) -> None:
    found = d_z_by_label(case(example_1[0], 3)["task_points"])
    assert found == pytest.approx(EXAMPLE_1_CASE_3, abs=6e-5)


def test_example_1_trajectory_per_case(example_1: tuple[JobOutcome, RecordingContext]) -> None:
    outcome = example_1[0]
    assert case(outcome, 1)["trajectory"]["fully_dexterous_fraction"] == 1.0
    assert case(outcome, 2)["trajectory"]["fully_dexterous_fraction"] == 0.0
    limited = case(outcome, 3)["trajectory"]
    assert 0.0 < limited["fully_dexterous_fraction"] < 1.0
    assert limited["D_mean"] == pytest.approx(limited["d_z_mean"] / 3)


def test_example_1_notes(example_1: tuple[JobOutcome, RecordingContext]) -> None:
    notes = joined_notes(example_1[0])
    assert "10 <= d <= 20" in notes and "d_min = 10.3923" in notes and "d_max = 19.7673" in notes
    assert "give the paper's (15, 14, 8)" in notes
    assert "8 < d <= 16" in notes and "0.035793 vs 0.298758" in notes
    assert "[0, 7] ∪ [9, 21]" in notes and "0.960107" in notes
    assert "inner radius from |l1 - l2| = 1 to 7.5677" in notes
    # the printed cubic passes (14, 13.9552), so A lies just beyond the trajectory's d_max
    assert "Task point A (14, 14) at d = 19.7990 lies outside" in notes


def test_example_1_unrounded_notes(
    example_1_exact: tuple[JobOutcome, RecordingContext],
) -> None:
    notes = joined_notes(example_1_exact[0])
    assert "give (14.8837, 13.8837, 8)" in notes
    assert "rounding the range outward" in notes
    assert "Distances rounded" not in notes


# -- Example 2 -------------------------------------------------------------------------


def test_example_2_design(example_2: tuple[JobOutcome, RecordingContext]) -> None:
    result = example_2[0].result
    assert result["distance_source"] == "task_points"
    assert (result["d_min"], result["d_max"]) == (18.0, 29.0)
    assert result["d_min_at"] == [18.0, 0.0] and result["d_max_at"] == [20.0, -21.0]
    assert result["links"] == [23.0, 22.0, 15.0]


def test_example_2_case_3(example_2: tuple[JobOutcome, RecordingContext]) -> None:
    found = d_z_by_label(case(example_2[0], 3)["task_points"])
    assert found == pytest.approx(EXAMPLE_2_CASE_3, abs=6e-5)


def test_example_2_notes(example_2: tuple[JobOutcome, RecordingContext]) -> None:
    notes = joined_notes(example_2[0])
    assert "'29 (Point F) and 18 (Point B)'" in notes
    assert "d_min = 18 (B), d_max = 29 (F)" in notes
    assert "(23, 22, 15) as printed" in notes
    assert "three task points" in notes and "1 (F) has d_z = 1" in notes
    assert "G 0.9805, A 0.8955, C 0.8630, E 0.7874, D 0.7840, B 0.7766" in notes
    assert "Example 1" not in notes and "outside the trajectory" not in notes


# -- other inputs (figures built, not rendered) ----------------------------------------


def run(ctx: RecordingContext, **inputs: Any) -> JobOutcome:
    spec = SynthesisSpec.model_validate({"grid": {"points_per_axis": 21}, **inputs})
    return run_synthesis(spec, ctx)


EXAMPLE_2_POINTS = [[16, 19], [18, 0], [-8, -25], [-15, 11], [-10, 16], [20, -21], [-7, 27]]


@pytest.mark.usefixtures("fast_figures")
def test_without_limits_there_are_two_cases(ctx: RecordingContext) -> None:
    outcome = run(ctx, task_points=EXAMPLE_2_POINTS, l3=15)
    result = outcome.result
    assert [c["case"] for c in result["cases"]] == [1, 2]
    assert result["discretisation"]["orientation_samples"] is None
    assert result["discretisation"]["task_points"] == "exact-closed-form"
    assert not any("Case 3" in note for note in outcome.all_notes)
    assert ctx.percents == sorted(ctx.percents) and ctx.percents[-1] == 100.0


@pytest.mark.usefixtures("fast_figures")
def test_l3_too_close_to_d_min(ctx: RecordingContext) -> None:
    # l3 < d_min as the paper asks, but l3 + |l1 - l2| = 18.5 > d_min = 18 (point B)
    outcome = run(ctx, task_points=EXAMPLE_2_POINTS, l3=17.5)
    condition = outcome.result["full_dexterity_condition"]
    assert condition["l3 < d_min (paper)"] is True
    assert condition["l3 + |l1 - l2| <= d_min"] is False
    assert condition["d_range_fully_dexterous"] is False
    assert case(outcome, 1)["all_task_points_fully_dexterous"] is False
    notes = joined_notes(outcome)
    assert "not fully dexterous over [18.0000, 29.0000]" in notes
    assert "Case 1 (ideal): task point B (18, 0)" in notes
    assert "not below d_min" not in notes


@pytest.mark.usefixtures("fast_figures")
def test_l3_not_below_d_min(ctx: RecordingContext) -> None:
    outcome = run(ctx, task_points=[[10, 0], [0, 20]], l3=12)
    assert outcome.result["full_dexterity_condition"]["l3 < d_min (paper)"] is False
    assert "l3 = 12 is not below d_min = 10.0000" in joined_notes(outcome)


@pytest.mark.usefixtures("fast_figures")
def test_polyline_trajectory_sets_the_range(ctx: RecordingContext) -> None:
    outcome = run(ctx, trajectory={"points": [[20, 0], [0, 20], [-25, 0]], "samples": 50},
                  task_points=[[5, 5]], l3=6, round_distances=True)  # fmt: skip
    result = outcome.result
    assert result["distance_source"] == "trajectory"
    assert result["d_min"] == pytest.approx(math.sqrt(200))
    assert result["d_min_at"] == pytest.approx([10.0, 10.0])
    assert result["d_max"] == 25.0 and result["d_max_at"] == [-25.0, 0.0]
    assert (result["d_min_used"], result["d_max_used"]) == (14.0, 25.0)
    assert result["links"] == [16.5, 15.5, 6.0]
    assert case(outcome, 1)["trajectory"]["samples"] == 50
    notes = joined_notes(outcome)
    assert "Task point A (5, 5) at d = 7.0711 lies outside" in notes
    assert "[14.1421, 25.0000] -> [14, 25]" in notes
    assert "Example" not in notes


@pytest.mark.usefixtures("fast_figures")
def test_trajectory_alone_has_no_task_points(ctx: RecordingContext) -> None:
    outcome = run(ctx, trajectory={"polynomial": [0.5, 10], "x_start": -5, "x_end": 5}, l3=5)
    assert outcome.result["task_points"] == []
    assert case(outcome, 1)["all_task_points_fully_dexterous"] is None
    assert outcome.result["d_min"] == pytest.approx(10 / math.sqrt(1.25))


@pytest.mark.usefixtures("fast_figures")
def test_example_2_points_reordered_are_still_recognised(ctx: RecordingContext) -> None:
    outcome = run(ctx, task_points=EXAMPLE_2_POINTS[::-1], l3=15)
    assert "Example 2" in joined_notes(outcome)
