"""Every accepted input computes: ``spm-conditioning-map``, ``spm-design-space`` and
``spm-optimisation``.

As in :mod:`tests.unit.families.planar_parallel.test_input_ranges` (whose checks these
tests share): raw requests are drawn across the declared ranges (link and pyramid angles
and the cone's half-opening in [1e-6, 180 - 1e-6], gamma from 0, torsion ranges of at
least 1e-6°, steps of at least 1e-6°, bounded counts), their ends and just outside; an
out-of-range value must be refused naming its field, an accepted request must run as
the worker runs it, plots on, and finish cleanly.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from tests.unit.families.planar_parallel.test_input_ranges import (
    check_request,
    definition,
    mixed,
    property_settings,
    run_like_the_worker,
    validated,
)
from worker.common.numeric_ranges import MIN_STEP
from worker.errors import InvalidInputs
from worker.families.spherical_parallel.workspace_spec import narrower_than
from worker.submission import validate_inputs

MAP = definition("spm-conditioning-map")
SPACE = definition("spm-design-space")
OPT = definition("spm-optimisation")
MARGIN, TOP = 1e-6, 180.0 - 1e-6
#: The optimisation has no synchronous limit: a couple of short starts on a few samples.
OPT_RUN_COST = 700_000


# -- the declared ranges, as an oracle -------------------------------------------------


def _out(value: Any, lo: float, hi: float) -> bool:
    return isinstance(value, int | float) and not lo <= value <= hi


def _angles_outside(raw: Mapping[str, Any], names: tuple[str, ...]) -> set[str]:
    found = {f"inputs.{n}" for n in names if _out(raw.get(n), MARGIN, TOP)}
    if _out(raw.get("gamma_deg"), 0.0, TOP):
        found.add("inputs.gamma_deg")
    return found


def workspace_outside(workspace: Mapping[str, Any]) -> set[str]:
    found = set()
    if _out(workspace.get("tilt_max_deg"), MARGIN, TOP):
        found.add("inputs.workspace.tilt_max_deg")
    lo, hi = workspace.get("torsion_deg", (0.0, 360.0))
    if (
        _out(lo, -360, 360)
        or _out(hi, -360, 360)
        or not 0 < hi - lo <= 360
        or (narrower_than(lo, hi, MIN_STEP))
    ):
        found.add("inputs.workspace.torsion_deg")
    if any(_out(n, 1, 360) for n in (workspace.get("samples") or {}).values()):
        found.add("inputs.workspace.samples")
    return found


def map_outside(raw: Mapping[str, Any]) -> set[str]:
    found = _angles_outside(raw, ("alpha1_deg", "alpha2_deg", "beta_deg"))
    found |= workspace_outside(raw["workspace"])
    for psi1, psi2, psi3 in raw.get("orientations") or ():
        if _out(psi1, -360, 360) or _out(psi2, 0, 180) or _out(psi3, -360, 360):
            found.add("inputs.orientations")
    if any(_out(v, -360, 360) for v in raw.get("map_torsions_deg") or ()):
        found.add("inputs.map_torsions_deg")
    for psi1, psi2 in raw.get("torsion_sweeps") or ():
        if _out(psi1, -360, 360) or _out(psi2, 0, 180):
            found.add("inputs.torsion_sweeps")
    return found


def space_outside(raw: Mapping[str, Any]) -> set[str]:
    found = _angles_outside(raw, ()) | workspace_outside(raw["workspace"])
    betas = raw["beta_deg"]
    if isinstance(betas, dict):
        if _out(betas["start"], MARGIN, TOP) or _out(betas["stop"], MARGIN, TOP):
            found.add("inputs.beta_deg")
        if _out(betas["step"], MIN_STEP, 180):
            found.add("inputs.beta_deg.step")
    elif any(_out(b, MARGIN, TOP) for b in betas):
        found.add("inputs.beta_deg")
    if _out((raw.get("index_map") or {}).get("beta_deg"), MARGIN, TOP):
        found.add("inputs.index_map.beta_deg")
    return found


def opt_outside(raw: Mapping[str, Any]) -> set[str]:
    found = _angles_outside(raw, ("alpha1_deg", "alpha2_deg", "beta_deg"))
    found |= workspace_outside(raw["workspace"])
    for name, low in (("beta_deg", MARGIN), ("gamma_deg", 0.0)):
        pair = (raw.get("bounds") or {}).get(name)
        if pair and (_out(pair[0], low, TOP) or _out(pair[1], low, TOP)
                     or narrower_than(pair[0], pair[1], MIN_STEP)):  # fmt: skip
            found.add(f"inputs.bounds.{name}")
    if _out(raw.get("singularity_tolerance"), 1e-12, math.nextafter(1.0, 0.0)):
        found.add("inputs.singularity_tolerance")
    return found


# -- drawing requests ------------------------------------------------------------------


def angle(outside: int) -> st.SearchStrategy[float]:
    """A link or pyramid angle: the ends, 90, uniform, within a decade or six of 0 or 180;
    rarely just outside (0, 5e-324, the next float, 180, 180 - 1 ulp)."""
    near = st.floats(-6.0, 0.0).map(lambda p: max(10.0**p, MARGIN))
    inside = st.one_of(st.sampled_from([MARGIN, TOP, 90.0]), st.floats(MARGIN, TOP), near,
                       near.map(lambda v: 180.0 - v))  # fmt: skip
    beyond = st.sampled_from([0.0, 5e-324, math.nextafter(MARGIN, 0.0),
                              math.nextafter(TOP, 180.0), 180.0 - 2.0**-45])  # fmt: skip
    return mixed(inside, beyond, outside)


def gamma(outside: int) -> st.SearchStrategy[float]:
    inside = st.one_of(st.just(0.0), st.just(5e-324), angle(0))
    return mixed(inside, st.sampled_from([-5e-324, 180.0]), outside)


@st.composite
def workspaces(draw: st.DrawFn, outside: int, samples: int = 3) -> dict[str, Any]:
    """A cone (every half-opening), a full turn from anywhere or a limited torsion range
    (from 1e-6° wide), sparse samples."""
    workspace: dict[str, Any] = {"tilt_max_deg": draw(angle(outside))}
    kind = draw(st.integers(0, 2))
    if kind == 1:
        lo = draw(st.one_of(st.sampled_from([-360.0, 0.0]), st.floats(-360.0, 0.0)))
        workspace["torsion_deg"] = [lo, lo + 360.0]
    elif kind == 2:
        width = draw(mixed(st.one_of(st.sampled_from([MIN_STEP, 30.0, 359.0]),
                                     st.floats(-6.0, 2.5).map(lambda p: 10.0**p)),
                           st.sampled_from([5e-7, 400.0]), outside))  # fmt: skip
        lo = draw(st.one_of(st.sampled_from([-360.0, -width / 2, 360.0 - width]),
                            st.floats(-360.0, max(-360.0, 360.0 - width))))  # fmt: skip
        workspace["torsion_deg"] = [lo, lo + width]
    counts = st.integers(1, samples)
    workspace["samples"] = {
        "azimuth": draw(counts),
        "tilt": draw(mixed(counts, st.sampled_from([0, 361]), outside)),
        "torsion": draw(counts),
    }
    return workspace


def designs(outside: int) -> st.SearchStrategy[dict[str, Any]]:
    return st.fixed_dictionaries(
        {"alpha1_deg": angle(outside), "alpha2_deg": angle(outside), "beta_deg": angle(outside)},
        optional={"gamma_deg": gamma(outside)},
    )


@st.composite
def map_requests(draw: st.DrawFn, outside: int = 4) -> dict[str, Any]:
    raw = draw(designs(outside)) | {"workspace": draw(workspaces(outside)), "plots": True}
    raw["branch"] = draw(st.sampled_from([-1, 1]))
    raw["map_grid"] = {"azimuth": draw(st.sampled_from([5, 13])), "tilt": draw(st.sampled_from(
        [2, 5]))}  # fmt: skip
    turn = st.one_of(st.sampled_from([-360.0, 360.0, 0.0]), st.floats(-360.0, 360.0))
    tilt = st.one_of(st.sampled_from([0.0, 180.0]), st.floats(0.0, 180.0))
    beyond = st.sampled_from([math.nextafter(360.0, 400.0), -1e300])
    if draw(st.booleans()):
        raw["orientations"] = draw(st.lists(st.tuples(turn, mixed(tilt, beyond, outside), turn)
                                            .map(list), min_size=1, max_size=3))  # fmt: skip
    if draw(st.booleans()):
        raw["map_torsions_deg"] = draw(st.lists(mixed(turn, beyond, outside), min_size=1,
                                                max_size=2))  # fmt: skip
    if draw(st.booleans()):
        raw["torsion_sweeps"] = draw(st.lists(st.tuples(turn, tilt).map(list), min_size=1,
                                              max_size=2))  # fmt: skip
    return raw


@st.composite
def beta_selections(draw: st.DrawFn, outside: int) -> Any:
    if draw(st.booleans()):
        return draw(st.lists(angle(outside), min_size=1, max_size=3))
    start, stop = sorted(draw(st.lists(angle(outside), min_size=2, max_size=2)))
    steps = st.sampled_from([MIN_STEP, 180.0, max(stop - start, MIN_STEP),
                             max((stop - start) / 2, MIN_STEP),
                             max((stop - start) / 60, MIN_STEP)])  # fmt: skip
    beyond = st.sampled_from([5e-324, math.nextafter(MIN_STEP, 0.0), 181.0])
    return {"start": start, "stop": stop, "step": draw(mixed(steps, beyond, outside))}


@st.composite
def space_requests(draw: st.DrawFn, outside: int = 4) -> dict[str, Any]:
    raw: dict[str, Any] = {"workspace": draw(workspaces(outside)), "plots": True}
    raw["beta_deg"] = draw(beta_selections(outside))
    if draw(st.booleans()):
        raw["identical_platforms"] = True
    elif draw(st.booleans()):
        raw["gamma_deg"] = draw(gamma(outside))
    if draw(st.booleans()):
        raw["index_map"] = {"beta_deg": draw(angle(outside)),
                            "points_per_side": draw(st.sampled_from([3, 5])),
                            "branch": draw(st.sampled_from([-1, 1]))}  # fmt: skip
    return raw


@st.composite
def optimisation_requests(draw: st.DrawFn, outside: int = 4) -> dict[str, Any]:
    raw: dict[str, Any] = {"workspace": draw(workspaces(outside, samples=2)), "plots": True,
                           "starts": draw(st.sampled_from([1, 2])),
                           "max_evaluations_per_start": 5,
                           "seed": draw(st.sampled_from([0, 2**32 - 1])),
                           "branch": draw(st.sampled_from([-1, 1]))}  # fmt: skip
    identical = draw(st.booleans())
    names = ["alpha1", "alpha2", "beta"] + ([] if identical else ["gamma"])
    free = draw(st.lists(st.sampled_from(names), min_size=1, max_size=len(names), unique=True))
    raw |= {"identical_platforms": identical, "free": free}
    for name in ("alpha1", "alpha2", "beta"):
        if name not in free:
            raw[f"{name}_deg"] = draw(angle(outside))
    if "gamma" not in free and not identical and draw(st.booleans()):
        raw["gamma_deg"] = draw(gamma(outside))
    bounds = {}
    for name in ("beta", "gamma"):
        if name in free and draw(st.booleans()):
            lo, hi = sorted(draw(st.lists(angle(outside), min_size=2, max_size=2)))
            hi = draw(st.sampled_from([hi, lo + MIN_STEP]))
            bounds[f"{name}_deg"] = [0.0 if name == "gamma" and lo < 1 else lo, hi]
    if bounds:
        raw["bounds"] = bounds
    if draw(st.booleans()):
        raw["singularity_tolerance"] = draw(mixed(
            st.sampled_from([1e-12, math.nextafter(1.0, 0.0), 0.01]), st.just(5e-324), outside
        ))  # fmt: skip
    return raw


# -- regressions -----------------------------------------------------------------------

BIG = {"workspace": {"tilt_max_deg": 45}}


@pytest.mark.parametrize(
    ("process", "raw", "field"),
    [
        # the request: the count of betas used to overflow in the validator
        (SPACE, {**BIG, "beta_deg": {"start": 1, "step": 5e-324, "stop": 2}},
         "inputs.beta_deg.step"),
        (SPACE, {**BIG, "beta_deg": {"start": 1, "step": 1e-6, "stop": 179}},
         "inputs.beta_deg.step"),
        (SPACE, {**BIG, "beta_deg": [5e-324]}, "inputs.beta_deg[0]"),
        (SPACE, {**BIG, "beta_deg": [60], "index_map": {"beta_deg": 180 - 2**-45}},
         "inputs.index_map.beta_deg"),
        # radians(5e-324 deg) is 0: SpmDesign used to refuse it inside the job
        (MAP, {**BIG, "alpha1_deg": 5e-324, "alpha2_deg": 90, "beta_deg": 90},
         "inputs.alpha1_deg"),
        (MAP, {"workspace": {"tilt_max_deg": 5e-324}, "alpha1_deg": 90, "alpha2_deg": 90,
               "beta_deg": 90}, "inputs.workspace.tilt_max_deg"),
        (MAP, {"workspace": {"tilt_max_deg": 45, "torsion_deg": [0, 1e-300]},
               "alpha1_deg": 90, "alpha2_deg": 90, "beta_deg": 90},
         "inputs.workspace.torsion_deg"),
        (OPT, {**BIG, "singularity_tolerance": 5e-324}, "inputs.singularity_tolerance"),
        (OPT, {**BIG, "free": ["alpha1", "alpha2", "beta", "gamma"],
               "bounds": {"gamma_deg": [10, 10 + 1e-9]}}, "inputs.bounds.gamma_deg"),
        (OPT, {**BIG, "free": ["alpha1", "alpha2"], "beta_deg": 179.99999999999997},
         "inputs.beta_deg"),
    ],
)  # fmt: skip
def test_extreme_values_are_refused_naming_the_field(process: Any, raw: dict[str, Any],
                                                     field: str) -> None:  # fmt: skip
    with pytest.raises(InvalidInputs) as info:
        validate_inputs(process, raw)
    assert field in [error["field"] for error in info.value.errors]


TINY = {"tilt_max_deg": MARGIN, "torsion_deg": [360 - MIN_STEP, 360],
        "samples": {"azimuth": 1, "tilt": 1, "torsion": 2}}  # fmt: skip


@pytest.mark.parametrize(
    ("process", "raw"),
    [
        # Extreme angles of a design that reaches its workspace (one that reaches none,
        # e.g. beta = MARGIN here, is refused: test_impossible_designs.py).
        (MAP, {"workspace": TINY, "alpha1_deg": MARGIN, "alpha2_deg": TOP, "beta_deg": TOP,
               "gamma_deg": TOP, "map_grid": {"azimuth": 5, "tilt": 2},
               "orientations": [[-360, 180, 360]]}),
        (SPACE, {"workspace": {**TINY, "tilt_max_deg": TOP}, "identical_platforms": True,
                 "beta_deg": {"start": MARGIN, "stop": TOP, "step": 90},
                 "index_map": {"beta_deg": MARGIN, "points_per_side": 3}}),
        (OPT, {"workspace": TINY, "starts": 1, "max_evaluations_per_start": 5,
               "free": ["alpha1", "alpha2", "beta", "gamma"], "singularity_tolerance": 1e-12,
               "bounds": {"beta_deg": [MARGIN, TOP], "gamma_deg": [TOP - 2e-6, TOP]}}),
    ],
)  # fmt: skip
def test_extreme_values_compute(process: Any, raw: dict[str, Any]) -> None:
    inputs = validated(process, raw, set())
    assert inputs is not None
    run_like_the_worker(process, inputs)


def test_schemas_publish_the_ranges() -> None:
    props = MAP.inputs_model.model_json_schema()["properties"]
    assert props["alpha1_deg"]["minimum"] == MARGIN and props["alpha1_deg"]["maximum"] == TOP
    assert props["gamma_deg"]["minimum"] == 0 and props["gamma_deg"]["maximum"] == TOP
    assert "in [1e-06, 180 - 1e-06]" in props["beta_deg"]["description"]
    schema = SPACE.inputs_model.model_json_schema()
    step = schema["$defs"]["BetaRange"]["properties"]["step"]
    assert step["minimum"] == MIN_STEP and "at most 721 betas" in step["description"]
    tilt = schema["$defs"]["WorkspaceSpec"]["properties"]["tilt_max_deg"]
    assert tilt["minimum"] == MARGIN and tilt["maximum"] == TOP
    props = OPT.inputs_model.model_json_schema()["properties"]
    assert props["singularity_tolerance"]["anyOf"][0]["minimum"] == 1e-12


# -- properties ------------------------------------------------------------------------

CASES = [
    (MAP, map_requests, map_outside),
    (SPACE, space_requests, space_outside),
    (OPT, optimisation_requests, opt_outside),
]


@pytest.mark.parametrize(
    ("process", "requests", "outside"), CASES, ids=["map", "space", "optimisation"]
)
def test_ranges_refuse_outside_values(process: Any, requests: Any, outside: Any) -> None:
    @property_settings(25)
    @given(requests(outside=25))
    def check(raw: dict[str, Any]) -> None:
        inputs = validated(process, raw, outside(raw))
        if inputs is not None:
            assert process.inputs_model.model_validate(inputs.model_dump(mode="json")) == inputs
            assert process.cost(inputs) > 0

    check()


@property_settings(12)
@given(map_requests())
def test_every_accepted_map_request_computes(raw: dict[str, Any]) -> None:
    check_request(MAP, raw, map_outside(raw), MAP.sync_cost_limit)


@property_settings(15)
@example(
    {
        "workspace": {"tilt_max_deg": 90, "torsion_deg": [-15, 15]},
        "plots": True,
        "beta_deg": {"start": 1, "stop": 179, "step": 89},
        "index_map": {"beta_deg": 179},
    }
)
@given(space_requests())
def test_every_accepted_design_space_request_computes(raw: dict[str, Any]) -> None:
    check_request(SPACE, raw, space_outside(raw), SPACE.sync_cost_limit)


@property_settings(8)
@given(optimisation_requests())
def test_every_accepted_optimisation_request_computes(raw: dict[str, Any]) -> None:
    check_request(OPT, raw, opt_outside(raw), OPT_RUN_COST)
