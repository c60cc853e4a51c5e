"""The study kernel of planar3r-dexterity-map against the process run per design:
random links (lengths out of range, spreads beyond the ratio, arms that reach none of a
given grid or none of the task), random joint limits (none, the full turn, a joint
locked, limits at ±180°; exact events and orientation sampling), task points (the base
included), trajectories, grids (default or given bounds), and random objectives among
the covered paths (the map's summary and areas included).  No shortcut:
every reason code and refused field agrees, and the numbers are equal to 1e-12
relative (to the bit, in fact)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.unit.worker.studies.engines import REGISTRY, assert_engines_agree, field
from worker.families.planar_serial.jobs.dexterity_evaluation import point_dexterity
from worker.families.planar_serial.kinematics.study_kernel import (
    TILE_PAIRS,
    designs_point_dexterity,
)
from worker.families.planar_serial.study import COVERS
from worker.studies.examples import STUDY_EXAMPLES
from worker.studies.rows import FEASIBLE, REFUSED

LENGTHS = [0.0, 5e-7, 1e-6, 1.0, 2.0, 5.0, 8.0, 14.0, 15.0, 20.0, 1e6, 2e6]
LIMITS = [
    None,
    [[-180, 180], [-180, 180], [-180, 180]],
    [[-150, 150], [-150, 150], [-175, 175]],
    [[-90, 120], [0, 150], [-180, 10]],
    [[30, 30], [-170, 170], [-120, 120]],  # joint 1 locked
    [[-180, 180], [-100, -20], [180, 180]],
]
OBJECTIVES = [
    "task_points[].d_z|min", "task_points[].d_z|mean", "task_points[0].d_z",
    "task_points[].D|sum", "task_points[1].region", "task_points[].region|max",
    "task_points[].distance|max", "task_points[0].x", "trajectory.d_z_min",
    "trajectory.d_z_mean", "trajectory.D_mean", "trajectory.fully_dexterous_fraction",
    "trajectory.samples", "links|sum", "links[2]", "discretisation.grid.step[0]",
    "discretisation.grid.bounds|max", "discretisation.radial_section.d_to",
    "discretisation.grid.points_per_axis", "summary.d_z_max", "summary.d_z_mean_reachable",
    "summary.D_mean_reachable", "summary.reachable_points", "summary.fully_dexterous_points",
    "areas.reachable", "areas.fully_dexterous", "areas.reachable_grid",
    "areas.fully_dexterous_grid", "areas.cell_area", "areas.unlimited_reference.reachable",
    "areas.unlimited_reference.fully_dexterous",
]  # fmt: skip
SETTINGS = settings(max_examples=60, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])  # fmt: skip


def length() -> st.SearchStrategy[float]:
    return st.one_of(st.sampled_from(LENGTHS), st.integers(1, 20).map(float),
                     st.floats(1e-6, 30.0))  # fmt: skip


def coordinate() -> st.SearchStrategy[float]:
    return st.one_of(st.integers(-30, 30).map(float), st.floats(-40.0, 40.0))


@st.composite
def trajectories(draw: st.DrawFn) -> dict[str, Any] | None:
    kind = draw(st.sampled_from(["none", "polyline", "polynomial"]))
    samples = draw(st.integers(2, 12))
    if kind == "polyline":
        points = [[draw(coordinate()), draw(coordinate())] for _ in range(3)]
        points[1] = [points[0][0] + 1.0, points[0][1]]  # never all coincident
        return {"points": points, "samples": samples}
    if kind == "polynomial":
        return {"polynomial": [draw(st.floats(-0.1, 0.1)), draw(st.floats(-2, 2)),
                               draw(coordinate())],
                "x_start": -12.0, "x_end": 15.0, "samples": samples}  # fmt: skip
    return None


@st.composite
def studies(draw: st.DrawFn) -> dict[str, Any]:
    links = draw(st.sampled_from([[15, 14, 8], [10, 10, 3], [1, 2, 1], [20, 5, 5]]))
    varied = draw(st.lists(st.integers(0, 2), min_size=1, max_size=2, unique=True))
    side = draw(st.sampled_from([2, 3, 7]))
    fixed: dict[str, Any] = {"links": links, "grid": {"points_per_axis": side}}
    limits = draw(st.sampled_from(LIMITS))
    if limits is not None:
        fixed["joint_limits_deg"] = limits
        fixed["method"] = draw(st.sampled_from(["exact-events", "exact-events",
                                                "orientation-sampling"]))  # fmt: skip
        fixed["orientation_step_deg"] = 10.0
    if draw(st.booleans()):
        fixed["grid"]["bounds"] = draw(st.sampled_from(
            [[20, 40, 20, 40], [-5, 5, -5, 5], [-1, 1, 30, 32]]))  # fmt: skip
    if draw(st.booleans()):
        points = [[draw(coordinate()), draw(coordinate())]
                  for _ in range(draw(st.integers(1, 4)))]  # fmt: skip
        fixed["task_points"] = [[0.0, 0.0], *points] if draw(st.booleans()) else points
    path = draw(trajectories())
    if path is not None:
        fixed["trajectory"] = path
    vary = {}
    for link in varied:
        lo, hi = sorted((draw(length()), draw(length())))
        vary[f"links[{link}]"] = [lo, hi, draw(st.integers(1, 4))]
    chosen = draw(st.lists(st.sampled_from(OBJECTIVES), min_size=1, max_size=3, unique=True))
    objectives = {name: draw(st.sampled_from(["max", "min"])) for name in chosen}
    return {"process": "planar3r-dexterity-map", "fixed": fixed, "vary": vary,
            "objectives": objectives}  # fmt: skip


@SETTINGS
@given(studies())
def test_the_kernel_agrees_with_the_process(inputs: dict[str, Any]) -> None:
    assert_engines_agree(inputs)


def test_the_worked_study_is_the_jobs_to_the_bit() -> None:
    """The worked 3R study (Example 1's task under joint limits), and links out of
    range, too spread, or missing a given grid: refused at the same fields."""
    arm = dict(STUDY_EXAMPLES[3].inputs)
    batched, per_design = assert_engines_agree(arm)
    assert np.array_equal(batched.objectives, per_design.objectives, equal_nan=True)
    assert (batched.codes == FEASIBLE).all()
    fixed = {**arm["fixed"], "grid": {"points_per_axis": 3, "bounds": [30, 40, 30, 40]}}
    edges = {**arm, "fixed": fixed,
             "vary": {"links[0]": [0, 40, 5], "links[2]": [1e-6, 16, 3]}}  # fmt: skip
    batched, _ = assert_engines_agree(edges)
    refusals = {field(batched, n) for n in np.flatnonzero(batched.codes == REFUSED)}
    assert refusals == {"inputs.links[0]", "inputs.links", "inputs.grid.bounds"}
    assert (batched.codes == FEASIBLE).any()


@pytest.mark.parametrize("limits", [None, np.radians([[-150, 150], [-150, 150], [-175, 175]])])
def test_tiles_do_not_change_a_number(limits: Any) -> None:
    """More designs than a tile holds: every row is the job's d_z of that design."""
    rng = np.random.default_rng(7)
    points = rng.uniform(-30, 30, (40, 2))
    links = rng.uniform(1, 15, (TILE_PAIRS // 40 + 3, 3))
    d_z = designs_point_dexterity(links, points, limits)
    for n in (0, 1, len(links) // 2, len(links) - 1):
        from worker.families.planar_serial.jobs.dexterity_evaluation import limited_joints

        deg = None if limits is None else np.degrees(limits).round().tolist()
        sampling = limited_joints(deg, 1.0)
        alone = point_dexterity(tuple(links[n].tolist()), points, sampling)  # type: ignore[arg-type]
        assert np.array_equal(d_z[n], alone)


def test_the_kernel_covers_what_it_declares() -> None:
    process = REGISTRY.get("planar3r-dexterity-map")
    assert process is not None and process.study_kernel is not None
    assert process.study_kernel.covers == COVERS
    declared = {entry.path for entry in process.result_paths}
    assert set(COVERS) <= declared
    described = process.describe()
    kernel = {e["path"] for e in described["result_paths"] if e.get("kernel")}
    assert kernel == set(COVERS)
