"""Every accepted input computes: ``planar3r-dexterity-map``, ``planar3r-synthesis`` and
``planar3r-design``.

Link lengths are drawn log-uniformly across [1e-6, 1e6] and just outside, task points
and trajectories across the coordinate range; a value outside must be refused naming
its field, and a request that validates must run as the worker runs it (stored JSON
validated again, plots on) with a JSON-clean result and non-empty artifacts. Grids are
coarse to keep each run short; few run examples, always the same ones
(``DEXLAB_PROPERTY_EXAMPLES=200`` searches longer).
"""

from __future__ import annotations

import math
from typing import Any

import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from tests.unit.families.planar_parallel.test_input_ranges import (
    check_request,
    definition,
    property_settings,
)
from worker.common.numeric_ranges import MAX_COORDINATE, MAX_LENGTH, MAX_LENGTH_RATIO, MIN_LENGTH
from worker.errors import InvalidInputs
from worker.submission import validate_inputs

MAP = definition("planar3r-dexterity-map")
SYNTHESIS = definition("planar3r-synthesis")

length = st.one_of(
    st.floats(-7, 7).map(lambda e: float(10**e)), st.sampled_from([MIN_LENGTH, MAX_LENGTH])
)
coordinate = st.one_of(
    st.floats(-2e6, 2e6), st.sampled_from([-MAX_COORDINATE, MAX_COORDINATE, 0.0])
)
point = st.tuples(coordinate, coordinate).map(list)
limits = st.one_of(
    st.none(),
    st.just([[-150, 150], [-150, 150], [-175, 175]]),
    st.just([[0, 90], [-45, 45], [-180, 180]]),
)


def links_outside(links: list[float]) -> set[str]:
    if any(not MIN_LENGTH <= v <= MAX_LENGTH for v in links):
        return {"inputs.links"}
    if max(links) / min(links) > MAX_LENGTH_RATIO:
        return {"inputs.links"}
    return set()


def points_outside(points: list[list[float]]) -> set[str]:
    bad = any(abs(c) > MAX_COORDINATE for p in points for c in p)
    return {"inputs.task_points"} if bad else set()


@pytest.mark.parametrize(
    ("process_id", "raw", "field"),
    [
        ("planar3r-dexterity-map", {"links": [5e-324] * 3}, "inputs.links[0]"),
        ("planar3r-dexterity-map", {"links": [1e308] * 3}, "inputs.links[0]"),
        ("planar3r-dexterity-map", {"links": [1e-6, 1, 2]}, "inputs.links"),
        ("planar3r-synthesis", {"l3": 5e-324, "task_points": [[1, 1]]}, "inputs.l3"),
        ("planar3r-synthesis", {"l3": 1, "task_points": [[1e308, 1]]}, "inputs.task_points[0][0]"),
        (
            "planar3r-synthesis",
            {"l3": 1, "trajectory": {"polynomial": [1e6, 0, 0], "x_start": 0, "x_end": 1e3}},
            "inputs.trajectory",
        ),
        (
            "planar3r-dexterity-map",
            {"links": [3, 2, 1], "grid": {"bounds": [0, 5e-324, 0, 1]}},
            "inputs.grid",
        ),
    ],
)
def test_the_issue_inputs_are_refused_naming_the_field(
    process_id: str, raw: dict[str, Any], field: str
) -> None:
    with pytest.raises(InvalidInputs) as caught:
        validate_inputs(definition(process_id), raw)
    fields = [e["field"] for e in caught.value.errors]
    assert any(f.startswith(field) for f in fields), caught.value.errors


@given(
    links=st.lists(length, min_size=3, max_size=3),
    task=st.one_of(st.none(), st.lists(point, min_size=1, max_size=4)),
    joint_limits=limits,
)
@example(links=[1e-6, 1e-6, 1e-6], task=[[1e6, 1e6]], joint_limits=None)
@example(links=[1e6, 1e6, 1.0], task=[[-1e6, 0.0]], joint_limits=[[0, 90], [-45, 45], [-180, 180]])
@example(links=[1.0, 1e-6, 1.0], task=None, joint_limits=[[-150, 150], [-150, 150], [-175, 175]])
@property_settings(12)
def test_dexterity_map_accepted_inputs_compute(
    links: list[float], task: list[list[float]] | None, joint_limits: Any
) -> None:
    raw: dict[str, Any] = {
        "links": links,
        "grid": {"points_per_axis": 31},
        "orientation_step_deg": 10,
    }
    if task is not None:
        raw["task_points"] = task
    if joint_limits is not None:
        raw["joint_limits_deg"] = joint_limits
    bad = links_outside(links) | (points_outside(task) if task else set())
    check_request(MAP, raw, bad, cost_limit=10**8)


@given(
    l3=length,
    task=st.lists(point, min_size=1, max_size=5),
    polynomial=st.one_of(st.none(), st.lists(st.floats(-10, 10), min_size=1, max_size=4)),
)
@example(l3=1e-6, task=[[1e-6, 0.0]], polynomial=None)
@example(l3=1e6, task=[[1e6, 1e6], [-1e6, -1e6]], polynomial=[1.0, 0.0])
@example(l3=1.0, task=[[0.0, 0.0]], polynomial=None)
@property_settings(12)
def test_synthesis_accepted_inputs_compute(
    l3: float, task: list[list[float]], polynomial: list[float] | None
) -> None:
    raw: dict[str, Any] = {
        "l3": l3,
        "task_points": task,
        "grid": {"points_per_axis": 31},
        "orientation_step_deg": 10,
    }
    if polynomial is not None:
        raw["trajectory"] = {"polynomial": polynomial, "x_start": -1.0, "x_end": 1.0}
    bad = points_outside(task)
    if not MIN_LENGTH <= l3 <= MAX_LENGTH:
        bad.add("inputs.l3")
    check_request(SYNTHESIS, raw, bad, cost_limit=10**8)


DESIGN = definition("planar3r-design")


def tool_outside(total: float, task: list[list[float]], tool: float | None) -> set[str]:
    """The field a held l3 makes bad: ``l3`` when given, else total_length_max (the paper
    rule's l3 for the budget, (total - d_max - 1) / 2, must be positive); either way l1
    and l2 need room (0.001 total each) and the links a spread of at most 1e6."""
    field = "inputs.total_length_max" if tool is None else "inputs.l3"
    if tool is not None and not MIN_LENGTH <= tool <= MAX_LENGTH:
        return {"inputs.l3"}
    l3 = tool if tool is not None else (total - max(math.hypot(*p) for p in task) - 1) / 2
    lowest = 1e-3 * total
    if l3 <= 0 or l3 > total - 2 * lowest:
        return {field}
    if max(total - l3, l3) / min(lowest, l3) > MAX_LENGTH_RATIO:
        return {field}
    return set()


@given(
    total=length,
    task=st.lists(point, min_size=1, max_size=4),
    joint_limits=limits,
    lowest=st.one_of(st.none(), length),
    tool=st.one_of(st.none(), length),
    box=st.one_of(st.none(), st.tuples(coordinate, coordinate).map(sorted)),
)
@example(total=1e-6, task=[[1e6, 1e6]], joint_limits=None, lowest=None, tool=None, box=None)
@example(total=1e6, task=[[1e-6, 0.0]], joint_limits=[[-150, 150], [-150, 150], [-175, 175]],
         lowest=1e-6, tool=None, box=None)  # fmt: skip
@example(total=10.0, task=[[0.0, 0.0]], joint_limits=[[0, 90], [-45, 45], [-180, 180]],
         lowest=None, tool=None, box=(-1e6, 1e6))  # fmt: skip
@example(total=1e6, task=[[3.0, 4.0]], joint_limits=None, lowest=None, tool=1.0, box=None)
@example(total=30.0, task=[[3.0, 4.0]], joint_limits=None, lowest=1.0, tool=1.0, box=None)
@property_settings(12)
def test_design_accepted_inputs_compute(
    total: float, task: list[list[float]], joint_limits: Any, lowest: float | None,
    tool: float | None, box: tuple[float, float] | None,
) -> None:  # fmt: skip
    raw: dict[str, Any] = {
        "task_points": task,
        "total_length_max": total,
        "grid": {"points_per_axis": 11},
        "max_generations": 2,
        "population_size": 5,
        "starts": 2,
    }
    if joint_limits is not None:
        raw["joint_limits_deg"] = joint_limits
    if lowest is not None:
        raw["link_bounds"] = [[lowest, total]] * 3
    if tool is not None:
        raw["l3"] = tool
    if box is not None:
        raw["base_box"] = [box[0], box[1], box[0], box[1]]
    bad = points_outside(task)
    if not MIN_LENGTH <= total <= MAX_LENGTH:
        bad.add("inputs.total_length_max")
    elif tool is not None and not MIN_LENGTH <= tool <= MAX_LENGTH:
        bad.add("inputs.l3")
    elif tool is not None and lowest is not None:
        bad |= {"inputs.l3", "inputs.link_bounds"}  # not both
    elif lowest is not None and (
        not MIN_LENGTH <= lowest <= MAX_LENGTH
        or 3 * lowest > total
        or total / lowest > MAX_LENGTH_RATIO
    ):
        bad.add("inputs.link_bounds")
    elif lowest is None and not bad:
        bad |= tool_outside(total, task, tool)
    if box is not None and (box[0] >= box[1] or any(abs(c) > MAX_COORDINATE for c in box)):
        bad.add("inputs.base_box")
    check_request(DESIGN, raw, bad, cost_limit=10**8)
