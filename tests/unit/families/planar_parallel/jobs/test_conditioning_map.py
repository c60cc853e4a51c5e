"""The planar2dof-conditioning-map job: the paper's Figs 4-5 and Table I designs, end to end."""

from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np
import pytest

from tests.unit.common.test_figures import png_pixels, svg_strings
from tests.unit.families.conftest import RecordingContext, unrendered_artifacts
from worker.contract import JobOutcome
from worker.families.planar_parallel import CONDITIONING_MAP
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.examples import CONDITIONING_MAP_EXAMPLES
from worker.families.planar_parallel.jobs import conditioning_map
from worker.families.planar_parallel.jobs.conditioning_map import run_conditioning_map
from worker.families.planar_parallel.specs import ConditioningMapSpec

RESULT_KEYS = {
    "actuation", "l1", "l2", "e", "delta", "architecture", "working_mode", "length_unit",
    "isotropic_point", "summary", "w_kappa0", "points", "discretisation", "data",
}  # fmt: skip
POINT_KEYS = {
    "x", "y", "reachable", "inverse_condition", "pressure_angles_deg",
    "min_pressure_angle_deg", "joint_angles_deg", "joint_displacements",
}  # fmt: skip
ARTIFACTS = {
    "inverse_condition_map.png": "image/png",
    "inverse_condition_map.svg": "image/svg+xml",
    "pressure_angle_map.png": "image/png",
    "pressure_angle_map.svg": "image/svg+xml",
    "conditioning_map.csv": "text/csv",
    "conditioning_map.npz": "application/x-npz",
}
#: The CSV's columns, each with its unit; the last two name the actuated joints'
#: quantity: an arm's angle, a leg's length or a slider's position.
CSV_COLUMNS = [
    "x [units]", "y [units]", "reachable [-]", "inverse_condition [-]",
    "pressure_angle_1 [deg]", "pressure_angle_2 [deg]", "min_pressure_angle [deg]",
]  # fmt: skip
JOINT_COLUMNS = {
    "proximal-arm": ["joint_1_angle [deg]", "joint_2_angle [deg]"],
    "telescopic-leg": ["leg_1_length [units]", "leg_2_length [units]"],
    "linear-drive": ["slider_1_position [units]", "slider_2_position [units]"],
}
#: docs/methods/planar-parallel.md: point values (1/kappa, angles) to 1e-6.
POINT_TOL = 1e-6
SQRT_HALF = math.sqrt(0.5)


@contextmanager
def unrendered_figures() -> Iterator[None]:
    """Figures built (their inputs checked) but not rendered, like ``fast_figures``."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(conditioning_map, "figure_artifacts", unrendered_artifacts)
        yield


@pytest.fixture
def fast_figures(fast_figures: None, monkeypatch: pytest.MonkeyPatch) -> None:
    """The shared fixture, extended to this job's module."""
    monkeypatch.setattr(conditioning_map, "figure_artifacts", unrendered_artifacts)


def run_example(index: int) -> tuple[JobOutcome, RecordingContext]:
    ctx = RecordingContext()
    spec = ConditioningMapSpec.model_validate(dict(CONDITIONING_MAP_EXAMPLES[index].inputs))
    return CONDITIONING_MAP.run(spec, ctx), ctx


@pytest.fixture(scope="module")
def examples() -> dict[int, tuple[JobOutcome, RecordingContext]]:
    """Every worked example but the first, with figures built and not rendered."""
    with unrendered_figures():
        return {i: run_example(i) for i in range(1, len(CONDITIONING_MAP_EXAMPLES))}


@pytest.fixture(scope="module")
def rendered() -> tuple[JobOutcome, RecordingContext]:
    """Figs 4-5(a), delta = 1.5, fully rendered."""
    return run_example(0)


def example(
    index: int, examples: dict[int, tuple[JobOutcome, RecordingContext]],
    rendered: tuple[JobOutcome, RecordingContext],
) -> tuple[JobOutcome, RecordingContext]:  # fmt: skip
    return rendered if index == 0 else examples[index]


def artifact(outcome: JobOutcome, name: str) -> bytes:
    return next(a.data for a in outcome.artifacts if a.name == name)


def reference_values(
    arch: pp.Architecture, point: tuple[float, float], mode: tuple[int, int]
) -> tuple[float, list[float], list[float]]:
    """1/kappa by the SVD of J = A^-1 B, pressure angles and th_1i (deg) of a proximal arm,
    by elementary trigonometry (independent of the kinematics' trig-free kernel)."""
    l1, l2, e = arch.l1, arch.l2, arch.e
    rows, diagonal, angles, joints = [], [], [], []
    for sign, m in zip((1.0, -1.0), mode, strict=True):
        px, py = point[0] - sign * e, point[1]
        rho = math.hypot(px, py)
        theta = math.atan2(py, px) + m * math.acos((rho**2 + l1**2 - l2**2) / (2 * l1 * rho))
        u = np.array([math.cos(theta), math.sin(theta)])
        w = (np.array([px, py]) - l1 * u) / l2
        rows.append(w)
        diagonal.append(l1 * (w[0] * -u[1] + w[1] * u[0]))  # l1 w^T Q u
        angles.append(math.degrees(math.acos(min(1.0, abs(float(u @ w))))))
        joints.append(math.degrees(math.atan2(math.sin(theta), math.cos(theta))))
    jac = np.array(rows) / np.array(diagonal)[:, None]
    sigma = np.linalg.svd(jac, compute_uv=False)
    return float(sigma[1] / sigma[0]), angles, joints


# -- every worked example ---------------------------------------------------------------

INDICES = list(range(len(CONDITIONING_MAP_EXAMPLES)))


@pytest.mark.parametrize("index", INDICES)
def test_progress_rises_to_the_end(index: int, examples: Any, rendered: Any) -> None:
    _, ctx = example(index, examples, rendered)
    assert ctx.percents == sorted(ctx.percents)
    assert ctx.percents[-1] == 100.0 and len(ctx.percents) >= 10
    assert all(message for _, message in ctx.reports)
    assert [m for _, m in ctx.reports].count("conditioning map") == 10


@pytest.mark.parametrize("index", INDICES)
def test_result_document(index: int, examples: Any, rendered: Any) -> None:
    outcome, _ = example(index, examples, rendered)
    result = outcome.result
    assert set(result) == RESULT_KEYS
    json.dumps(result, allow_nan=False)
    assert result["data"] == {"csv": "conditioning_map.csv", "npz": "conditioning_map.npz"}
    assert result["discretisation"]["grid"]["points_per_axis"] == 301
    assert result["discretisation"]["w_kappa0"]["columns"] == 801
    assert result["w_kappa0"]["found"] is True
    assert all(set(entry) == POINT_KEYS for entry in result["points"])


@pytest.mark.parametrize("index", INDICES)
def test_artifacts_and_data(index: int, examples: Any, rendered: Any) -> None:
    outcome, _ = example(index, examples, rendered)
    assert {a.name: a.media_type for a in outcome.artifacts} == ARTIFACTS
    text = artifact(outcome, "conditioning_map.csv").decode()
    rows = list(csv.reader(io.StringIO(text)))
    assert rows[0] == CSV_COLUMNS + JOINT_COLUMNS[outcome.result["actuation"]]
    assert len(rows) - 1 == 301**2
    data = np.genfromtxt(io.StringIO(text), delimiter=",", skip_header=1)
    with np.load(io.BytesIO(artifact(outcome, "conditioning_map.npz"))) as npz:
        assert npz["inverse_condition"].shape == (301, 301)
        np.testing.assert_allclose(data[:301, 0], npz["x"], rtol=1e-11)
        np.testing.assert_allclose(data[::301, 1], npz["y"], rtol=1e-11)
        np.testing.assert_array_equal(data[:, 2], npz["reachable"].ravel())
        np.testing.assert_allclose(data[:, 3], npz["inverse_condition"].ravel(), rtol=1e-11,
                                   atol=1e-12, equal_nan=True)  # fmt: skip
        np.testing.assert_allclose(data[:, 6], npz["min_pressure_angle_deg"].ravel(),
                                   rtol=1e-11, equal_nan=True)  # fmt: skip
        assert npz["w_kappa0_boundary_0"].shape[1] == 2
        axes, units = json.loads(str(npz["axes"])), json.loads(str(npz["units"]))
        assert axes["inverse_condition"] == ["y", "x"]
        assert axes["pressure_angles_deg"] == ["y", "x", "chain"]
        assert set(units) == set(npz.files) - {"axes", "units", "metadata"}
        assert units["x"] == "units" and units["pressure_angles_deg"] == "deg"
        meta = json.loads(str(npz["metadata"]))
        assert meta["process"] == "planar2dof-conditioning-map"
        assert meta["inputs"]["actuation"] == outcome.result["actuation"]


@pytest.mark.parametrize("index", INDICES)
def test_map_is_the_kinematics_map(index: int, examples: Any, rendered: Any) -> None:
    outcome, _ = example(index, examples, rendered)
    spec = ConditioningMapSpec.model_validate(dict(CONDITIONING_MAP_EXAMPLES[index].inputs))
    with np.load(io.BytesIO(artifact(outcome, "conditioning_map.npz"))) as npz:
        l1, l2, e = npz["architecture_l1_l2_e"]
        arch = pp.Architecture(spec.actuation, float(l1), float(l2), float(e))
        expected = pp.conditioning_map(arch, npz["x"], npz["y"], spec.working_mode)
        np.testing.assert_array_equal(npz["inverse_condition"], expected.inverse_condition)
        np.testing.assert_array_equal(npz["reachable"], expected.reachable)
        summary = outcome.result["summary"]
        assert summary["reachable_points"] == int(expected.reachable.sum())
        assert summary["inverse_condition"]["max"] == pytest.approx(
            np.nanmax(expected.inverse_condition)
        )


def test_rendered_figures(rendered: tuple[JobOutcome, RecordingContext]) -> None:
    outcome, _ = rendered
    assert all(a.data for a in outcome.artifacts)
    for stem, label in (("inverse_condition_map", r"conditioning index $1/\kappa$ (eq 7)"),
                        ("pressure_angle_map",
                         r"minimum pressure angle $\beta_{\min}$ (eq 15) [°]")):  # fmt: skip
        png_pixels(artifact(outcome, f"{stem}.png"))
        strings = svg_strings(artifact(outcome, f"{stem}.svg"))
        assert {"x [units]", "y [units]", label} <= set(strings)
        assert r"boundary of $W_{\kappa 0}$: $1/\kappa = 0.5$" in strings
        assert any("proximal-arm robot" in s for s in strings)


# -- Figs 4-5: the isotropic designs delta = 1.5, 2.0, 2.5 -------------------------------


@pytest.mark.parametrize(("index", "delta"), [(0, 1.5), (1, 2.0), (2, 2.5)])
def test_figure_4_designs(index: int, delta: float, examples: Any, rendered: Any) -> None:
    result = example(index, examples, rendered)[0].result
    assert result["architecture"] == "isotropic" and result["delta"] == delta
    assert result["e"] == pytest.approx(SQRT_HALF * (delta - 1.0), abs=1e-15)
    iso = result["isotropic_point"]
    assert iso["x"] == 0.0 and iso["y"] == pytest.approx(-SQRT_HALF * (1.0 + delta))
    assert iso["inverse_condition"] == pytest.approx(1.0, abs=POINT_TOL) and iso["isotropic"]
    region = result["w_kappa0"]
    assert region["inverse_condition_limit"] == 0.5
    assert region["boundary"] and len(region["boundary"][0][0]) == 2
    assert region["area"] <= region["area_grid"] * 1.01
    assert region["below_resolution"] is False
    assert region["largest_inverse_condition"]["value"] == pytest.approx(1.0, abs=1e-5)
    assert_message_quotes_the_areas(region)


def assert_message_quotes_the_areas(region: dict[str, Any]) -> None:
    """The message names both areas, with the values the entry publishes."""
    assert f"area {region['area']:.6g}, " in region["message"]
    assert f"rectangle_region_area {region['rectangle_region_area']:.6g} " in region["message"]


def test_w_kappa0_shrinks_with_delta(examples: Any, rendered: Any) -> None:
    # the paper: the area bounded by a given 1/kappa0 decreases with delta, less so past 2
    areas = [example(i, examples, rendered)[0].result["w_kappa0"]["area_grid"] for i in (0, 1, 2)]
    assert areas[0] > areas[1] > areas[2]
    assert areas[0] - areas[1] > areas[1] - areas[2]


def test_column_description_matches_the_grid_past_delta_2(examples: Any) -> None:
    for index in (1, 2):
        region = examples[index][0].result["w_kappa0"]
        assert region["area"] == pytest.approx(region["area_grid"], rel=0.01)
        assert region["undescribed_area_grid"] < 0.005 * region["area_grid"]
        assert not any("above a gap" in note for note in examples[index][0].all_notes)


def test_delta_1_5_has_overhangs_noted(rendered: tuple[JobOutcome, RecordingContext]) -> None:
    outcome, _ = rendered
    region = outcome.result["w_kappa0"]
    assert region["undescribed_area_grid"] > 0.03 * region["area_grid"]
    # The lowest runs plus the overhangs are the whole set, which 'area' is (METHODS §2).
    assert region["rectangle_region_area"] + region["undescribed_area_grid"] == pytest.approx(
        region["area_grid"], rel=0.01
    )
    assert region["area"] == pytest.approx(region["area_grid"], rel=0.01)
    assert region["area"] > 1.03 * region["rectangle_region_area"]
    assert any("above a gap in some columns" in note for note in outcome.all_notes)
    assert any("more than the lowest run of each column" in n for n in outcome.all_notes)


def test_default_grid_holds_the_reachable_workspace(examples: Any) -> None:
    result = examples[1][0].result  # delta = 2.0
    reach, e = 3.0, SQRT_HALF
    assert result["discretisation"]["grid"]["bounds"] == pytest.approx(
        [-1.03 * (reach - e), 1.03 * (reach - e), -1.03 * reach, 1.03 * reach]
    )


# -- Table I designs with the paper's rectangle corners ---------------------------------


def test_table_i_30_corners(examples: Any) -> None:
    outcome = examples[3][0]
    points = outcome.result["points"]
    assert [(p["x"], p["y"]) for p in points] == [
        (-1.4644, -0.9395), (1.4644, -0.9395), (1.4644, -1.6717), (-1.4644, -1.6717)
    ]  # fmt: skip
    # docs/methods/planar-parallel.md: min 1/kappa on the paper's 30° rectangle is 0.486 < 0.526, at
    # the corners
    assert points[2]["inverse_condition"] == pytest.approx(0.486, abs=5e-4)
    assert points[2]["inverse_condition"] == pytest.approx(points[3]["inverse_condition"])
    notes = "\n".join(outcome.all_notes)
    assert "does not lie inside its W_kappa0: min 1/kappa on it is 0.4859" in notes
    assert "vs the limit 0.526" in notes


def test_table_i_35_e_erratum(examples: Any) -> None:
    outcome = examples[4][0]
    assert outcome.result["e"] == pytest.approx(0.6010407640085655, abs=1e-12)
    notes = "\n".join(outcome.all_notes)
    assert "Table I prints e = 0.6001 for delta = 1.85" in notes and "0.6010" in notes


@pytest.mark.parametrize("index", [3, 4])
def test_point_values_against_an_independent_computation(index: int, examples: Any) -> None:
    outcome = examples[index][0]
    arch = pp.isotropic_architecture(outcome.result["l2"])
    for entry in outcome.result["points"]:
        value, angles, joints = reference_values(arch, (entry["x"], entry["y"]), (1, -1))
        assert entry["reachable"] is True
        assert entry["inverse_condition"] == pytest.approx(value, abs=POINT_TOL)
        assert entry["pressure_angles_deg"] == pytest.approx(angles, abs=POINT_TOL)
        assert entry["min_pressure_angle_deg"] == pytest.approx(min(angles), abs=POINT_TOL)
        assert entry["joint_angles_deg"] == pytest.approx(joints, abs=POINT_TOL)
        assert entry["joint_displacements"] is None


# -- the telescopic-leg example ----------------------------------------------------------


def test_telescopic_legs(examples: Any) -> None:
    outcome = examples[5][0]
    result = outcome.result
    assert result["actuation"] == "telescopic-leg" and result["delta"] is None
    assert result["isotropic_point"] == pytest.approx(
        {"x": 0.0, "y": -0.5, "inverse_condition": 1.0, "min_pressure_angle_deg": 90.0,
         "isotropic": True, "degenerate": False}
    )  # fmt: skip
    assert result["summary"]["min_pressure_angle_deg"] == {"min": 90.0, "max": 90.0,
                                                           "mean": 90.0}  # fmt: skip
    # W_kappa0 is two lobes: 'area' is both, the column-wise boundary the lower one
    region = result["w_kappa0"]
    assert region["area"] == pytest.approx(region["area_grid"], rel=0.02)
    assert region["rectangle_region_area"] == pytest.approx(region["area_grid"] / 2, rel=0.02)
    notes = "\n".join(outcome.all_notes)
    assert "both pressure angles are 90° everywhere" in notes and "above a gap" in notes


# -- other inputs (figures built, not rendered) ------------------------------------------


def run(ctx: RecordingContext, **inputs: Any) -> JobOutcome:
    spec = ConditioningMapSpec.model_validate({"grid": {"points_per_axis": 41}, **inputs})
    return run_conditioning_map(spec, ctx)


@pytest.mark.usefixtures("fast_figures")
def test_isotropic_point_as_a_given_point(ctx: RecordingContext) -> None:
    h = SQRT_HALF * 2.7
    outcome = run(ctx, l2=1.7, architecture="isotropic", points=[[0.0, -h]])
    (entry,) = outcome.result["points"]
    # docs/methods/planar-parallel.md: at (0, -H) th11 = -45°, th12 = -135°, 1/kappa = 1, links
    # perpendicular
    assert entry["inverse_condition"] == pytest.approx(1.0, abs=POINT_TOL)
    assert entry["joint_angles_deg"] == pytest.approx([-45.0, -135.0], abs=POINT_TOL)
    assert entry["pressure_angles_deg"] == pytest.approx([90.0, 90.0], abs=POINT_TOL)
    assert outcome.result["w_kappa0"] is None
    assert outcome.result["discretisation"]["w_kappa0"] is None


@pytest.mark.usefixtures("fast_figures")
def test_eq_17_point_has_the_allowable_pressure_angle(ctx: RecordingContext) -> None:
    limit, delta = pp.max_condition_limit(30.0)
    e = SQRT_HALF * (delta - 1.0)
    y0 = -math.sqrt(1 + delta**2 - 2 * delta * math.cos(math.radians(30.0)))
    outcome = run(ctx, l2=delta, architecture="isotropic", points=[[e, y0], [-e, y0]])
    first, second = outcome.result["points"]
    assert first["pressure_angles_deg"][0] == pytest.approx(30.0, abs=POINT_TOL)
    assert second["pressure_angles_deg"][1] == pytest.approx(30.0, abs=POINT_TOL)
    assert first["inverse_condition"] == pytest.approx(0.52555, abs=1e-4)
    assert first["inverse_condition"] == pytest.approx(limit, abs=1e-12)


@pytest.mark.usefixtures("fast_figures")
def test_unreachable_points_are_null_and_noted(ctx: RecordingContext) -> None:
    outcome = run(ctx, l2=1.5, e=0.3, points=[[0.0, -1.5], [5.0, 5.0], [0.0, 0.0]],
                  length_unit="mm")  # fmt: skip
    entries = outcome.result["points"]
    assert [e["reachable"] for e in entries] == [True, False, False]
    assert entries[1]["inverse_condition"] is None and entries[1]["joint_angles_deg"] is None
    assert outcome.result["architecture"] == "given" and outcome.result["e"] == 0.3
    notes = "\n".join(outcome.all_notes)
    assert "2 of the 3 given points are out of reach in working mode [+1, -1]" in notes
    assert "#2 (5, 5), #3 (0, 0)" in notes


@pytest.mark.usefixtures("fast_figures")
def test_another_working_mode_has_no_isotropic_point(ctx: RecordingContext) -> None:
    # coincident actuated joints (e = 0): w1 and w2 are never perpendicular on x = 0
    outcome = run(ctx, l2=1.5, e=0.0, working_mode=[-1, 1])
    iso = outcome.result["isotropic_point"]
    assert iso["isotropic"] is False and iso["degenerate"] is False
    assert iso["inverse_condition"] == pytest.approx(0.894427191, abs=1e-6)  # 2/√5
    assert outcome.result["working_mode"] == [-1, 1]
    assert any("No isotropic point (1/kappa = 1) in working mode [-1, +1]" in n
               for n in outcome.all_notes)  # fmt: skip


@pytest.mark.usefixtures("fast_figures")
def test_folded_links_are_not_an_isotropic_point(ctx: RecordingContext) -> None:
    # Mode [+1, +1]: 1/kappa on x = 0 peaks where both links fold (beta = 0, v1 = v2 = 0):
    # eq (9) gives 1/kappa -> 1 with sigma -> infinity, the paper's right triangle (Fig. 3).
    outcome = run(ctx, l2=1.5, architecture="isotropic", working_mode=[1, 1])
    iso = outcome.result["isotropic_point"]
    assert iso["degenerate"] is True and iso["isotropic"] is False
    assert iso["inverse_condition"] == pytest.approx(1.0, abs=1e-6)
    assert iso["min_pressure_angle_deg"] < 1.0
    assert any("is where the links fold" in n for n in outcome.all_notes)


@pytest.mark.usefixtures("fast_figures")
def test_linear_drive(ctx: RecordingContext) -> None:
    outcome = run(ctx, actuation="linear-drive", l2=2.0, inverse_condition_limit=0.5,
                  points=[[0.3, -1.0]])  # fmt: skip
    result = outcome.result
    assert result["e"] is None and result["delta"] is None
    assert result["isotropic_point"]["y"] == pytest.approx(-math.sqrt(2.0))
    (entry,) = result["points"]
    # sliders at x +- sqrt(l2² - y²); pressure angles acos(|y| / l2) = 60°
    assert entry["joint_displacements"] == pytest.approx([0.3 + math.sqrt(3), 0.3 - math.sqrt(3)])
    assert entry["pressure_angles_deg"] == pytest.approx([60.0, 60.0], abs=POINT_TOL)
    assert entry["joint_angles_deg"] is None
    bounds = result["discretisation"]["grid"]["bounds"]
    assert bounds == pytest.approx([-4.12, 4.12, -2.06, 2.06])
    assert any("1/kappa does not depend on x" in n for n in outcome.all_notes)


@pytest.mark.usefixtures("fast_figures")
def test_given_bounds_and_an_empty_w_kappa0(ctx: RecordingContext) -> None:
    outcome = run(ctx, l2=1.5, architecture="isotropic", inverse_condition_limit=0.9,
                  grid={"bounds": [3, 4, 3, 4], "points_per_axis": 5})  # fmt: skip
    result = outcome.result
    assert result["discretisation"]["grid"] == {
        "bounds": [3.0, 4.0, 3.0, 4.0], "points_per_axis": 5, "step": [0.25, 0.25]
    }  # fmt: skip
    assert result["summary"]["reachable_points"] == 0
    assert result["summary"]["inverse_condition"] == {"min": None, "max": None, "mean": None}
    assert result["w_kappa0"]["found"] is True  # the region exists, off this grid
    assert result["w_kappa0"]["area_grid"] == 0.0
    assert any("No grid node is reachable" in note for note in outcome.all_notes)


@pytest.mark.usefixtures("fast_figures")
def test_a_thin_w_kappa0_is_found_and_noted(ctx: RecordingContext) -> None:
    # issue 26: the largest 1/kappa is 0.54941 at (0, +-2.3148), where both links fold; the
    # set is two wedges there of about 1.5e-4 each (brute force: test_kappa_region.py)
    outcome = run(ctx, l1=2.229, l2=4.8702, e=1.2718, working_mode=[-1, -1],
                  inverse_condition_limit=0.543, grid={"points_per_axis": 201})  # fmt: skip
    region = outcome.result["w_kappa0"]
    assert region["found"] is True
    assert region["area"] == pytest.approx(2.981e-4, rel=3e-3)
    assert region["rectangle_region_area"] == pytest.approx(2.426e-4, rel=3e-3)
    assert region["largest_inverse_condition"]["value"] == pytest.approx(0.549413, abs=1e-6)
    assert region["below_resolution"] is True
    assert region["boundary"]
    assert_message_quotes_the_areas(region)
    reachable = outcome.result["summary"]["reachable_area_grid"]
    assert region["area"] < 1e-4 * reachable
    notes = "\n".join(outcome.all_notes)
    assert "W_kappa0 is below the resolution" in notes and "W_kappa0 is empty" not in notes
    assert outcome.result["discretisation"]["w_kappa0"]["columns_added"] > 0


@pytest.mark.usefixtures("fast_figures")
def test_a_limit_above_the_largest_inverse_condition_is_empty(ctx: RecordingContext) -> None:
    outcome = run(ctx, l1=2.229, l2=4.8702, e=1.2718, working_mode=[-1, -1],
                  inverse_condition_limit=0.5495)  # fmt: skip
    region = outcome.result["w_kappa0"]
    assert region["found"] is False and region["area"] == 0.0 and not region["below_resolution"]
    notes = "\n".join(outcome.all_notes)
    assert "W_kappa0 is empty" in notes and "the largest 1/kappa is 0.5494128" in notes


@pytest.mark.usefixtures("fast_figures")
def test_an_empty_w_kappa0_is_noted(ctx: RecordingContext) -> None:
    # telescopic legs from one pivot (e = 0) are parallel everywhere: 1/kappa = 0
    outcome = run(ctx, actuation="telescopic-leg", e=0.0, inverse_condition_limit=0.5)
    region = outcome.result["w_kappa0"]
    assert region["found"] is False and region["area"] == 0.0 and region["boundary"] == []
    assert region["largest_inverse_condition"] is None
    assert outcome.result["isotropic_point"] is None
    assert outcome.result["summary"]["inverse_condition"]["max"] == 0.0
    notes = "\n".join(outcome.all_notes)
    assert "W_kappa0 is empty" in notes and "no isotropic point" in notes


def test_plots_false_gives_data_files_only(ctx: RecordingContext) -> None:
    outcome = run(ctx, l2=1.5, architecture="isotropic", plots=False)
    assert [a.name for a in outcome.artifacts] == ["conditioning_map.csv", "conditioning_map.npz"]
    assert ctx.percents[-1] == 100.0 and "plots" not in [m for _, m in ctx.reports]
