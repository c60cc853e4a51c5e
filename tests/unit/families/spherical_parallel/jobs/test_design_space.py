"""The spm-design-space job: the paper's Figs 5-6 and Example III's design space."""

from __future__ import annotations

import csv
import io
import json
import math
from typing import Any

import numpy as np
import pytest

from tests.unit.families.conftest import RecordingContext, unrendered_artifacts
from worker.common.figures import figure_artifacts
from worker.contract import JobOutcome
from worker.families.spherical_parallel import DESIGN_SPACE
from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.examples import (
    DESIGN_SPACE_EXAMPLES,
    FIG_5_F_MAX,
    FIG_5_F_MIN,
)
from worker.families.spherical_parallel.jobs import design_space
from worker.families.spherical_parallel.specs import DesignSpaceSpec

RESULT_KEYS = {"workspace", "identical_platforms", "gamma_deg", "method", "designs", "summary",
               "index_map", "sampling", "data"}  # fmt: skip


@pytest.fixture(scope="module")
def unrendered() -> Any:
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(design_space, "figure_artifacts", unrendered_artifacts)
        yield


def run(inputs: dict[str, Any]) -> tuple[JobOutcome, RecordingContext]:
    ctx = RecordingContext()
    return DESIGN_SPACE.run(DesignSpaceSpec.model_validate(inputs), ctx), ctx


@pytest.fixture(scope="module")
def fig_5(unrendered: Any) -> tuple[JobOutcome, RecordingContext]:
    return run(dict(DESIGN_SPACE_EXAMPLES[0].inputs))


@pytest.fixture(scope="module")
def example_3(unrendered: Any) -> tuple[JobOutcome, RecordingContext]:
    return run(dict(DESIGN_SPACE_EXAMPLES[1].inputs))


def by_beta(outcome: JobOutcome) -> dict[float, dict[str, Any]]:
    return {row["beta_deg"]: row for row in outcome.result["designs"]}


def artifact(outcome: JobOutcome, name: str) -> bytes:
    return next(a.data for a in outcome.artifacts if a.name == name)


# -- Fig. 5 and §6.1 -------------------------------------------------------------------


def test_result_document(fig_5: tuple[JobOutcome, RecordingContext]) -> None:
    outcome, ctx = fig_5
    assert set(outcome.result) == RESULT_KEYS
    json.dumps(outcome.result, allow_nan=False)
    assert ctx.percents == sorted(ctx.percents) and ctx.percents[-1] == 100.0
    assert {a.name for a in outcome.artifacts} == {
        "design_space.png", "design_space.svg", "index_map.png", "index_map.svg",
        "design_space.csv", "design_space.npz",
    }  # fmt: skip
    assert outcome.result["gamma_deg"] == 0.0 and not outcome.result["identical_platforms"]
    assert "closed form" in outcome.result["method"]
    assert outcome.result["sampling"]["n"] == 144


def test_beta_75(fig_5: tuple[JobOutcome, RecordingContext]) -> None:
    row = by_beta(fig_5[0])[75.0]
    assert row["f_min"] == pytest.approx(math.cos(math.radians(135.0)), abs=1e-5)
    assert row["f_max"] == pytest.approx(math.cos(math.radians(15.0)), abs=1e-5)
    assert row["f_min"] == pytest.approx(FIG_5_F_MIN, abs=1e-3)  # the paper's printed -0.707
    assert row["f_max"] == pytest.approx(FIG_5_F_MAX, abs=1e-3)  # and 0.966
    assert row["D1_deg"] == pytest.approx(45.0, abs=1e-6)
    assert row["D2_deg"] == pytest.approx(15.0, abs=1e-6)
    assert row["status"] == "rectangle" and not row["degenerate"] and not row["empty"]
    rectangle = row["rectangle"]
    assert rectangle["abs_alpha_difference_max_deg"] == pytest.approx(45.0)
    assert rectangle["abs_alpha_sum_minus_180_max_deg"] == pytest.approx(15.0)
    np.testing.assert_allclose(rectangle["corners_deg"],
                               [[60, 105], [105, 60], [120, 75], [75, 120]], atol=1e-9)  # fmt: skip
    assert rectangle["alpha1_range_deg"] == pytest.approx([60.0, 120.0])
    assert rectangle["area_deg2"] == pytest.approx(2 * 45 * 15)


def test_beta_60_degenerates_to_a_line(fig_5: tuple[JobOutcome, RecordingContext]) -> None:
    outcome, _ = fig_5
    row = by_beta(outcome)[60.0]
    assert row["f_max"] == pytest.approx(1.0, abs=1e-5)
    assert row["D2_deg"] == pytest.approx(0.0, abs=1e-6)
    assert row["status"] == "degenerate" and row["degenerate"] and not row["empty"]
    assert outcome.result["summary"]["degenerate_betas_deg"] == [60.0]
    assert outcome.result["summary"]["widest_beta_deg"] == 90.0
    row_90 = by_beta(outcome)[90.0]
    assert (row_90["D1_deg"], row_90["D2_deg"]) == pytest.approx((30.0, 30.0))


def test_design_space_rows_against_the_kinematics(fig_5: tuple[JobOutcome, RecordingContext]
                                                  ) -> None:  # fmt: skip
    space = sp.design_space(sp.Workspace(math.radians(60)), 0.0, np.radians([60, 75, 90]))
    rows = fig_5[0].result["designs"]
    np.testing.assert_allclose([r["f_min"] for r in rows], space.f_min, atol=1e-12)
    np.testing.assert_allclose([r["f_max"] for r in rows], space.f_max, atol=1e-12)


def test_fig_6_index_map(fig_5: tuple[JobOutcome, RecordingContext]) -> None:
    index_map = fig_5[0].result["index_map"]
    assert index_map["beta_deg"] == 75.0 and index_map["points_per_side"] == 31
    assert not index_map["degenerate"] and index_map["unscored_designs"] == 0
    best = index_map["best"]
    # the paper's two dotted optima, with identical values, at opposite corners
    assert [(b["alpha1_deg"], b["alpha2_deg"]) for b in best] == [(60.0, 105.0), (120.0, 75.0)]
    values = [b["indices"]["mean_square_inverse_condition"] for b in best]
    assert values[0] == pytest.approx(values[1], abs=1e-12)
    assert index_map["max"] == pytest.approx(values[0])
    expected = sp.workspace_indices(
        sp.SpmDesign.from_degrees(60, 105, 75),
        sp.orientation_samples(sp.Workspace(math.radians(60)))[0],
    )
    assert values[0] == pytest.approx(expected.mean_square_inverse_condition, abs=1e-4)
    assert values[0] < 0.2974  # below Table 1's optimum at beta = 90


def test_fig_5_notes(fig_5: tuple[JobOutcome, RecordingContext]) -> None:
    notes = " ".join(fig_5[0].all_notes)
    assert "for beta = 75° the paper gives f_min = -0.707" in notes and "reproduced" in notes
    assert "beta = 60° degenerates into the line a1 + a2 = 180°" in notes


def test_csv_and_npz(fig_5: tuple[JobOutcome, RecordingContext]) -> None:
    outcome, _ = fig_5
    rows = list(csv.reader(io.StringIO(artifact(outcome, "design_space.csv").decode())))
    assert rows[0] == ["beta [deg]", "gamma [deg]", "f_min [-]", "f_max [-]", "D1 [deg]",
                       "D2 [deg]", "degenerate [-]", "empty [-]"]  # fmt: skip
    assert [r[0] for r in rows[1:]] == ["60", "75", "90"] and rows[1][6] == "1"
    with np.load(io.BytesIO(artifact(outcome, "design_space.npz"))) as npz:
        assert npz["corners_deg"].shape == (3, 4, 2)
        assert npz["index_map_mean_square"].shape == (31, 31)
        axes, units = json.loads(str(npz["axes"])), json.loads(str(npz["units"]))
        assert axes["D1_deg"] == ["beta_deg"] and axes["corners_deg"][0] == "beta_deg"
        assert units["D1_deg"] == "deg" and units["f_min"] == "-"
        assert set(units) == set(npz.files) - {"axes", "units", "metadata"}
        assert json.loads(str(npz["metadata"]))["process"] == "spm-design-space"


# -- Example III: identical platforms, limited torsion ---------------------------------


def test_identical_platforms(example_3: tuple[JobOutcome, RecordingContext]) -> None:
    outcome, _ = example_3
    result = outcome.result
    assert result["identical_platforms"] and result["gamma_deg"] is None
    assert [r["beta_deg"] for r in result["designs"]] == [float(b) for b in range(20, 71, 5)]
    assert all(r["gamma_deg"] == r["beta_deg"] for r in result["designs"])
    assert result["index_map"] is None
    assert "a 36 x 9 x 5 grid" in result["method"]  # 30° of torsion: 5 values, 7.5° apart
    ws = sp.Workspace(math.radians(45), (math.radians(-15), math.radians(15)), False)
    for row in result["designs"]:
        d1, d2 = sp.design_widths(ws, math.radians(row["beta_deg"]), math.radians(row["beta_deg"]))
        assert row["f_min"] == pytest.approx(-math.cos(d1), abs=1e-5)
        assert row["f_max"] == pytest.approx(math.cos(d2), abs=1e-5)
    assert result["summary"]["degenerate_betas_deg"] == [20.0, 70.0]


def test_table_3_design_is_feasible(unrendered: Any) -> None:
    outcome, _ = run({"workspace": {"tilt_max_deg": 45, "torsion_deg": [-15, 15]},
                      "identical_platforms": True, "beta_deg": [33.3], "plots": False})  # fmt: skip
    row = outcome.result["designs"][0]
    assert abs(54.9 - 115.4) <= row["D1_deg"] and abs(54.9 + 115.4 - 180) <= row["D2_deg"]
    assert {a.name for a in outcome.artifacts} == {"design_space.csv", "design_space.npz"}


def test_an_empty_design_space(unrendered: Any) -> None:
    # a 180° cone with a full turn: only (90, 90) remains at beta = 90
    outcome, _ = run({"workspace": {"tilt_max_deg": 90}, "beta_deg": [90, 45], "plots": False})
    rows = by_beta(outcome)
    assert rows[90.0]["status"] == "empty" and rows[90.0]["empty"]
    assert rows[90.0]["rectangle"]["area_deg2"] == 0.0
    assert "Empty at beta = 90°" in " ".join(outcome.all_notes)


def test_rendered_figures(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(design_space, "figure_artifacts", figure_artifacts)
    outcome, _ = run({**DESIGN_SPACE_EXAMPLES[0].inputs,
                      "index_map": {"beta_deg": 75, "points_per_side": 7}})  # fmt: skip
    assert artifact(outcome, "design_space.png").startswith(b"\x89PNG")
    assert artifact(outcome, "index_map.png").startswith(b"\x89PNG")
