"""Input and result paths of design studies."""

from __future__ import annotations

import math
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from worker.studies.paths import (
    nearest_place,
    parse_input_path,
    parse_result_path,
    read_result,
    show_input_path,
    varied_input_problem,
    with_input,
)

RESULT: dict[str, Any] = {
    "optimum": {"eta": 0.42, "converged": True, "label": "x"},
    "task_points": [{"label": "A", "d_z": 1.0}, {"label": "B", "d_z": 0.75}, {"d_z": 0.5}],
    "links": [15.0, 14.0, 8.0],
    "empty": [],
    "nested": {"rows": [[1.0, 2.0], [3.0]]},
    "nan": float("nan"),
}


@pytest.mark.parametrize(
    ("text", "path"),
    [
        ("alpha1_deg", ("alpha1_deg",)),
        ("links[0]", ("links", 0)),
        ("workspace.tilt_max_deg", ("workspace", "tilt_max_deg")),
        ("chains[0].lengths[2]", ("chains", 0, "lengths", 2)),
        ("grid[1][0]", ("grid", 1, 0)),
    ],
)
def test_input_paths(text: str, path: tuple[Any, ...]) -> None:
    assert parse_input_path(text) == path


@pytest.mark.parametrize(
    "text", ["", "1abc", "links[]", "links[-1]", "a..b", "a b", "links[0", "a.", 42, "x" * 201]
)
def test_bad_input_paths_are_refused(text: Any) -> None:
    with pytest.raises(ValueError, match="path"):
        parse_input_path(text)


def test_with_input_copies_and_sets() -> None:
    fixed = {"chains": [{"lengths": [1, 2, 3]}], "links": [15, 14, 8]}
    changed = with_input(fixed, parse_input_path("chains[0].lengths[2]"), 9.5)
    assert changed["chains"][0]["lengths"] == [1, 2, 9.5]
    assert fixed["chains"][0]["lengths"] == [1, 2, 3]  # the original is untouched
    assert with_input({}, ("delta",), 1.5) == {"delta": 1.5}
    assert with_input({}, ("workspace", "tilt_max_deg"), 30.0) == {
        "workspace": {"tilt_max_deg": 30.0}
    }


@pytest.mark.parametrize(
    ("fixed", "text", "message"),
    [
        (
            {"links": [1, 2, 3]},
            "links[3]",
            r"'links' in 'fixed' is a list of 3: it has no element \[3\]",
        ),
        ({}, "links[0]", "'fixed' has no list 'links': a varied list element must be in a list"),
        ({"ground": 0}, "lengths[0]", "'fixed' has no list 'lengths'"),
        ({}, "chains[0].lengths[2]", "'fixed' has no list 'chains'"),
        (
            {"chains": [{"name": "a"}]},
            "chains[0].lengths[2]",
            r"'fixed' has no list 'chains\[0\].lengths'",
        ),
        ({"links": 5}, "links.first", "'links' in 'fixed' is the number 5, not a mapping"),
        ({"links": {"a": 1}}, "links[0]", "'links' in 'fixed' is a mapping, not a list"),
        ({"links": "abc"}, "links[0]", "'links' in 'fixed' is a text, not a list"),
    ],
)
def test_with_input_refuses_what_is_not_there(
    fixed: dict[str, Any], text: str, message: str
) -> None:
    with pytest.raises(ValueError, match=message):
        with_input(fixed, parse_input_path(text), 1.0)


FIXED: dict[str, Any] = {"links": [15, 14, 8], "grid": {"points_per_axis": 5}, "unit": "cm"}


@pytest.mark.parametrize(
    ("text", "earlier", "message"),
    [
        ("links[2]", [], None),
        ("grid.bounds", [], None),  # a missing key is created
        ("workspace.tilt_max_deg", ["links[0]"], None),  # a mapping on the way too
        ("links[3]", [], "is a list of 3"),
        ("chains[0]", [], "'fixed' has no list 'chains'"),
        ("unit.x", [], "'unit' in 'fixed' is a text, not a mapping"),
        ("grid.points_per_axis", [], "both fixed and varied"),
        ("links", [], "both fixed and varied"),
        ("links[1]", ["links[01]"], "names the same input as 'links[01]'"),
        ("workspace.tilt_max_deg", ["workspace"], "lies inside 'workspace'"),
        ("workspace", ["workspace.tilt_max_deg"], "holds 'workspace.tilt_max_deg'"),
    ],
)
def test_varied_input_problems(text: str, earlier: list[str], message: str | None) -> None:
    others = {name: parse_input_path(name) for name in earlier}
    problem = varied_input_problem(FIXED, parse_input_path(text), others)
    assert problem is None if message is None else message in (problem or ""), problem


@pytest.mark.parametrize(
    ("text", "missing", "place"),
    [
        ("links[1]", False, "links[1]"),
        ("links[7]", False, "links"),
        ("grid.points_per_axis", False, "grid.points_per_axis"),
        ("grid.points", False, "grid"),
        ("grid.points", True, "grid.points"),  # a missing member names itself
        ("grid.points.deeper", True, "grid.points"),
        ("unit.x", True, "unit"),
        ("chains[0].loops[0]", True, "chains"),
        ("chains[0].loops[0]", False, ""),
    ],
)
def test_the_nearest_place_is_what_the_document_holds(text: str, missing: bool, place: str) -> None:
    found = nearest_place(FIXED, parse_input_path(text), missing=missing)
    assert show_input_path(found) == place


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("optimum.eta", 0.42),
        ("task_points[].d_z|min", 0.5),
        ("task_points[].d_z|max", 1.0),
        ("task_points[].d_z|mean", 0.75),
        ("task_points[1].d_z", 0.75),
        ("links|sum", 37.0),
        ("links[2]", 8.0),
        ("links|max", 15.0),
        ("empty|sum", 0.0),
        ("nested.rows[]|sum", 6.0),
        ("empty|min", None),
        ("optimum.converged", None),  # a flag is not a number
        ("optimum.label", None),
        ("optimum.missing", None),
        ("links", None),  # a list needs a reduction
        ("links[7]", None),
        ("nan", None),
        ("task_points[].label|min", None),
    ],
)
def test_read_result(text: str, value: float | None) -> None:
    assert read_result(RESULT, parse_result_path(text)) == value


@pytest.mark.parametrize(
    ("text", "message"),
    [("task_points[].d_z", r"reduce them"), ("links|median", "one of min, max"),
     ("links|", "one of min")],
)  # fmt: skip
def test_bad_result_paths_are_refused(text: str, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        parse_result_path(text)


@settings(max_examples=200, deadline=None, derandomize=True)
@given(st.lists(st.floats(-1e6, 1e6), max_size=20), st.sampled_from(["min", "max", "mean", "sum"]))
def test_reductions_match_python(values: list[float], reduction: str) -> None:
    got = read_result({"v": [{"x": v} for v in values]}, parse_result_path(f"v[].x|{reduction}"))
    if reduction == "sum":
        assert got == pytest.approx(math.fsum(values))
    elif not values:
        assert got is None
    else:
        expected = {"min": min, "max": max, "mean": lambda v: math.fsum(v) / len(v)}[reduction]
        assert got == pytest.approx(expected(values))
