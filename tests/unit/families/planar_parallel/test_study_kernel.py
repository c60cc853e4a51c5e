"""The study kernel of planar2dof-conditioning-map against the process run per design:
random robot types, working modes, grids and limits, random dimensions and limits
varied (edge values, lengths out of range or out of ratio, chains that cannot meet,
grids out of scale), random objectives among the covered paths.  No shortcut: every
reason code and refused field agrees, and the numbers are equal to 1e-12 relative."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.unit.worker.studies.engines import REGISTRY, assert_engines_agree, field
from worker.common.grids import WorkspaceGrid
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.jobs.architecture import default_bounds
from worker.families.planar_parallel.kinematics import study_kernel
from worker.families.planar_parallel.kinematics.study_kernel import (
    grid_axes,
    map_summary,
)
from worker.families.planar_parallel.study import GRID_PATHS, REGION_PATHS
from worker.studies.rows import FEASIBLE, REFUSED

LENGTHS = [0.0, 5e-7, 1e-6, 0.3, 0.5, 1.0, 1.5, 2.0, 3.0, 1e5, 1e6, 2e6]
LIMITS = [0.0, 5e-7, 1e-6, 0.2, 0.5, 0.9, 0.999, 1.0]
GRID_OBJECTIVES = [
    "summary.inverse_condition.min", "summary.inverse_condition.max",
    "summary.inverse_condition.mean", "summary.reachable_points", "summary.reachable_area_grid",
    "w_kappa0.area_grid", "l1", "l2", "e", "delta", "working_mode[]|sum",
    "w_kappa0.inverse_condition_limit", "discretisation.grid.bounds[0]",
    "discretisation.grid.step[]|max", "discretisation.grid.points_per_axis",
]  # fmt: skip
SETTINGS = settings(max_examples=40, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])  # fmt: skip


def length() -> st.SearchStrategy[float]:
    return st.one_of(st.sampled_from(LENGTHS), st.floats(1e-6, 5.0))


def axis(draw: st.DrawFn, values: st.SearchStrategy[float], most: int) -> list[float]:
    lo, hi = sorted((draw(values), draw(values)))
    return [lo, hi, draw(st.integers(1, most))]


def robot(draw: st.DrawFn) -> tuple[dict[str, Any], list[str]]:
    """Fixed inputs of a random type and the inputs that may be varied."""
    actuation = draw(st.sampled_from(["proximal-arm", "proximal-arm", "telescopic-leg",
                                      "linear-drive"]))  # fmt: skip
    mode = [draw(st.sampled_from([1, -1])) for _ in "ab"]
    fixed: dict[str, Any] = {"actuation": actuation, "working_mode": mode}
    if actuation == "proximal-arm":
        fixed["l1"] = draw(st.sampled_from([0.5, 1.0, 2.0]))
        fixed["l2"] = draw(st.sampled_from([1.0, 1.5, 2.5]))
        if draw(st.booleans()):
            fixed["architecture"] = "isotropic"
            return fixed, ["l1", "l2"]
        fixed["e"] = draw(st.sampled_from([0.0, 0.3, 1.0]))
        return fixed, ["l1", "l2", "e"]
    if actuation == "telescopic-leg":
        fixed["e"] = draw(st.sampled_from([0.5, 1.0]))
        return fixed, ["e", "l1"]
    fixed["l2"] = draw(st.sampled_from([0.5, 1.0]))
    return fixed, ["l2", "e"]


@st.composite
def studies(draw: st.DrawFn, objectives: list[str], most: int) -> dict[str, Any]:
    fixed, lengths = robot(draw)
    grid: dict[str, Any] = {"points_per_axis": draw(st.integers(2, 17))}
    if draw(st.integers(0, 3)) == 0:
        grid["bounds"] = draw(st.sampled_from([[-2, 2, -3, 1], [-1e-3, 1e-3, -1e-3, 1e-3]]))
    fixed["grid"] = grid
    if draw(st.booleans()):
        fixed["inverse_condition_limit"] = draw(st.sampled_from([0.3, 0.5, 0.8]))
    names = lengths + (["inverse_condition_limit"] if "inverse_condition_limit" in fixed else [])
    chosen = draw(st.lists(st.sampled_from(names), min_size=1, max_size=2, unique=True))
    vary = {name: axis(draw, st.sampled_from(LIMITS) if name == "inverse_condition_limit"
                       else length(), most) for name in chosen}  # fmt: skip
    for name in chosen:
        fixed.pop(name, None)
    goals = draw(st.lists(st.sampled_from(objectives), min_size=1, max_size=3, unique=True))
    senses = {name: draw(st.sampled_from(["max", "min"])) for name in goals}
    return {"process": "planar2dof-conditioning-map", "fixed": fixed, "vary": vary,
            "objectives": senses}  # fmt: skip


@SETTINGS
@given(studies(GRID_OBJECTIVES, 4))
def test_the_map_agrees_with_the_process(inputs: dict[str, Any]) -> None:
    assert_engines_agree(inputs)


@settings(SETTINGS, max_examples=12)
@given(studies(["w_kappa0.area", "w_kappa0.rectangle_region_area",
                "w_kappa0.largest_inverse_condition.value", "w_kappa0.largest_inverse_condition.y",
                *GRID_OBJECTIVES], 2))  # fmt: skip
def test_w_kappa0_agrees_with_the_process(inputs: dict[str, Any]) -> None:
    assert_engines_agree(inputs)


def test_the_worked_designs_to_the_bit() -> None:
    """The paper's isotropic robots, l2 from 1 to 3 (and below l1: refused), W_kappa0 at
    1/kappa0 = 0.5: W_kappa0's areas bit for bit (the same search), the mean 1/kappa to
    1e-12 (summed in tiles)."""
    inputs = {"process": "planar2dof-conditioning-map",
              "fixed": {"architecture": "isotropic", "inverse_condition_limit": 0.5,
                        "grid": {"points_per_axis": 31}},
              "vary": {"l2": [0.8, 3.0, 5]},
              "objectives": {"w_kappa0.area": "max", "summary.inverse_condition.mean": "max",
                             "w_kappa0.rectangle_region_area": "max"}}  # fmt: skip
    batched, per_design = assert_engines_agree(inputs)
    areas = [0, 2]
    assert np.array_equal(batched.objectives[:, areas], per_design.objectives[:, areas],
                          equal_nan=True)  # fmt: skip
    assert batched.codes.tolist() == [REFUSED] + [FEASIBLE] * 4
    assert field(batched, 0) == "inputs"


@pytest.mark.parametrize(
    ("vary", "refused"),
    [({"l1": [1e-12, 1e-6, 2]}, "inputs.l1"), ({"e": [-1, 4.0, 2]}, "inputs.e"),
     ({"e": [1e-7, 0.5, 2]}, "inputs.e"), ({"l2": [1e6, 3e6, 2]}, "inputs.l2"),
     ({"e": [1e-6, 0.3, 2]}, "inputs.e"),
     ({"inverse_condition_limit": [0.5, 1.0, 2]}, "inputs.inverse_condition_limit"),
     ({"e": [0.3, 3.0, 2]}, "inputs.e"), ({"l1": [1.0, 1e4, 2]}, "inputs.grid.bounds"),
     ({"l1": [1e-6, 1.0, 2]}, "inputs.l2")],
)  # fmt: skip
def test_each_refusal_names_the_process_field(vary: dict[str, list[float]], refused: str) -> None:
    """Out of range, e between 0 and 1e-6 or e >= l1 + l2 (chains that cannot meet),
    a spread of lengths beyond 1e6 (named at e, the shortest), a grid out of scale."""
    fixed: dict[str, Any] = {"l1": 1.0, "l2": 1.5, "e": 0.3, "inverse_condition_limit": 0.5,
                             "grid": {"points_per_axis": 5}}  # fmt: skip
    if refused == "inputs.grid.bounds":  # a side of 0.002: a robot of 1e4 is out of scale
        fixed["grid"]["bounds"] = [-1e-3, 1e-3, -1e-3, 1e-3]
    for name in vary:
        fixed.pop(name)
    inputs = {"process": "planar2dof-conditioning-map", "fixed": fixed, "vary": vary,
              "objectives": {"summary.inverse_condition.max": "max"}}  # fmt: skip
    batched, _ = assert_engines_agree(inputs)
    refused_fields = {field(batched, n) for n in np.flatnonzero(batched.codes == REFUSED)}
    assert refused in refused_fields


def test_the_grid_is_the_jobs() -> None:
    """The kernel's nodes and 1/kappa over them are the job's map, bit for bit."""
    lengths = np.array([[1.0, 1.7, 0.7 * 0.7071067811865476], [1.0, 2.3, 0.2]])
    bounds = np.stack([np.asarray(default_bounds(pp.Architecture("proximal-arm", *row)))
                       for row in lengths.tolist()])  # fmt: skip
    x, y = grid_axes(bounds, 57)
    summary = map_summary("proximal-arm", (1, -1), lengths, (x, y), np.array([0.5, 0.4]))
    for k, row in enumerate(lengths.tolist()):
        arch = pp.Architecture("proximal-arm", *row)
        grid = WorkspaceGrid(default_bounds(arch), 57)
        assert np.array_equal(grid.x, x[k]) and np.array_equal(grid.y, y[k])
        values = pp.conditioning_map(arch, grid.x, grid.y, (1, -1)).inverse_condition
        finite = values[np.isfinite(values)]
        assert summary.minimum[k] == finite.min() and summary.maximum[k] == finite.max()
        assert summary.mean[k] == pytest.approx(finite.mean(), rel=1e-14)
        assert summary.inside[k] == (np.nan_to_num(values, nan=-1.0) >= [0.5, 0.4][k]).sum()


def test_the_kernel_covers_what_it_declares() -> None:
    process = REGISTRY.get("planar2dof-conditioning-map")
    assert process is not None and process.study_kernel is not None
    declared = {entry.path for entry in process.result_paths}
    assert set(process.study_kernel.covers) <= declared
    assert {*GRID_PATHS, *REGION_PATHS} <= set(process.study_kernel.covers)
    described = {entry["path"]: entry for entry in process.describe()["result_paths"]}
    assert described["w_kappa0.area"].get("kernel") is True
    assert "kernel" not in described["isotropic_point.x"]


def test_the_template_leaves_the_dimensions_to_the_kernel() -> None:
    """l1 = 2 with l2 varied from its reference 1 (eq 12 needs l2 >= l1): the template
    validates, the kernel refuses l2 = 1 per design as the process does."""
    inputs = {"process": "planar2dof-conditioning-map",
              "fixed": {"l1": 2.0, "architecture": "isotropic", "grid": {"points_per_axis": 9}},
              "vary": {"l2": [1.0, 4.0, 3]},
              "objectives": {"summary.inverse_condition.max": "max"}}  # fmt: skip
    batched, _ = assert_engines_agree(inputs)
    assert batched.codes.tolist() == [REFUSED, FEASIBLE, FEASIBLE]


@pytest.mark.parametrize("tile", [7, 100, 5000])
def test_tiles_change_nothing(tile: int, monkeypatch: pytest.MonkeyPatch) -> None:
    """Rows of one design's grid in tiles, or designs in tiles: the same summary (the
    mean to 1e-14, summed in pieces)."""
    lengths = np.array([[1.0, 1.5, 0.2], [0.5, 2.0, 0.0], [1.0, 1.0, 1.0]])
    axes = grid_axes(default_bounds_of(lengths), 41)
    whole = map_summary("proximal-arm", (1, -1), lengths, axes, np.full(3, 0.3))
    monkeypatch.setattr(study_kernel, "TILE_NODES", tile)
    tiled = map_summary("proximal-arm", (1, -1), lengths, axes, np.full(3, 0.3))
    for name in ("reachable", "minimum", "maximum", "inside"):
        assert np.array_equal(getattr(whole, name), getattr(tiled, name)), name
    np.testing.assert_allclose(tiled.mean, whole.mean, rtol=1e-14)


def default_bounds_of(lengths: np.ndarray) -> np.ndarray:
    return study_kernel.default_bounds("proximal-arm", lengths)
