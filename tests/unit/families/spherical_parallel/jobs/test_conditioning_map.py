"""The spm-conditioning-map job: the paper's designs (Tables 1-3, Fig. 7) end to end,
checked against docs/methods/spherical-parallel.md and the kinematics' own re-computation."""

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
from worker.families.spherical_parallel import CONDITIONING_MAP
from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.examples import CONDITIONING_MAP_EXAMPLES, TABLE_2_GRAPHIC
from worker.families.spherical_parallel.jobs import conditioning_artifacts
from worker.families.spherical_parallel.specs import ConditioningMapSpec

RESULT_KEYS = {
    "design", "branch", "workspace", "sampling", "indices", "workspace_minimum",
    "design_space", "type_ii_singularity", "inverse_kinematics", "orientations", "maps",
    "torsion_sweeps", "definitions", "data",
}  # fmt: skip
DATA = {"conditioning_samples.csv": "text/csv", "conditioning_map.npz": "application/x-npz"}
PLOTS = {f"{stem}.{ext}" for stem in ("inverse_condition_map", "torsion_sweeps")
         for ext in ("png", "svg")}  # fmt: skip
#: Orientations (deg) checked one by one against the per-orientation reference loop.
ORIENTATIONS = [[0.0, 30.0, 0.0], [10.0, 20.0, 30.0], [35.0, 45.0, 200.0], [250.0, 5.0, -40.0]]


@pytest.fixture(scope="module")
def unrendered() -> Any:
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(conditioning_artifacts, "figure_artifacts", unrendered_artifacts)
        yield


def run(inputs: dict[str, Any]) -> tuple[JobOutcome, RecordingContext]:
    ctx = RecordingContext()
    spec = ConditioningMapSpec.model_validate(inputs)
    return CONDITIONING_MAP.run(spec, ctx), ctx


def example(index: int, **extra: Any) -> dict[str, Any]:
    return {**dict(CONDITIONING_MAP_EXAMPLES[index].inputs), **extra}


@pytest.fixture(scope="module")
def table_1(unrendered: Any) -> tuple[JobOutcome, RecordingContext]:
    return run(example(0))


@pytest.fixture(scope="module")
def table_2(unrendered: Any) -> tuple[JobOutcome, RecordingContext]:
    return run(example(1, orientations=ORIENTATIONS))


@pytest.fixture(scope="module")
def graphic(unrendered: Any) -> tuple[JobOutcome, RecordingContext]:
    return run(example(2))


@pytest.fixture(scope="module")
def table_3(unrendered: Any) -> tuple[JobOutcome, RecordingContext]:
    return run(example(3))


def artifact(outcome: JobOutcome, name: str) -> bytes:
    return next(a.data for a in outcome.artifacts if a.name == name)


EXAMPLES = ["table_1", "table_2", "graphic", "table_3"]


@pytest.mark.parametrize("name", EXAMPLES)
class TestWorkedExamples:
    def test_progress_rises_to_the_end(self, name: str, request: pytest.FixtureRequest) -> None:
        _, ctx = request.getfixturevalue(name)
        assert len(ctx.percents) >= 6 and ctx.percents == sorted(ctx.percents)
        assert ctx.percents[-1] == 100.0 and all(message for _, message in ctx.reports)

    def test_result_document(self, name: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(name)
        result = outcome.result
        assert set(result) == RESULT_KEYS
        json.dumps(result, allow_nan=False)
        assert {a.name: a.media_type for a in outcome.artifacts if a.name in DATA} == DATA
        assert {a.name for a in outcome.artifacts} == set(DATA) | PLOTS
        sampling = result["sampling"]
        assert sampling["n"] == 144 and sampling["default"]
        assert sampling["counts"] == {"azimuth": 4, "tilt": 12, "torsion": 3}
        assert sampling["psi1_deg"] == [0.0, 90.0, 180.0, 270.0]
        assert result["inverse_kinematics"]["samples"] == 144
        assert result["inverse_kinematics"]["unreachable"] == []
        assert len(result["inverse_kinematics"]["entries"]) == 144

    def test_indices_are_the_kinematics_own(self, name: str, request: pytest.FixtureRequest
                                            ) -> None:  # fmt: skip
        outcome, _ = request.getfixturevalue(name)
        result = outcome.result
        design = sp.SpmDesign.from_degrees(*result["design"].values())
        samples = np.radians(np.array([e["psi_deg"] for e in
                                       result["inverse_kinematics"]["entries"]]))  # fmt: skip
        reference = sp.per_orientation_reference(design, samples, result["branch"])
        indices = result["indices"]
        for key in ("rms_inverse_condition", "mean_square_inverse_condition", "gci",
                    "min_inverse_condition", "max_inverse_condition"):  # fmt: skip
            assert indices[key] == pytest.approx(getattr(reference, key), abs=1e-4)
        assert indices["rms_inverse_condition"] ** 2 == pytest.approx(
            indices["mean_square_inverse_condition"], abs=1e-12
        )
        assert indices["gci"] <= indices["rms_inverse_condition"] + 1e-12  # AM <= QM

    def test_csv_and_npz_agree(self, name: str, request: pytest.FixtureRequest) -> None:
        outcome, _ = request.getfixturevalue(name)
        text = artifact(outcome, "conditioning_samples.csv").decode()
        rows = list(csv.reader(io.StringIO(text)))
        assert rows[0] == list(conditioning_artifacts.CSV_COLUMNS)
        assert len(rows) == 145
        data = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1)
        with np.load(io.BytesIO(artifact(outcome, "conditioning_map.npz"))) as npz:
            np.testing.assert_allclose(data[:, :3], npz["samples_deg"], atol=1e-9)
            np.testing.assert_allclose(data[:, 7], npz["inverse_condition"], rtol=1e-11)
            np.testing.assert_allclose(data[:, 7] * data[:, 8], 1.0, rtol=1e-10)
            assert npz["map_inverse_condition"].shape == (3, 41, 121)
            assert npz["sweep_inverse_condition"].shape == (3, 361)
            mean_square = float(np.mean(npz["inverse_condition"] ** 2))
        assert mean_square == pytest.approx(
            outcome.result["indices"]["mean_square_inverse_condition"], abs=1e-12
        )


# -- docs/methods/spherical-parallel.md
# ---------------------------------------------------------------------


def test_table_1_values(table_1: tuple[JobOutcome, RecordingContext]) -> None:
    result = table_1[0].result
    indices = result["indices"]
    assert indices["mean_square_inverse_condition"] == pytest.approx(0.2974, abs=1e-4)
    assert indices["rms_inverse_condition"] == pytest.approx(0.5453, abs=1e-4)
    # the paper prints 0.28 ("C_n"): mean(1/kappa^2) within its ±0.04
    assert indices["mean_square_inverse_condition"] == pytest.approx(0.28, abs=0.04)
    assert result["design_space"]["feasible"] and result["design_space"]["on_edge"]
    minimum = result["workspace_minimum"]
    psi1, psi2, psi3 = minimum["psi_deg"]
    assert minimum["inverse_condition"] == pytest.approx(0.0, abs=1e-6)
    assert psi2 == pytest.approx(60.0) and (psi3 - psi1) % 120.0 == pytest.approx(90.0)
    assert indices["min_inverse_condition"] > 0.29  # the samples do not see it


def test_table_1_notes(table_1: tuple[JobOutcome, RecordingContext]) -> None:
    notes = " ".join(table_1[0].all_notes)
    assert "1/kappa falls to 0" in notes
    assert "Table 1 prints 'C_n' = 0.28" in notes and "0.2974 here" in notes
    assert "not the root mean square of eq 25 (0.5453)" in notes


def test_table_2_values(table_2: tuple[JobOutcome, RecordingContext]) -> None:
    indices = table_2[0].result["indices"]
    assert indices["mean_square_inverse_condition"] == pytest.approx(0.7021, abs=1e-4)
    assert indices["rms_inverse_condition"] == pytest.approx(0.8379, abs=1e-4)
    assert indices["gci"] == pytest.approx(0.8357, abs=1e-4)
    assert indices["mean_square_inverse_condition"] == pytest.approx(0.72, abs=0.04)
    assert "(48, 90, 90) is not the optimum" in " ".join(table_2[0].all_notes)


def test_graphic_design_is_an_erratum(graphic: tuple[JobOutcome, RecordingContext]) -> None:
    value = graphic[0].result["indices"]["mean_square_inverse_condition"]
    assert value == pytest.approx(0.616, abs=1e-3)
    assert abs(value - TABLE_2_GRAPHIC.printed) > 0.04  # printed 0.67: outside ±0.04
    assert "prints 'C_n' = 0.67" in " ".join(graphic[0].all_notes)


def test_table_3_values(table_3: tuple[JobOutcome, RecordingContext]) -> None:
    result = table_3[0].result
    assert result["workspace"]["torsion_deg"] == [-15.0, 15.0]
    assert result["sampling"]["psi3_deg"] == [-15.0, 0.0, 15.0]
    # a limited range sits in the middle of the sweeps' turn
    assert result["torsion_sweeps"][0]["psi3_deg"] == {"from": -180.0, "to": 180.0, "step": 1.0}
    assert result["indices"]["mean_square_inverse_condition"] == pytest.approx(0.585, abs=0.04)
    assert "It is not the optimum" in " ".join(table_3[0].all_notes)


#: docs/methods/spherical-parallel.md, Fig. 7 at psi1 = 35°: the range of 1/kappa over a torsion
#: turn.
FIG_7 = {
    "table_2": {15.0: (0.895, 0.899), 30.0: (0.846, 0.863), 45.0: (0.584, 0.800)},
    "graphic": {15.0: (0.862, 0.867), 30.0: (0.773, 0.797), 45.0: (0.558, 0.758)},
}


@pytest.mark.parametrize("name", ["table_2", "graphic"])
def test_fig_7_ranges(name: str, request: pytest.FixtureRequest) -> None:
    outcome, _ = request.getfixturevalue(name)
    sweeps = outcome.result["torsion_sweeps"]
    assert [(s["psi1_deg"], s["psi2_deg"]) for s in sweeps] == [(35.0, 15.0), (35.0, 30.0),
                                                                 (35.0, 45.0)]  # fmt: skip
    for sweep in sweeps:
        lo, hi = FIG_7[name][sweep["psi2_deg"]]
        assert sweep["min_inverse_condition"] == pytest.approx(lo, abs=1e-3)
        assert sweep["max_inverse_condition"] == pytest.approx(hi, abs=1e-3)
        assert sweep["inside_cone"] and sweep["unreachable_points"] == 0
    with np.load(io.BytesIO(artifact(outcome, "conditioning_map.npz"))) as npz:
        values = npz["sweep_inverse_condition"]
    np.testing.assert_allclose(values[:, :121], values[:, 120:241], atol=1e-12)  # period 120°
    assert "Fig. 7" in " ".join(outcome.all_notes)


# -- single poses ----------------------------------------------------------------------


def test_orientations_against_the_reference_loop(
    table_2: tuple[JobOutcome, RecordingContext],
) -> None:
    entries = table_2[0].result["orientations"]
    assert [e["psi_deg"] for e in entries] == ORIENTATIONS
    design = sp.SpmDesign.from_degrees(48, 90, 90)
    reference = sp.per_orientation_reference(design, np.radians(ORIENTATIONS), -1)
    for k, entry in enumerate(entries):
        assert entry["real"]
        assert entry["inverse_condition"] == pytest.approx(reference.inverse_condition[k],
                                                           abs=1e-6)  # fmt: skip
        assert entry["condition_number"] * entry["inverse_condition"] == pytest.approx(1.0)
        assert entry["condition_number"] >= 1.0
        assert entry["det_a"] == pytest.approx(reference.det_a[k], abs=1e-6)
        wrapped = np.remainder(np.array(entry["joint_angles_deg"])
                               - np.degrees(reference.theta[k]) + 180.0, 360.0) - 180.0  # fmt: skip
        np.testing.assert_allclose(wrapped, 0.0, atol=1e-6)


def test_orientations_close_the_chain(table_2: tuple[JobOutcome, RecordingContext]) -> None:
    design = sp.SpmDesign.from_degrees(48, 90, 90)
    for entry in table_2[0].result["orientations"]:
        theta = np.radians(entry["joint_angles_deg"])
        u, w, v = sp.unit_vectors(design, theta, np.radians(entry["psi_deg"]))
        np.testing.assert_allclose(np.einsum("ik,ik->i", w, v), math.cos(math.pi / 2), atol=1e-9)
        assert np.all(np.einsum("ik,ik->i", np.cross(u, w), v) < 0.0)  # branch -1 (eq 29)


# -- designs that miss part of the workspace -------------------------------------------


def test_an_infeasible_design_is_never_scored(unrendered: Any) -> None:
    # (60, 90, 75) breaks |a1 + a2 - 180| <= 15° (eq 19b): some legs fold open at tilt 60°
    outcome, _ = run({"alpha1_deg": 60, "alpha2_deg": 90, "beta_deg": 75,
                      "workspace": {"tilt_max_deg": 60}, "orientations": [[0, 60, 90], [0, 0, 0]],
                      "plots": False})  # fmt: skip
    result = outcome.result
    json.dumps(result, allow_nan=False)
    assert not result["indices"]["all_real"]
    assert result["indices"]["mean_square_inverse_condition"] is None
    assert result["indices"]["rms_inverse_condition"] is None
    assert not result["design_space"]["feasible"]
    assert result["design_space"]["margins_deg"][1] == pytest.approx(-15.0)
    ik = result["inverse_kinematics"]
    assert ik["real"] == 129 and len(ik["unreachable"]) == 15
    assert len(ik["unreachable_psi_deg"]) == 15
    assert all(not ik["entries"][i]["real"] for i in ik["unreachable"])
    unreachable, centre = result["orientations"]
    assert not unreachable["real"] and unreachable["condition_number"] is None
    assert unreachable["joint_angles_deg"][0] is None and unreachable["joint_angles_deg"][1] > 0
    assert centre["real"] and centre["inverse_condition"] > 0.0
    assert "15 of 144 samples have no real inverse kinematics" in " ".join(outcome.all_notes)


def test_without_plots_only_data(unrendered: Any) -> None:
    outcome, _ = run(example(0, plots=False))
    assert {a.name for a in outcome.artifacts} == set(DATA)


def test_denser_sampling_is_reported(unrendered: Any) -> None:
    outcome, _ = run(example(0, workspace={"tilt_max_deg": 60, "samples": {"azimuth": 12,
                     "tilt": 24, "torsion": 9}}, plots=False))  # fmt: skip
    result = outcome.result
    assert result["sampling"]["n"] == 12 * 24 * 9 and not result["sampling"]["default"]
    assert result["inverse_kinematics"]["entries"] is None  # over 2000: in the CSV only
    assert not result["inverse_kinematics"]["listed"]
    # docs/methods/spherical-parallel.md: the values move by about ±0.04 with the layout
    assert result["indices"]["mean_square_inverse_condition"] == pytest.approx(0.2974, abs=0.04)


def test_rendered_figures(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(conditioning_artifacts, "figure_artifacts", figure_artifacts)
    outcome, _ = run(example(1))
    for name in PLOTS:
        data = artifact(outcome, name)
        assert data.startswith(b"\x89PNG") if name.endswith(".png") else b"<svg" in data[:500]
