"""The study kernels of chain-parallelism and fourbar-grashof against the processes run
per design: random lengths (ties, change points, loops at the edge of closing,
lengths outside the range and spreads beyond the ratio), random objectives among the
covered paths.  No shortcut: every reason code and refused field agrees too, and the
numbers are equal to 1e-12 relative (to the bit, in fact)."""

from __future__ import annotations

from typing import Any

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.unit.worker.studies.engines import REGISTRY, assert_engines_agree, both_engines, field
from worker.families.chains.examples import CHAIN_PARALLELISM_EXAMPLES
from worker.studies.rows import FEASIBLE, REFUSED

LENGTHS = [0.0, 5e-7, 1e-6, 1.0, 2.0, 3.0, 5.0, 10.0, 15.0, 20.0, 1e6, 2e6]
CHAIN_OBJECTIVES = [
    "chains[].P|max", "chains[0].Q", "chains[1].rank.by_Q", "chains[].rank.by_P|sum",
    "chains[].Q_normalized|mean", "chains[].loops[].Q|sum", "chains[0].loops[0].Q",
    "chains[].total_length|min", "chains[].mobility|max", "chains[4].P", "chains[0].P_normalized",
    "chains[0].rank.by_P", "chains[].joints|sum", "chains[1].independent_loops",
]  # fmt: skip
FOURBAR_OBJECTIVES = [
    "criterion.margin", "criterion.shortest", "criterion.longest", "criterion.s_plus_l",
    "criterion.p_plus_q", "lengths|sum", "lengths[2]", "links[].length|max", "ground",
    "links[].index|sum",
]  # fmt: skip
SETTINGS = settings(max_examples=60, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])  # fmt: skip


def length() -> st.SearchStrategy[float]:
    return st.one_of(st.sampled_from(LENGTHS), st.integers(1, 12).map(float),
                     st.floats(1e-6, 30.0))  # fmt: skip


def goals(draw: st.DrawFn, names: list[str]) -> dict[str, str]:
    chosen = draw(st.lists(st.sampled_from(names), min_size=1, max_size=3, unique=True))
    return {name: draw(st.sampled_from(["max", "min"])) for name in chosen}


def grid(draw: st.DrawFn) -> list[float]:
    lo, hi = sorted((draw(length()), draw(length())))
    return [lo, hi, draw(st.integers(1, 4))]


@st.composite
def loop_studies(draw: st.DrawFn) -> dict[str, Any]:
    n = draw(st.integers(3, 6))
    count = draw(st.integers(2, 4))
    chains = [{"name": f"c{i}", "lengths": [draw(st.integers(1, 6).map(float))
                                            for _ in range(n)]} for i in range(count)]  # fmt: skip
    paths = draw(st.lists(st.tuples(st.integers(0, count - 1), st.integers(0, n - 1)),
                          min_size=1, max_size=2, unique=True))  # fmt: skip
    vary = {f"chains[{i}].lengths[{j}]": grid(draw) for i, j in paths}
    return {"process": "chain-parallelism", "fixed": {"chains": chains}, "vary": vary,
            "objectives": goals(draw, CHAIN_OBJECTIVES)}  # fmt: skip


def named(chain: dict[str, Any]) -> dict[str, Any]:
    """A multi-loop chain with its links named k1, k2, ... (a path takes no digit key)."""
    links = {f"k{name}": (dict(value) if isinstance(value, dict) else value)
             for name, value in chain["links"].items()}  # fmt: skip
    loops = [[f"k{side}" for side in loop] for loop in chain["loops"]]
    return {"name": chain["name"], "links": links, "loops": loops}


@st.composite
def polygon_studies(draw: st.DrawFn) -> dict[str, Any]:
    """Fig 4's seven-link chains (two ternary links each), any length or side varied."""
    fixed = dict(CHAIN_PARALLELISM_EXAMPLES[2].inputs)
    fixed["chains"] = [named(chain) for chain in fixed["chains"]]
    places = [f"chains[{i}].links.k{k}" for i in (0, 1) for k in (2, 3, 5, 6, 7)]
    places += [f"chains[{i}].links.k{k}.sides.{side}" for i in (0, 1) for k in (1, 4)
               for side in "abc"]  # fmt: skip
    chosen = draw(st.lists(st.sampled_from(places), min_size=1, max_size=2, unique=True))
    for place in chosen:  # a varied key is given by the study, not by 'fixed'
        _, index, _, link, *side = place.replace("[", ".").replace("]", "").split(".")
        links = fixed["chains"][int(index)]["links"]
        if side:
            links[link] = {"sides": dict(links[link]["sides"])}
            del links[link]["sides"][side[-1]]
        else:
            del links[link]
    return {"process": "chain-parallelism", "fixed": fixed,
            "vary": {place: grid(draw) for place in chosen},
            "objectives": goals(draw, CHAIN_OBJECTIVES)}  # fmt: skip


@st.composite
def fourbar_studies(draw: st.DrawFn) -> dict[str, Any]:
    links = draw(st.lists(st.integers(0, 3), min_size=1, max_size=2, unique=True))
    fixed = {"lengths": [draw(st.integers(1, 8).map(float)) for _ in range(4)],
             "ground": draw(st.integers(0, 3))}  # fmt: skip
    return {"process": "fourbar-grashof", "fixed": fixed,
            "vary": {f"lengths[{k}]": grid(draw) for k in links},
            "objectives": goals(draw, FOURBAR_OBJECTIVES)}  # fmt: skip


@SETTINGS
@given(loop_studies())
def test_loop_chains_agree_with_the_process(inputs: dict[str, Any]) -> None:
    assert_engines_agree(inputs)


@SETTINGS
@given(polygon_studies())
def test_chains_with_polygonal_links_agree_with_the_process(inputs: dict[str, Any]) -> None:
    assert_engines_agree(inputs)


@SETTINGS
@given(fourbar_studies())
def test_four_bars_agree_with_the_process(inputs: dict[str, Any]) -> None:
    assert_engines_agree(inputs)


def test_the_numbers_are_the_jobs_to_the_bit() -> None:
    """Fig 2d's third link from 6 to 24 cm among the Fig 2 quadrangles (the worked
    study): every objective, feasible or not, bit for bit."""
    inputs = {"process": "chain-parallelism", "fixed": dict(CHAIN_PARALLELISM_EXAMPLES[0].inputs),
              "vary": {"chains[3].lengths[2]": [0, 60, 61]},
              "objectives": {"chains[3].rank.by_Q": "min", "chains[].Q_normalized|max": "min",
                             "chains[].P|sum": "max"}}  # fmt: skip
    batched, per_design = assert_engines_agree(inputs)
    assert np.array_equal(batched.objectives, per_design.objectives, equal_nan=True)
    assert (batched.codes == FEASIBLE).sum() == 49  # 0 < l < 18 + 15 + 17
    refusals = {field(batched, n) for n in np.flatnonzero(batched.codes == REFUSED)}
    assert refusals == {"inputs.chains[3].lengths[2]", "inputs.chains[3].loops[0]"}


def test_change_points_and_equal_links() -> None:
    inputs = {"process": "fourbar-grashof", "fixed": {"lengths": [1, 2, 3, 4], "ground": 0},
              "vary": {"lengths[0]": [0.5, 4, 8], "lengths[3]": [0.5, 6, 12]},
              "objectives": {"criterion.margin": "max", "criterion.longest": "min"}}  # fmt: skip
    batched, _ = assert_engines_agree(inputs)
    margins = batched.objectives[batched.codes == FEASIBLE, 0]
    assert (margins == 0).any() and (margins > 0).any() and (margins < 0).any()


def test_the_kernels_cover_what_they_declare() -> None:
    for process_id in ("chain-parallelism", "fourbar-grashof"):
        process = REGISTRY.get(process_id)
        assert process is not None and process.study_kernel is not None
        declared = {entry.path for entry in process.result_paths}
        assert set(process.study_kernel.covers) <= declared, process_id
    echo = {"process": "fourbar-grashof", "fixed": {"lengths": [2, 7, 9, 6], "ground": 1},
            "vary": {"lengths[0]": [1, 3, 3]}, "objectives": {"ground": "max"}}  # fmt: skip
    assert both_engines(echo)[0].codes.tolist() == [0, 0, 0]
