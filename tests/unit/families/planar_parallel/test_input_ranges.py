"""Every accepted input computes: ``planar2dof-conditioning-map`` and ``planar2dof-optimisation``.

Each process declares the numeric ranges it supports in its input schema (the shared
convention of :mod:`worker.common.numeric_ranges`, narrowed where the method needs it).
Property tests draw raw requests across those ranges, their ends and just outside: a
value outside must be refused at validation with an error naming its field; a request
that validates must run as the worker runs it (the stored JSON validated again, plots
on) and finish with a JSON-clean result and non-empty artifacts, never raise.

Rendering takes about a second a figure, so the running tests draw few examples, always
the same ones; set ``DEXLAB_PROPERTY_EXAMPLES=200`` to search longer, with fresh
examples each time. The validation-only tests draw more.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping
from typing import Any

import pytest
from hypothesis import HealthCheck, assume, event, example, given, settings
from hypothesis import strategies as st

from tests.unit.families.conftest import RecordingContext
from worker.common.numeric_ranges import MAX_COORDINATE, MAX_LENGTH, MIN_LENGTH, MIN_STEP
from worker.errors import InvalidInputs
from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.optimisation_spec import eq17_reach
from worker.processes import ProcessDefinition
from worker.registry import default_registry
from worker.submission import validate_inputs

RUN_EXAMPLES = int(os.environ.get("DEXLAB_PROPERTY_EXAMPLES", "0"))


def property_settings(examples: int) -> Any:
    return settings(
        max_examples=RUN_EXAMPLES or examples,
        deadline=None,
        derandomize=not RUN_EXAMPLES,  # a longer search explores new examples each time
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
    )


def definition(process_id: str) -> ProcessDefinition:
    found = default_registry().get(process_id)
    assert found is not None
    return found


MAP = definition("planar2dof-conditioning-map")
OPT = definition("planar2dof-optimisation")
#: The map's W_kappa0 search (257,121) and a grid of up to 301² nodes; the optimisation's
#: single delta (S_max over the paper's 151 deltas) or a short sweep, mesh up to 1001².
MAP_RUN_COST = 400_000
OPT_RUN_COST = 10_500_000


# -- the declared ranges, as an oracle -------------------------------------------------


def _outside(value: Any, lo: float, hi: float, *, hi_open: bool = False) -> bool:
    """Whether a number lies outside [lo, hi] ([lo, hi) if ``hi_open``); None passes."""
    if not isinstance(value, int | float):
        return False
    return not (lo <= value < hi if hi_open else lo <= value <= hi)


def map_outside(raw: Mapping[str, Any]) -> set[str]:
    """The fields of a map request holding a value outside its declared range."""
    found = {f"inputs.{name}" for name in ("l1", "l2")
             if _outside(raw.get(name), MIN_LENGTH, MAX_LENGTH)}  # fmt: skip
    e = raw.get("e")
    if isinstance(e, float) and e != 0.0 and _outside(e, MIN_LENGTH, MAX_LENGTH):
        found.add("inputs.e")
    if _outside(raw.get("inverse_condition_limit"), 1e-6, 1.0, hi_open=True):
        found.add("inputs.inverse_condition_limit")
    bounds = (raw.get("grid") or {}).get("bounds") or ()
    if any(_outside(v, -MAX_COORDINATE, MAX_COORDINATE) for v in bounds):
        found.add("inputs.grid.bounds")
    for point in raw.get("points") or ():
        if any(_outside(v, -MAX_COORDINATE, MAX_COORDINATE) for v in point):
            found.add("inputs.points")
    return found


def opt_outside(raw: Mapping[str, Any]) -> set[str]:
    """The fields of an optimisation request holding a value outside its declared range."""
    checks = {
        "allowable_pressure_angle_deg": (1.0, 90.0, True),
        "inverse_condition_limit": (1e-6, 1.0, True),
        "aspect_ratio": (0.01, 100.0, False),
        "delta_step": (MIN_STEP, 10.0, False),
        "delta": (1.0, 10.0, False),
    }
    found = {f"inputs.{name}" for name, (lo, hi, hi_open) in checks.items()
             if _outside(raw.get(name), lo, hi, hi_open=hi_open)}  # fmt: skip
    if any(_outside(v, 1.0, 10.0) for v in raw.get("delta_range") or ()):
        found.add("inputs.delta_range")
    return found


# -- drawing requests ------------------------------------------------------------------


@st.composite
def mixed(
    draw: st.DrawFn, inside: st.SearchStrategy[Any], beyond: st.SearchStrategy[Any], outside: int
) -> Any:
    """A draw of ``inside``, or ``outside`` times in 100 of ``beyond`` (sampled, not an
    integer compared: Hypothesis draws small integers far more often than 1 in 100)."""
    leave = draw(st.sampled_from([False] * (100 - outside) + [True] * outside))
    return draw(beyond if leave else inside)


def magnitude(lo: float, hi: float, outside: int) -> st.SearchStrategy[float]:
    """Values of [lo, hi] (lo > 0): its ends or log-uniform inside; ``outside`` times in
    100 just outside (the next float) or far outside (5e-324, 1e300)."""
    inside = st.one_of(
        st.sampled_from([lo, hi]),
        st.floats(math.log10(lo), math.log10(hi)).map(lambda p: min(max(10.0**p, lo), hi)),
    )
    beyond = st.sampled_from([math.nextafter(lo, 0.0), math.nextafter(hi, math.inf), 5e-324,
                              1e300])  # fmt: skip
    return mixed(inside, beyond, outside)


def within(lo: float, hi: float, outside: int, beyond: float = 1.1) -> st.SearchStrategy[float]:
    """[lo, hi] (lo > 0) on a log scale, ends likely; ``outside`` times in 100 the range
    stretched by ``beyond`` either way (which may or may not leave the declared range)."""
    inside = st.one_of(
        st.sampled_from([lo, hi, math.sqrt(lo * hi)]),
        st.floats(math.log10(lo), math.log10(hi)).map(lambda p: min(max(10.0**p, lo), hi)),
    )
    return mixed(inside, st.sampled_from([lo / beyond, hi * beyond]), outside)


def coordinate(outside: int) -> st.SearchStrategy[float]:
    inside = st.one_of(st.sampled_from([-MAX_COORDINATE, MAX_COORDINATE, 0.0]),
                       st.floats(-MAX_COORDINATE, MAX_COORDINATE))  # fmt: skip
    return mixed(inside, st.just(math.nextafter(MAX_COORDINATE, math.inf)), outside)


def fraction(outside: int, beyond: float) -> st.SearchStrategy[float]:
    """A conditioning limit in [1e-6, 1): its ends, the paper's 0.5 or uniform."""
    inside = st.one_of(st.sampled_from([1e-6, math.nextafter(1.0, 0.0), 0.5]),
                       st.floats(1e-6, 0.999999))  # fmt: skip
    return mixed(inside, st.just(beyond), outside)


def grid_side(size: float, points: int, outside: int) -> st.SearchStrategy[tuple[float, float]]:
    """(min, max) of a grid axis: a side within a factor 1e6 of the robot's size (steps of
    at least 1e-6; rarely beyond both), centred on the robot or at the edge of the
    coordinate range."""
    lo = max(size / 1e6, MIN_STEP * (points - 1))
    hi = min(size * 1e6, 2 * MAX_COORDINATE)
    if lo > hi:
        return st.just((-hi / 2, hi / 2))

    def place(side: float, where: int) -> tuple[float, float]:
        if where == 0:
            return -side / 2, side / 2
        edge = MAX_COORDINATE if where == 1 else -MAX_COORDINATE + side
        return edge - side, edge

    return st.tuples(within(lo, hi, outside), st.integers(0, 2)).map(lambda p: place(*p))


@st.composite
def map_requests(draw: st.DrawFn, outside: int = 4) -> dict[str, Any]:
    """Robots of every type and scale (their lengths within a factor 1e6), with or without
    a grid of their own, a limit and points."""
    actuation = draw(st.sampled_from(["proximal-arm", "telescopic-leg", "linear-drive"]))
    l1 = draw(magnitude(MIN_LENGTH, MAX_LENGTH, outside))
    near = (max(MIN_LENGTH, l1 / 1e6), min(MAX_LENGTH, l1 * 1e6)) if l1 > 0 else (1.0, 1.0)
    raw: dict[str, Any] = {
        "actuation": actuation,
        "l1": l1,
        "l2": draw(within(*near, outside)) if near[0] <= near[1] else 1.0,
        "working_mode": draw(st.sampled_from([[1, -1], [1, 1], [-1, 1], [-1, -1]])),
        "plots": True,
    }
    if actuation == "proximal-arm" and draw(st.booleans()):
        raw["architecture"] = "isotropic"
        raw["l2"] = max(raw["l2"], l1)
    elif actuation != "linear-drive" or draw(st.booleans()):
        lengths = (l1, raw["l2"])
        span = (max(MIN_LENGTH, max(lengths) / 1e6), min(MAX_LENGTH, min(lengths) * 1e6))
        e = st.just(0.0) if span[0] > span[1] else st.one_of(st.just(0.0), within(*span, outside))
        raw["e"] = draw(mixed(e, st.just(5e-324), outside))
    size = max(l1, raw["l2"], raw.get("e") or 0.0)
    count = draw(st.sampled_from([2, 3, 21, 301, 2001]))
    grid: dict[str, Any] = {"points_per_axis": count}
    if draw(st.booleans()):
        (x0, x1), (y0, y1) = (draw(grid_side(size, count, outside)) for _ in range(2))
        grid["bounds"] = [x0, x1, y0, y1]
    raw["grid"] = grid
    if draw(st.booleans()):
        raw["inverse_condition_limit"] = draw(fraction(outside, 1.0))
    if draw(st.booleans()):
        close = st.tuples(st.floats(-2.0, 2.0), st.floats(-2.0, 2.0)).map(
            lambda p: [p[0] * size, p[1] * size]
        )
        anywhere = st.lists(coordinate(outside), min_size=2, max_size=2)
        raw["points"] = draw(st.lists(st.one_of(close, anywhere), min_size=1, max_size=3))
    return raw


@st.composite
def optimisation_requests(draw: st.DrawFn, outside: int = 4) -> dict[str, Any]:
    raw: dict[str, Any] = {"plots": True}
    if draw(st.booleans()):
        inside = st.one_of(st.sampled_from([1.0, math.nextafter(90.0, 0.0), 30.0]),
                           st.floats(1.0, 89.999))  # fmt: skip
        raw["allowable_pressure_angle_deg"] = draw(mixed(inside, st.just(0.5), outside))
    else:
        raw["inverse_condition_limit"] = draw(fraction(outside, 5e-324))
    raw["aspect_ratio"] = draw(magnitude(0.01, 100.0, outside))
    raw["mean_mesh"] = draw(st.sampled_from([2, 3, 11, 1001]))
    if draw(st.integers(0, 2)) == 0:
        raw["delta"] = draw(st.one_of(st.sampled_from([1.0, 10.0]), st.floats(1.0, 10.0)))
        return raw
    ends = st.one_of(st.sampled_from([1.0, 10.0, 2.5]), st.floats(1.0, 10.0))
    lo, hi = sorted(draw(st.lists(ends, min_size=2, max_size=2, unique=True)))
    raw["delta_range"] = [lo, hi]
    steps = st.sampled_from([10.0, hi - lo, max((hi - lo) / 2, MIN_STEP), MIN_STEP])
    raw["delta_step"] = draw(mixed(steps, st.just(5e-324), outside))
    return raw


# -- the check -------------------------------------------------------------------------


def validated(process: ProcessDefinition, raw: dict[str, Any], outside: set[str]) -> Any:
    """The validated inputs, or None when refused (naming an out-of-range field if any)."""
    try:
        inputs = validate_inputs(process, raw)
    except InvalidInputs as exc:
        fields = [error["field"] for error in exc.errors]
        assert fields and all(field.startswith("inputs") for field in fields)
        if outside:
            assert any(field.startswith(path) for field in fields for path in outside), (
                fields, outside,
            )  # fmt: skip
        return None
    assert not outside, f"accepted although outside the declared ranges: {sorted(outside)}"
    return inputs


def run_like_the_worker(process: ProcessDefinition, inputs: Any) -> None:
    """The stored JSON validated again, run with plots on: a clean result and files."""
    stored = json.loads(json.dumps(inputs.model_dump(mode="json"), allow_nan=False))
    again = process.inputs_model.model_validate(stored)
    assert again == inputs
    ctx = RecordingContext()
    outcome = process.run(again, ctx)
    json.dumps(outcome.result, allow_nan=False)
    assert outcome.artifacts
    assert all(artifact.data for artifact in outcome.artifacts), [
        a.name for a in outcome.artifacts if not a.data
    ]
    assert ctx.percents[-1] == 100.0


def check_request(
    process: ProcessDefinition, raw: dict[str, Any], outside: set[str], cost_limit: int
) -> None:
    """Refused at validation, or (within ``cost_limit``) run cleanly."""
    inputs = validated(process, raw, outside)
    event("refused" if inputs is None else "accepted")
    if inputs is not None:
        assume(process.cost(inputs) <= cost_limit)
        run_like_the_worker(process, inputs)


# -- regressions -----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("process", "raw", "field"),
    [
        # the sweep's count used to overflow in the validator (an HTTP 500)
        (OPT, {"inverse_condition_limit": 0.5, "delta_step": 5e-324}, "inputs.delta_step"),
        (OPT, {"inverse_condition_limit": 0.5, "delta_range": [1, 10], "delta_step": 1e-6},
         "inputs.delta_step"),
        # a rectangle 1e-300 wide used to break the figures' layout (LinAlgError)
        (OPT, {"inverse_condition_limit": 1e-300, "aspect_ratio": 1e-300},
         "inputs.inverse_condition_limit"),
        (OPT, {"inverse_condition_limit": 0.5, "aspect_ratio": 1e-300}, "inputs.aspect_ratio"),
        # eq (17) gave a NaN limit (its point out of reach) and the job failed
        (OPT, {"allowable_pressure_angle_deg": 1e-300}, "inputs.allowable_pressure_angle_deg"),
        (OPT, {"allowable_pressure_angle_deg": 30, "delta_range": [9.9, 10]},
         "inputs.delta_range"),
        # squares of these overflowed (or divided 0 by 0) inside the job
        (MAP, {"l1": 1e300, "l2": 1e300, "e": 0}, "inputs.l1"),
        (MAP, {"l1": 1e-300, "l2": 1e-300, "e": 0}, "inputs.l1"),
        (MAP, {"l2": 2, "e": 0.5, "points": [[1e300, 0]]}, "inputs.points[0][0]"),
        (MAP, {"l2": 2, "e": 1e-300}, "inputs.e"),
        (MAP, {"l1": 1e-6, "l2": 1e6, "e": 1}, "inputs.l2"),
        # grid cells 1e-12 wide, or a grid 1e12 times the robot
        (MAP, {"l2": 2, "e": 0.5, "grid": {"bounds": [0, 1e-12, 0, 1]}}, "inputs.grid.bounds"),
        (MAP, {"l1": 1e-6, "l2": 1e-6, "e": 0, "grid": {"bounds": [-1e6, 1e6, -1e6, 1e6]}},
         "inputs.grid.bounds"),
        # the telescopic legs' W_kappa0 search box grows as e / limit: to infinity here
        (MAP, {"actuation": "telescopic-leg", "e": 1, "inverse_condition_limit": 5e-324},
         "inputs.inverse_condition_limit"),
    ],
)  # fmt: skip
def test_extreme_values_are_refused_naming_the_field(
    process: ProcessDefinition, raw: dict[str, Any], field: str
) -> None:
    with pytest.raises(InvalidInputs) as info:
        validate_inputs(process, raw)
    assert field in [error["field"] for error in info.value.errors]


@pytest.mark.parametrize(
    ("process", "raw"),
    [
        # eq (17)'s point leaves the reach beyond delta = 2.62: the limit used to be NaN
        (OPT, {"allowable_pressure_angle_deg": 89.99999999, "delta_range": [1, 10],
               "delta_step": 10, "mean_mesh": 2}),
        (OPT, {"allowable_pressure_angle_deg": 1, "delta_range": [3.7, 3.75],
               "delta_step": 0.05, "mean_mesh": 2, "aspect_ratio": 0.01}),
        # a single delta without a rectangle used to be reported as the design (NaN sizes)
        (OPT, {"inverse_condition_limit": 1e-6, "aspect_ratio": 100, "mean_mesh": 2,
               "delta": 1.0}),
        # the isotropic point's refinement left a thin band of reach: NaN in the result
        (MAP, {"l1": 1e-6, "l2": 1e-3, "architecture": "isotropic", "working_mode": [-1, 1],
               "grid": {"points_per_axis": 2}}),
        # a given point far outside the grid: its label used to collapse the layout
        (MAP, {"actuation": "linear-drive", "l1": 1e-6, "l2": 1e-6,
               "grid": {"points_per_axis": 2}, "points": [[-1e6, -1e6]]}),
        (MAP, {"l1": 1e6, "l2": 1e6, "e": 1e6, "inverse_condition_limit": 1e-6,
               "grid": {"points_per_axis": 2}, "points": [[1e6, -1e6]]}),
        (MAP, {"actuation": "telescopic-leg", "e": 0, "inverse_condition_limit": 0.5,
               "grid": {"points_per_axis": 3}}),
    ],
)  # fmt: skip
def test_extreme_values_compute(process: ProcessDefinition, raw: dict[str, Any]) -> None:
    inputs = validated(process, raw, set())
    assert inputs is not None
    run_like_the_worker(process, inputs)


# -- the kinematics' share of the fixes ------------------------------------------------


def test_eq17_limit_is_maximised_where_its_point_is_in_reach() -> None:
    # beyond delta_+ (2.618 at 90°) eq (17)'s point is out of reach: NaN, never the maximum
    limit, delta = pp.max_condition_limit(89.99999999, (1.0, 10.0))
    assert math.isfinite(limit) and 0.99 < limit < 1.0 and 1.0 <= delta < eq17_reach(90.0)
    wide, at = pp.max_condition_limit(30.0, (1.0, 10.0))  # a second peak near the reach
    assert wide >= pp.max_condition_limit(30.0, (1.0, 2.5))[0] and at < eq17_reach(30.0)
    assert all(math.isnan(v) for v in pp.max_condition_limit(30.0, (9.9, 10.0)))


def test_isotropic_point_stays_in_a_thin_band_of_reach() -> None:
    # l1 = 1e-3 l2: x = 0 is in reach on a band 3e-6 deep, a few of the 4001 samples
    arch = pp.isotropic_architecture(1e-3, 1e-6)
    point = pp.isotropic_point(arch, (-1, 1))
    assert math.isfinite(float(pp.inverse_condition(arch, point, (-1, 1))))


def test_mean_counts_nodes_out_of_reach_by_a_hair_as_zero() -> None:
    # delta = 1: the pivots meet at the origin, which the slender rectangle touches
    sweep = pp.design_sweep(1e-6, [1.0], 0.01, 3, columns=257, rows=160)
    row = sweep.rows[0]
    assert row.rectangle.found and 0.0 < row.mean_inverse_condition < 1.0
    assert math.isfinite(row.eta) and sweep.found


def test_schemas_publish_the_ranges() -> None:
    schema = MAP.inputs_model.model_json_schema()
    props = schema["properties"]
    assert props["l1"]["minimum"] == MIN_LENGTH and props["l1"]["maximum"] == MAX_LENGTH
    assert props["l1"]["x-max-ratio"] == 1e6 and props["e"]["x-max-ratio"] == 1e6
    assert props["inverse_condition_limit"]["anyOf"][0]["minimum"] == 1e-6
    bounds = schema["$defs"]["GridSpec"]["properties"]["bounds"]
    assert bounds["x-max-ratio"] == 1e6
    assert {item["minimum"] for item in bounds["anyOf"][0]["prefixItems"]} == {-MAX_COORDINATE}
    assert "[1e-06, 1e+06]" in props["l1"]["description"]
    props = OPT.inputs_model.model_json_schema()["properties"]
    assert props["delta_step"]["anyOf"][0]["minimum"] == MIN_STEP
    assert props["aspect_ratio"]["minimum"] == 0.01 and props["aspect_ratio"]["maximum"] == 100
    assert props["allowable_pressure_angle_deg"]["anyOf"][0]["minimum"] == 1.0
    assert "at most 10,001 deltas" in props["delta_step"]["description"]


# -- properties ------------------------------------------------------------------------


@property_settings(25)
@given(map_requests(outside=25))
def test_map_ranges_refuse_outside_values(raw: dict[str, Any]) -> None:
    inputs = validated(MAP, raw, map_outside(raw))
    if inputs is not None:
        assert MAP.inputs_model.model_validate(inputs.model_dump(mode="json")) == inputs
        assert 0 < MAP.cost(inputs) <= 5_000_000


@property_settings(25)
@given(optimisation_requests(outside=25))
def test_optimisation_ranges_refuse_outside_values(raw: dict[str, Any]) -> None:
    inputs = validated(OPT, raw, opt_outside(raw))
    if inputs is not None:
        assert OPT.inputs_model.model_validate(inputs.model_dump(mode="json")) == inputs
        assert OPT.cost(inputs) > 0


@property_settings(15)
@example({"l1": 1e-6, "l2": 1.0, "e": 1e-6, "grid": {"points_per_axis": 2},
          "inverse_condition_limit": math.nextafter(1.0, 0.0), "plots": True})  # fmt: skip
@given(map_requests())
def test_every_accepted_map_request_computes(raw: dict[str, Any]) -> None:
    check_request(MAP, raw, map_outside(raw), MAP_RUN_COST)


@property_settings(4)
@given(optimisation_requests())
def test_every_accepted_optimisation_request_computes(raw: dict[str, Any]) -> None:
    check_request(OPT, raw, opt_outside(raw), OPT_RUN_COST)
