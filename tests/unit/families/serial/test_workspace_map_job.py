"""The ``serial-workspace-map`` process: properties of its maps (base rotation, joint
limits, the convergence prefixes), a job end to end, and agreement with the exact d_z
of the planar 3R family (docs/methods/serial.md, "Workspace map")."""

from __future__ import annotations

import io
import json
from typing import Any

import numpy as np
import pytest

from tests.unit.families.conftest import RecordingContext
from worker.errors import InvalidInputs
from worker.families.serial.arms import EXAMPLE_1_PLANAR, UR5
from worker.registry import default_registry
from worker.submission import validate_inputs

PROCESS = default_registry().get("serial-workspace-map")


def run(inputs: dict[str, Any], plots: bool = False) -> Any:
    assert PROCESS is not None
    return PROCESS.run(validate_inputs(PROCESS, {**inputs, "plots": plots}), RecordingContext())


def limited(robot: dict[str, Any], degrees: float) -> dict[str, Any]:
    return {**robot, "dh": [{**row, "limits": [-degrees, degrees]} for row in robot["dh"]]}


def npz(outcome: Any) -> Any:
    data = next(a.data for a in outcome.artifacts if a.name == "workspace_map.npz")
    return np.load(io.BytesIO(data))


def test_a_job_gives_its_summary_convergence_and_files() -> None:
    assert PROCESS is not None
    inputs = {"robot": EXAMPLE_1_PLANAR, "samples": 4000, "voxel_size": 2.0,
              "orientation_bins": 12, "length_unit": "units"}  # fmt: skip
    outcome = run(inputs, plots=True)
    result = outcome.result
    names = {a.name for a in outcome.artifacts}
    assert names == {f.name for f in PROCESS.files}
    summary, convergence = result["summary"], result["convergence"]
    assert result["grid"]["axes"] == ["x", "y"] and result["grid"]["cell"] == "pixel"
    assert "reached_volume" not in summary  # a planar arm's map has an area
    assert summary["reached_area"] == pytest.approx(summary["reached_voxels"] * 4.0)
    assert convergence["samples"] == [500, 1000, 2000, 4000]
    assert convergence["reached_area"][-1] == summary["reached_area"]
    assert convergence["mean_reachability_index"][-1] == pytest.approx(
        summary["mean_reachability_index"]
    )
    assert convergence["met"] == (
        max(convergence["relative_change_volume"][-1], convergence["relative_change_index"][-1])
        <= convergence["tolerance"]
    )
    data = npz(outcome)
    axes, units = json.loads(str(data["axes"])), json.loads(str(data["units"]))
    assert axes["reachability_index"] == ["x", "y"] and units["x"] == "units"
    assert json.loads(str(data["metadata"]))["process"] == "serial-workspace-map"
    assert int(data["reached"].sum()) == summary["reached_voxels"]
    csv = next(a.data for a in outcome.artifacts if a.name == "workspace_map.csv").decode()
    lines = csv.strip().split("\n")
    assert lines[0].startswith("x [units],y [units],reachability_index [-],samples [-]")
    assert len(lines) == 1 + summary["reached_voxels"]
    assert PROCESS.cost is not None and PROCESS.cost(validate_inputs(PROCESS, inputs)) == 12_000


def test_bad_inputs_name_their_field() -> None:
    assert PROCESS is not None
    for body, field in (
        ({"robot": UR5, "voxel_size": 0.1, "bounds": [[0, 1], [0, 1]]}, "inputs.bounds"),
        ({"robot": UR5, "voxel_size": 0.1, "bounds": [[0, 1], [1, 0], [0, 1]]},
         "inputs.bounds[1]"),
        ({"robot": UR5, "voxel_size": 0.0005}, "inputs.voxel_size"),
        ({"robot": UR5, "voxel_size": 0.1, "sampler": "halton"}, "inputs.sampler"),
    ):  # fmt: skip
        with pytest.raises(InvalidInputs) as caught:
            validate_inputs(PROCESS, body)
        assert [e["field"] for e in caught.value.errors] == [field]


@pytest.mark.parametrize("sampler", ["sobol", "uniform"])
def test_convergence_numbers_repeat_in_a_run_with_twice_the_samples(sampler: str) -> None:
    inputs = {"robot": UR5, "samples": 3000, "voxel_size": 0.15, "sampler": sampler,
              "seed": 4, "length_unit": "m"}  # fmt: skip
    once = run(inputs).result["convergence"]
    twice = run({**inputs, "samples": 6000}).result["convergence"]
    assert twice["samples"][:3] == once["samples"][1:]
    assert twice["reached_volume"][:3] == once["reached_volume"][1:]
    assert twice["mean_reachability_index"][:3] == once["mean_reachability_index"][1:]
    assert twice["relative_change_volume"][:2] == once["relative_change_volume"][1:]


@pytest.mark.parametrize("yaw", [90.0, 37.0])
def test_a_base_rotation_about_z_keeps_the_reached_volume(yaw: float) -> None:
    inputs = {"robot": UR5, "samples": 20_000, "voxel_size": 0.1, "length_unit": "m"}
    turned = {**UR5, "base": {"xyz": [0, 0, 0], "rpy_deg": [0, 0, yaw]}}
    plain, rotated = run(inputs), run({**inputs, "robot": turned})
    a, b = plain.result["summary"], rotated.result["summary"]
    # the same samples, their tool points turned: only voxel effects differ
    tolerance = 0.01 if yaw == 90.0 else 0.04
    assert b["reached_volume"] == pytest.approx(a["reached_volume"], rel=tolerance)
    assert b["samples_in_grid"] == a["samples_in_grid"]
    assert b["manipulability_max"] == pytest.approx(a["manipulability_max"], rel=1e-9)
    if yaw == 90.0:  # the grid maps onto itself: the reached sets agree voxel by voxel
        first, second = npz(plain)["reached"], npz(rotated)["reached"]
        turned_back = np.rot90(first, k=1, axes=(0, 1))
        assert np.mean(turned_back == second) > 0.995


def test_joint_limits_only_shrink_the_reached_set() -> None:
    inputs = {"robot": EXAMPLE_1_PLANAR, "voxel_size": 2.0, "orientation_bins": 36,
              "length_unit": "units"}  # fmt: skip
    free = npz(run({**inputs, "samples": 200_000}))
    bound = npz(run({**inputs, "samples": 25_000, "robot": limited(EXAMPLE_1_PLANAR, 100)}))
    assert bound["reached"].sum() < free["reached"].sum()
    assert not np.any(bound["reached"] & ~free["reached"])
    # per pixel, no more bins than the (denser) free map, up to one bin of sampling
    index_gap = bound["reachability_index"] - free["reachability_index"]
    assert np.all(index_gap[bound["reached"]] <= 1 / 36 + 1e-12)
    reached = bound["reached"]
    assert bound["reachability_index"][reached].mean() < free["reachability_index"][reached].mean()
