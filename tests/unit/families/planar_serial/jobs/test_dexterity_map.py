"""The planar3r-dexterity-map job: the paper's Example 1 design, end to end."""

from __future__ import annotations

import csv
import io
import json
import math
from typing import Any

import numpy as np
import pytest

from tests.unit.families.conftest import RecordingContext
from worker.contract import JobOutcome
from worker.families.planar_serial import DEXTERITY_MAP
from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.examples import DEXTERITY_MAP_EXAMPLES, PAPER_JOINT_LIMITS_DEG
from worker.families.planar_serial.jobs.dexterity_map import run_dexterity_map
from worker.families.planar_serial.jobs.regions import region_table
from worker.families.planar_serial.jobs.trajectories import trajectory_path, trajectory_samples
from worker.families.planar_serial.kinematics.limited_exact import (
    exact_limited_orientation_dexterity,
)
from worker.families.planar_serial.specs import (
    DexterityMapSpec,
    PolylineTrajectory,
    PolynomialTrajectory,
)

RESULT_KEYS = {
    "links", "joint_limits_deg", "length_unit", "method", "discretisation", "regions",
    "full_dexterity_bands", "areas", "summary", "task_points", "trajectory", "data",
}  # fmt: skip
ARTIFACTS = {
    "heatmap.png": "image/png",
    "heatmap.svg": "image/svg+xml",
    "surface.png": "image/png",
    "surface.svg": "image/svg+xml",
    "radial_section.png": "image/png",
    "radial_section.svg": "image/svg+xml",
    "dexterity_map.csv": "text/csv",
    "dexterity_map.npz": "application/x-npz",
}
#: docs/methods/planar-serial.md: Example 1, Case 3 (joint limits) at the task points A..E.
CASE_3_DZ = {"A": 1.0, "B": 0.8807, "C": 0.7436, "D": 0.7697, "E": 0.7273}


def run_example(index: int) -> tuple[JobOutcome, RecordingContext]:
    ctx = RecordingContext()
    spec = DexterityMapSpec.model_validate(dict(DEXTERITY_MAP_EXAMPLES[index].inputs))
    return DEXTERITY_MAP.run(spec, ctx), ctx


@pytest.fixture(scope="module")
def ideal() -> tuple[JobOutcome, RecordingContext]:
    return run_example(0)


@pytest.fixture(scope="module")
def limited() -> tuple[JobOutcome, RecordingContext]:
    return run_example(1)


def artifact(outcome: JobOutcome, name: str) -> bytes:
    return next(a.data for a in outcome.artifacts if a.name == name)


def by_label(outcome: JobOutcome) -> dict[str, dict[str, Any]]:
    return {entry["label"]: entry for entry in outcome.result["task_points"]}


# -- both worked examples ------------------------------------------------------------


@pytest.mark.parametrize("example", ["ideal", "limited"])
class TestWorkedExamples:
    def test_progress_rises_to_the_end(self, example: str, request: pytest.FixtureRequest) -> None:
        _, ctx = request.getfixturevalue(example)
        percents = ctx.percents
        assert len(percents) >= 5
        assert percents == sorted(percents)
        assert percents[0] >= 0.0 and percents[-1] == 100.0
        assert any(90.0 <= p < 100.0 for p in percents)
        assert all(message for _, message in ctx.reports)

    def test_result_document(self, example: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(example)
        result = outcome.result
        assert set(result) == RESULT_KEYS
        json.dumps(result, allow_nan=False)
        assert result["links"] == [15.0, 14.0, 8.0]
        assert result["data"] == {"csv": "dexterity_map.csv", "npz": "dexterity_map.npz"}
        grid = result["discretisation"]["grid"]
        assert grid["points_per_axis"] == 201
        assert grid["bounds"] == pytest.approx([-38.85, 38.85, -38.85, 38.85])
        assert grid["step"] == pytest.approx([0.3885, 0.3885])
        assert [r["region"] for r in result["regions"]] == [1, 2, 3, 4]
        assert [e["label"] for e in result["task_points"]] == ["A", "B", "C", "D", "E"]
        assert result["summary"]["warnings"] == []
        assert result["summary"]["unreachable_task_points"] == []

    def test_artifacts(self, example: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(example)
        assert {a.name: a.media_type for a in outcome.artifacts} == ARTIFACTS
        assert all(a.data for a in outcome.artifacts)
        assert artifact(outcome, "heatmap.png").startswith(b"\x89PNG")

    def test_csv_has_one_row_per_node(self, example: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(example)
        rows = list(csv.reader(io.StringIO(artifact(outcome, "dexterity_map.csv").decode())))
        assert rows[0] == [
            "x [units]", "y [units]", "distance [units]", "d_z [-]", "D [-]", "region [-]"
        ]  # fmt: skip
        assert len(rows) - 1 == 201**2

    def test_csv_and_npz_agree(self, example: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(example)
        data = np.loadtxt(io.StringIO(artifact(outcome, "dexterity_map.csv").decode()),
                          delimiter=",", skiprows=1)  # fmt: skip
        with np.load(io.BytesIO(artifact(outcome, "dexterity_map.npz"))) as npz:
            assert npz["d_z"].shape == (201, 201)
            np.testing.assert_allclose(data[:, 3], npz["d_z"].ravel(), rtol=1e-11, atol=1e-12)
            np.testing.assert_allclose(data[:, 4], npz["D"].ravel(), rtol=1e-11, atol=1e-12)
            np.testing.assert_array_equal(data[:, 5], npz["region"].ravel())
            np.testing.assert_allclose(data[:201, 0], npz["x"], rtol=1e-11)
            np.testing.assert_allclose(data[::201, 1], npz["y"], rtol=1e-11)
            np.testing.assert_array_equal(npz["links"], [15.0, 14.0, 8.0])
            assert json.loads(str(npz["axes"]))["d_z"] == ["y", "x"]
            units = json.loads(str(npz["units"]))
            assert (
                units["x"] == "units" and units["d_z"] == "-" and units["joint_limits_deg"] == "deg"
            )
            assert set(units) == set(npz.files) - {"axes", "units", "metadata"}
            meta = json.loads(str(npz["metadata"]))
            assert meta["process"] == "planar3r-dexterity-map"
            assert meta["inputs"]["links"] == [15.0, 14.0, 8.0]

    def test_summary_counts_the_map(self, example: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(example)
        result = outcome.result
        with np.load(io.BytesIO(artifact(outcome, "dexterity_map.npz"))) as npz:
            d_z = npz["d_z"]
        summary, areas = result["summary"], result["areas"]
        assert summary["reachable_points"] == np.count_nonzero(d_z > 0)
        assert summary["fully_dexterous_points"] == np.count_nonzero(d_z >= 1 - 1e-12)
        assert summary["d_z_mean_reachable"] == pytest.approx(d_z[d_z > 0].mean())
        assert summary["D_mean_reachable"] == pytest.approx(summary["d_z_mean_reachable"] / 3)
        assert areas["cell_area"] == pytest.approx(0.3885**2)
        assert areas["reachable_grid"] == pytest.approx(
            summary["reachable_points"] * areas["cell_area"]
        )
        if example == "ideal":
            assert areas["reachable"] == pytest.approx(math.pi * 37**2)
            assert areas["fully_dexterous"] == pytest.approx(math.pi * 409)
            assert "unlimited_reference" not in areas
            return
        # under joint limits: the limited arm's areas, from the map; unlimited as reference
        assert areas["reachable"] == areas["reachable_grid"]
        assert areas["fully_dexterous"] == areas["fully_dexterous_grid"]
        assert areas["fully_dexterous"] < 0.5 * math.pi * 409
        reference = areas["unlimited_reference"]
        assert reference["reachable"] == pytest.approx(math.pi * 37**2)
        assert reference["fully_dexterous"] == pytest.approx(math.pi * 409)
        assert reference["full_dexterity_bands"] == [[0.0, 7.0], [9.0, 21.0]]
        assert reference["regions"] == region_table((15.0, 14.0, 8.0))


# -- Case 1: revolute joints, exact ----------------------------------------------------


def test_ideal_is_exact(ideal: tuple[JobOutcome, RecordingContext]) -> None:
    outcome, _ = ideal
    result = outcome.result
    assert result["method"] == "exact-closed-form"
    assert result["joint_limits_deg"] is None
    discretisation = result["discretisation"]
    assert discretisation["orientation_step_deg"] is None
    assert discretisation["orientation_samples"] is None
    assert discretisation["elbow_branches"] is None
    assert discretisation["task_points"] == "exact-closed-form"


def test_ideal_map_is_the_closed_form(ideal: tuple[JobOutcome, RecordingContext]) -> None:
    outcome, _ = ideal
    with np.load(io.BytesIO(artifact(outcome, "dexterity_map.npz"))) as npz:
        x, y, d_z, region = npz["x"], npz["y"], npz["d_z"], npz["region"]
    points = np.stack(np.meshgrid(x, y), axis=-1)
    expected = planar_serial.exact_orientation_dexterity((15, 14, 8), points)
    np.testing.assert_array_equal(d_z, expected)
    distance = np.hypot(points[..., 0], points[..., 1])
    np.testing.assert_array_equal(region, planar_serial.paper_regions((15, 14, 8), distance))


def test_ideal_task_points_and_trajectory(ideal: tuple[JobOutcome, RecordingContext]) -> None:
    outcome, _ = ideal
    for entry in outcome.result["task_points"]:
        assert entry["d_z"] == pytest.approx(1.0, abs=1e-12)
        assert entry["D"] == pytest.approx(1 / 3)
        assert entry["region"] == 2
    assert by_label(outcome)["B"]["distance"] == pytest.approx(math.hypot(12, 8))
    assert outcome.result["trajectory"] == pytest.approx(
        {"samples": 200, "d_z_mean": 1.0, "D_mean": 1 / 3, "d_z_min": 1.0,
         "fully_dexterous_fraction": 1.0}
    )  # fmt: skip


def test_ideal_areas_ratio(ideal: tuple[JobOutcome, RecordingContext]) -> None:
    areas = ideal[0].result["areas"]
    assert areas["fully_dexterous"] / areas["reachable"] == pytest.approx(0.298758, abs=1e-6)
    assert areas["reachable_grid"] == pytest.approx(areas["reachable"], rel=0.01)
    assert areas["fully_dexterous_grid"] == pytest.approx(areas["fully_dexterous"], rel=0.01)


def test_ideal_bands_are_the_closed_form(ideal: tuple[JobOutcome, RecordingContext]) -> None:
    assert ideal[0].result["full_dexterity_bands"] == [[0.0, 7.0], [9.0, 21.0]]


def test_regions_against_methods(ideal: tuple[JobOutcome, RecordingContext]) -> None:
    region_1, region_2, region_3, region_4 = ideal[0].result["regions"]
    assert (region_1["d_from"], region_1["d_to"]) == (0.0, 8.0)
    assert region_1["fully_dexterous_bands"] == [[0.0, 7.0]]
    assert region_1["d_z_min"] == pytest.approx(0.960107, abs=1e-6)
    assert region_1["d_z_min_at"] == pytest.approx(7.937, abs=1e-3)
    assert "low dexterity" in region_1["paper"]
    assert (region_2["d_from"], region_2["d_to"]) == (8.0, 21.0)
    assert region_2["fully_dexterous_bands"] == [[9.0, 21.0]]
    assert region_2["d_z_min"] == pytest.approx(0.9602, abs=1e-4)
    assert "[9, 21]" in region_2["corrected"]
    assert region_3["fully_dexterous_bands"] == []
    assert region_3["d_z_min"] == pytest.approx(0.0, abs=1e-6)
    assert region_4["d_to"] is None and region_4["d_z_max"] == 0.0


def test_example_2_quick_look_fits_the_synchronous_limit() -> None:
    """The third worked example: Example 2's design (23, 22, 15) on a 101 x 101 grid;
    every task point A..G (18 <= d <= 29) lies in the band [16, 30] of full dexterity."""
    definition = DEXTERITY_MAP
    spec = DexterityMapSpec.model_validate(dict(DEXTERITY_MAP_EXAMPLES[2].inputs))
    assert definition.cost(spec) <= definition.sync_cost_limit
    outcome = definition.run(spec, RecordingContext())
    entries = by_label(outcome)
    assert list(entries) == list("ABCDEFG")
    assert entries["F"]["distance"] == pytest.approx(29.0)
    assert entries["B"]["distance"] == pytest.approx(18.0)
    for entry in entries.values():
        assert entry["d_z"] == pytest.approx(1.0, abs=1e-12)
    assert outcome.result["regions"][1]["fully_dexterous_bands"] == [[16.0, 30.0]]


def test_ideal_notes(ideal: tuple[JobOutcome, RecordingContext]) -> None:
    notes = ideal[0].all_notes
    assert len(notes) == 1
    assert "Region 2" in notes[0] and "[0, 7] ∪ [9, 21]" in notes[0]
    assert "0.960107" in notes[0]


# -- Case 3: joint limits, exact events (and sampled, the reference) -------------------


@pytest.fixture(scope="module")
def sampled() -> tuple[JobOutcome, RecordingContext]:
    return run_example(3)


def test_limited_discretisation(limited: tuple[JobOutcome, RecordingContext]) -> None:
    result = limited[0].result
    assert result["method"] == "exact-events"
    assert result["joint_limits_deg"] == [list(p) for p in PAPER_JOINT_LIMITS_DEG]
    discretisation = result["discretisation"]
    assert discretisation["orientation_step_deg"] is None
    assert discretisation["orientation_samples"] is None
    assert discretisation["unused_inputs"] == ["orientation_step_deg"]
    # annulus edges, th2, th1 and th3 limits: 8 conditions, two roots each
    assert discretisation["events_per_point"] == 16
    assert discretisation["elbow_branches"] == 2
    assert discretisation["task_points"] == "exact-events"
    assert discretisation["radial_section"]["method"] == "exact-events"


def test_sampled_discretisation(sampled: tuple[JobOutcome, RecordingContext]) -> None:
    result = sampled[0].result
    assert result["method"] == "orientation-sampling"
    discretisation = result["discretisation"]
    assert discretisation["orientation_step_deg"] == pytest.approx(1.0)
    assert discretisation["orientation_samples"] == 360
    assert discretisation["elbow_branches"] == 2
    assert discretisation["task_points"] == "bisection-refined (tol 1e-10 rad)"
    assert "unused_inputs" not in discretisation


def test_exact_and_sampled_maps_agree_to_the_sampling_error(
    limited: tuple[JobOutcome, RecordingContext], sampled: tuple[JobOutcome, RecordingContext]
) -> None:
    maps = []
    for outcome, _ in (limited, sampled):
        with np.load(io.BytesIO(artifact(outcome, "dexterity_map.npz"))) as npz:
            maps.append(npz["d_z"])
    exact, coarse = maps
    # each feasible arc's two ends move by less than one 1-degree step in total
    assert np.abs(exact - coarse).max() <= 2 / 360
    assert 0 < np.abs(exact - coarse).mean() < 0.5 / 360
    # the exact values are not multiples of 1/360; the sampled ones are
    assert np.allclose(coarse * 360, np.round(coarse * 360))
    assert not np.allclose(exact * 360, np.round(exact * 360))
    for a, b in zip(by_label(limited[0]).values(), by_label(sampled[0]).values(), strict=True):
        assert a["d_z"] == pytest.approx(b["d_z"], abs=1e-9)


def test_limited_task_points_match_methods(limited: tuple[JobOutcome, RecordingContext]) -> None:
    entries = by_label(limited[0])
    for label, d_z in CASE_3_DZ.items():
        assert entries[label]["d_z"] == pytest.approx(d_z, abs=6e-5)
        assert entries[label]["D"] == pytest.approx(entries[label]["d_z"] / 3)


def test_limited_map_loses_dexterity(limited: tuple[JobOutcome, RecordingContext]) -> None:
    result = limited[0].result
    assert result["summary"]["fully_dexterous_points"] < 0.5 * 8493
    assert result["trajectory"]["fully_dexterous_fraction"] < 1.0
    assert result["trajectory"]["d_z_mean"] == pytest.approx(result["trajectory"]["D_mean"] * 3)


def test_limited_notes(limited: tuple[JobOutcome, RecordingContext]) -> None:
    notes = "\n".join(limited[0].all_notes)
    for label in "BCDE":
        assert f"task point {label} " in notes
    assert "task point A " not in notes
    assert "d_z = 0.8807 < 1" in notes
    assert "ray at 0°" in notes
    assert "trajectory is fully dexterous at" in notes
    region_2 = limited[0].all_notes[0]
    assert "Region 2" in region_2 and "with these joint limits, along the ray at 0°" in region_2
    assert "[0, 0.43235] ∪ [15.5677, 20.897]" in region_2 and "0.605127" in region_2
    assert "with unlimited joints [0, 7] ∪ [9, 21]" in region_2


# -- issue 26, finding 2: under joint limits every field describes the limited arm ----


def along_the_ray(distances: np.ndarray) -> np.ndarray:
    """Example 1's arm under the paper's limits along the radial section's ray (0°)."""
    points = np.stack([distances, np.zeros_like(distances)], axis=-1)
    return exact_limited_orientation_dexterity(
        (15, 14, 8), points, np.radians(PAPER_JOINT_LIMITS_DEG)
    )


def test_limited_regions_are_the_limited_arms(limited: tuple[JobOutcome, RecordingContext]) -> None:
    result = limited[0].result
    regions = result["regions"]
    for region in regions[:3]:
        distances = np.linspace(region["d_from"], region["d_to"], 4001)
        d_z = along_the_ray(distances)
        assert region["d_z_min"] <= d_z.min() + 1e-10
        assert region["d_z_max"] >= d_z.max() - 1e-10
        assert along_the_ray(np.array([region["d_z_min_at"]]))[0] == region["d_z_min"]
        assert "with these joint limits, along the ray at 0°" in region["corrected"]
        assert region["paper"].endswith("; claimed for unlimited joints")
    region_1, region_2, region_3, _ = regions
    assert region_2["d_z_min"] == pytest.approx(0.686358, abs=1e-6)  # not 0.960 (unlimited)
    assert region_2["d_z_min_at"] == 8.0
    assert region_1["d_z_min"] == pytest.approx(0.605127, abs=1e-6)
    assert region_3["d_z_max"] == pytest.approx(0.976595, abs=1e-6)
    # task point B (d = 14.42, region 2) has 0.8807 in the same result: inside the range
    b = by_label(limited[0])["B"]
    assert b["region"] == 2 and region_2["d_z_min"] < b["d_z"] < region_2["d_z_max"]
    assert "[9, 21]" not in region_2["corrected"] and "[15.5677, 20.897]" in region_2["corrected"]


def test_limited_bands_are_the_limited_arms(limited: tuple[JobOutcome, RecordingContext]) -> None:
    result = limited[0].result
    np.testing.assert_allclose(result["full_dexterity_bands"],
                               [[0.0, 0.432350], [15.567650, 20.897015]], atol=1e-6)  # fmt: skip
    region_1, region_2, region_3, _ = result["regions"]
    assert region_1["fully_dexterous_bands"] == result["full_dexterity_bands"][:1]
    assert region_2["fully_dexterous_bands"] == result["full_dexterity_bands"][1:]
    assert region_3["fully_dexterous_bands"] == []
    distances = np.linspace(0.0, 37.0, 37001)
    full = along_the_ray(distances) >= 1 - 1e-12
    inside = np.zeros_like(full)
    for lo, hi in result["full_dexterity_bands"]:
        inside |= (distances >= lo - 1e-9) & (distances <= hi + 1e-9)
    np.testing.assert_array_equal(full, inside)


@pytest.mark.usefixtures("fast_figures")
@pytest.mark.parametrize(
    ("links", "limits_deg"),
    [
        ((15, 14, 8), [[-90, 90], [-120, 120], [-170, 170]]),
        ((10, 10, 5), [[0, 120], [-150, 30], [-90, 90]]),
        ((23, 22, 15), [[-150, 150], [-150, 150], [-175, 175]]),
        ((6, 9, 3), [[-180, 180], [-45, 45], [-180, 180]]),
    ],
)
def test_other_arms_regions_hold_their_ray(ctx: RecordingContext, links, limits_deg) -> None:
    spec = DexterityMapSpec.model_validate(
        {"links": links, "joint_limits_deg": limits_deg, "grid": {"points_per_axis": 3}}
    )
    result = run_dexterity_map(spec, ctx).result
    for region in result["regions"][:3]:
        if region["d_z_min"] is None:
            continue
        distances = np.linspace(region["d_from"], region["d_to"], 2001)
        points = np.stack([distances, np.zeros_like(distances)], axis=-1)
        d_z = exact_limited_orientation_dexterity(links, points, np.radians(limits_deg))
        assert region["d_z_min"] <= d_z.min() + 1e-10 and region["d_z_max"] >= d_z.max() - 1e-10
        assert region["d_z_min"] >= d_z.min() - 0.02  # not the unlimited arm's
    assert result["areas"]["unlimited_reference"]["regions"] == region_table(links)


# -- other inputs (figures built, not rendered) ----------------------------------------


def run(ctx: RecordingContext, **inputs: Any) -> JobOutcome:
    spec = DexterityMapSpec.model_validate({"links": [15, 14, 8], **inputs})
    return run_dexterity_map(spec, ctx)


@pytest.mark.usefixtures("fast_figures")
def test_exact_map_reports_progress_by_row_blocks(ctx: RecordingContext) -> None:
    run(ctx, grid={"points_per_axis": 41})
    grid_reports = [p for p, message in ctx.reports if message == "dexterity map"]
    assert len(grid_reports) == 10
    assert grid_reports == sorted(grid_reports) and grid_reports[-1] == pytest.approx(80.0)


@pytest.mark.usefixtures("fast_figures")
def test_sampled_map_reports_progress_by_chunk(ctx: RecordingContext) -> None:
    # 2**22 elements per chunk / 3600 samples = 1165 points: 2 chunks for 41 x 41 nodes.
    run(ctx, grid={"points_per_axis": 41}, joint_limits_deg=[[-90, 90]] * 3,
        orientation_step_deg=0.1, method="orientation-sampling")  # fmt: skip
    grid_reports = [p for p, message in ctx.reports if message == "dexterity map"]
    assert len(grid_reports) == 2


@pytest.mark.usefixtures("fast_figures")
def test_exact_map_under_limits_reports_progress_by_chunk(ctx: RecordingContext) -> None:
    # 2048 points per chunk: 3 chunks for 65 x 65 = 4225 nodes
    outcome = run(ctx, grid={"points_per_axis": 65}, joint_limits_deg=[[-90, 90]] * 3,
                  orientation_step_deg=0.1)  # fmt: skip
    grid_reports = [p for p, message in ctx.reports if message == "dexterity map"]
    assert len(grid_reports) == 3
    assert grid_reports == sorted(grid_reports) and grid_reports[-1] == pytest.approx(80.0)
    # the step was given but the exact method does not use it: a note says so
    assert "orientation_step_deg is not used by this method" in "\n".join(outcome.notes)


@pytest.mark.usefixtures("fast_figures")
def test_given_bounds_and_no_task_points(ctx: RecordingContext) -> None:
    outcome = run(ctx, grid={"bounds": [0, 10, -5, 5], "points_per_axis": 3}, length_unit="mm")
    result = outcome.result
    assert result["discretisation"]["grid"] == {
        "bounds": [0.0, 10.0, -5.0, 5.0], "points_per_axis": 3, "step": [5.0, 5.0]
    }  # fmt: skip
    assert result["length_unit"] == "mm"
    assert result["task_points"] == [] and result["trajectory"] is None
    csv_text = artifact(outcome, "dexterity_map.csv").decode()
    assert csv_text.splitlines()[1] == "0,-5,5,1,0.333333333333,1"


@pytest.mark.usefixtures("fast_figures")
def test_full_turn_limits_use_the_closed_form(ctx: RecordingContext) -> None:
    outcome = run(ctx, grid={"points_per_axis": 5}, joint_limits_deg=[[-180, 180]] * 3,
                  task_points=[[12, 8]])  # fmt: skip
    assert outcome.result["method"] == "exact-closed-form"
    assert outcome.result["joint_limits_deg"] == [[-180.0, 180.0]] * 3
    assert outcome.result["task_points"][0]["d_z"] == 1.0
    assert any("full turn" in note for note in outcome.all_notes)


@pytest.mark.usefixtures("fast_figures")
def test_polyline_trajectory_and_shortfalls(ctx: RecordingContext) -> None:
    outcome = run(ctx, grid={"points_per_axis": 5}, task_points=[[30, 0], [0, 0], [40, 0]],
                  trajectory={"points": [[0, 0], [30, 0], [40, 0]], "samples": 41})  # fmt: skip
    result = outcome.result
    assert [e["region"] for e in result["task_points"]] == [3, 1, 4]
    assert [e["label"] for e in result["task_points"]] == ["A", "B", "C"]
    assert result["task_points"][1]["d_z"] == 1.0
    assert result["task_points"][2]["d_z"] == 0.0
    trajectory = result["trajectory"]
    assert trajectory["samples"] == 41
    # samples every 1 unit along the x axis from 0 to 40: d_z = 1 on [0, 7] and [9, 21]
    assert trajectory["fully_dexterous_fraction"] == pytest.approx(21 / 41)
    assert trajectory["d_z_min"] == 0.0
    notes = "\n".join(outcome.all_notes)
    assert "task point A (30, 0) has d_z" in notes and "task point C (40, 0)" in notes
    assert "task point B" not in notes
    assert "fully dexterous at 51.2% of its 41 samples" in notes


@pytest.mark.usefixtures("fast_figures")
def test_many_shortfalls_are_summarised(ctx: RecordingContext) -> None:
    points = [[30 + 0.1 * i, 0] for i in range(25)]
    outcome = run(ctx, grid={"points_per_axis": 3}, task_points=points)
    shortfalls = [n for n in outcome.all_notes if "task point" in n]
    assert len(shortfalls) == 21
    assert shortfalls[-1].startswith("5 more task points have d_z < 1")


@pytest.mark.usefixtures("fast_figures")
def test_swapped_links_have_an_empty_region_2(ctx: RecordingContext) -> None:
    spec = DexterityMapSpec.model_validate({"links": [15, 8, 14], "grid": {"points_per_axis": 3}})
    outcome = run_dexterity_map(spec, ctx)
    region_1, region_2, region_3, _ = outcome.result["regions"]
    assert outcome.result["full_dexterity_bands"] == [[0.0, 7.0]]
    assert region_1["fully_dexterous_bands"] == [[0.0, 7.0]]
    assert region_2["d_from"] == region_2["d_to"] == 14.0
    assert region_2["corrected"].startswith("empty") and region_2["d_z_min"] is None
    assert region_3["corrected"].startswith("d_z < 1 throughout")
    assert outcome.result["areas"]["fully_dexterous"] == pytest.approx(49 * math.pi)
    # the paper's Example 1, Case 2 arm: its printed band is wrong
    notes = "\n".join(outcome.all_notes)
    assert "8 < d <= 16" in notes and "0.035793 vs 0.298758" in notes


@pytest.mark.usefixtures("fast_figures")
def test_example_2_design_under_the_papers_limits(ctx: RecordingContext) -> None:
    points = [[16, 19], [18, 0], [-8, -25], [-15, 11], [-10, 16], [20, -21], [-7, 27]]
    spec = DexterityMapSpec.model_validate(
        {"links": [23, 22, 15], "joint_limits_deg": [list(p) for p in PAPER_JOINT_LIMITS_DEG],
         "task_points": points, "grid": {"points_per_axis": 3}}
    )  # fmt: skip
    outcome = run_dexterity_map(spec, ctx)
    found = {e["label"]: e["d_z"] for e in outcome.result["task_points"]}
    expected = {"A": 0.8955, "B": 0.7766, "C": 0.8630, "D": 0.7840, "E": 0.7874, "F": 1.0,
                "G": 0.9805}  # fmt: skip
    assert found == pytest.approx(expected, abs=6e-5)
    notes = "\n".join(outcome.all_notes)
    assert "three task points" in notes and "1 (F) has d_z = 1" in notes


def test_polyline_samples_are_even_in_arc_length() -> None:
    spec = PolylineTrajectory(points=((0.0, 0.0), (3.0, 0.0), (3.0, 4.0)), samples=8)
    samples = trajectory_samples(spec)
    steps = np.hypot(*np.diff(samples, axis=0).T)
    # length 7 in 7 equal steps: the corner (3, 0) is a sample
    np.testing.assert_allclose(steps, 1.0)
    np.testing.assert_allclose(samples[[0, 3, 7]], [[0, 0], [3, 0], [3, 4]])
    np.testing.assert_array_equal(trajectory_path(spec), [[0, 0], [3, 0], [3, 4]])


def test_polynomial_samples_are_even_in_x() -> None:
    spec = PolynomialTrajectory(polynomial=(1.0, 0.0, 0.0), x_start=2.0, x_end=0.0, samples=3)
    np.testing.assert_allclose(trajectory_samples(spec), [[2, 4], [1, 1], [0, 0]])
    assert trajectory_path(spec).shape == (400, 2)


def test_plots_false_gives_data_files_only(ctx: RecordingContext) -> None:
    from worker.families.planar_serial.jobs.synthesis import run_synthesis
    from worker.families.planar_serial.specs import SynthesisSpec

    spec = DexterityMapSpec.model_validate(
        {"links": [15, 14, 8], "grid": {"points_per_axis": 11}, "plots": False}
    )
    outcome = run_dexterity_map(spec, ctx)
    assert {a.name for a in outcome.artifacts} == {"dexterity_map.csv", "dexterity_map.npz"}
    synth = SynthesisSpec.model_validate(
        {
            "task_points": [[16, 19], [18, 0]],
            "l3": 15,
            "grid": {"points_per_axis": 11},
            "plots": False,
        }
    )
    outcome = run_synthesis(synth, ctx)
    assert [a.name for a in outcome.artifacts] == ["synthesis_cases.npz"]


# -- issue 26, finding 4: an empty map, or a task point out of reach, is flagged ------


@pytest.mark.usefixtures("fast_figures")
def test_an_empty_map_says_so_first(ctx: RecordingContext) -> None:
    # 2 x 2 nodes at the corners of the default grid, all beyond the reach 37
    outcome = run(ctx, grid={"points_per_axis": 2}, task_points=[[10, 0]])
    summary = outcome.result["summary"]
    assert summary["reachable_points"] == 0 and summary["d_z_max"] == 0.0
    (warning,) = summary["warnings"]
    assert warning.startswith("The map is empty: no node of the grid")
    assert "d_z = 0 at all 4 nodes" in warning and "more points_per_axis" in warning
    assert outcome.all_notes[0] == warning
    assert summary["unreachable_task_points"] == []


@pytest.mark.usefixtures("fast_figures")
def test_an_empty_map_under_joint_limits_names_them(ctx: RecordingContext) -> None:
    # th1 and th2 locked at 0: the wrist stays at (29, 0), so no node has d_z > 0
    limits = [[0, 0], [0, 0], [-180, 180]]
    outcome = run(ctx, grid={"points_per_axis": 21}, joint_limits_deg=limits)
    result = outcome.result
    assert result["summary"]["reachable_points"] == 0
    (warning,) = result["summary"]["warnings"]
    assert "The map is empty" in warning and "[[0.0, 0.0], [0.0, 0.0], [-180.0, 180.0]]" in warning
    assert outcome.all_notes[0] == warning
    assert all(region["d_z_max"] == 0.0 for region in result["regions"])
    assert result["full_dexterity_bands"] == []


@pytest.mark.usefixtures("fast_figures")
def test_a_task_point_out_of_reach_is_a_warning(ctx: RecordingContext) -> None:
    outcome = run(ctx, grid={"points_per_axis": 5}, task_points=[[12, 8], [40, 0], [0, 50]])
    summary = outcome.result["summary"]
    assert summary["unreachable_task_points"] == ["B", "C"]
    (warning,) = summary["warnings"]
    assert warning.startswith("Task points B (40, 0), C (0, 50) are out of reach (d_z = 0)")
    assert outcome.all_notes[0] == warning
    assert "task point B (40, 0) has d_z = 0.0000 < 1" in "\n".join(outcome.all_notes)
