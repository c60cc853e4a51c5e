"""A study's inputs refused where they are wrong: each error at its own field (the
varied path, the bound, the objective), before any design is built."""

from __future__ import annotations

import re
from typing import Any

import pytest
from pydantic import ValidationError

from tests.unit.worker.studies.registry import STUDY_INPUTS
from worker.studies.evaluation import design_inputs
from worker.studies.spec import StudySpec

CHAINS = [{"name": "a", "lengths": [15, 15, 15, 15]}, {"name": "b", "lengths": [20, 10, 20, 10]}]
BASE: dict[str, Any] = {
    "process": "chain-parallelism",
    "fixed": {"chains": CHAINS, "length_unit": "cm"},
    "vary": {"chains[0].lengths[2]": [10, 20, 3]},
    "objectives": {"chains[0].P": "max"},
}


def refusal(**change: Any) -> tuple[tuple[str | int, ...], str]:
    """The one error of the study ``BASE`` with ``change``: its location and message."""
    with pytest.raises(ValidationError) as caught:
        STUDY_INPUTS.model_validate({**BASE, **change})
    (error,) = caught.value.errors()
    return error["loc"], error["msg"]


@pytest.mark.parametrize(
    ("change", "loc", "message"),
    [
        # issue 26, finding 6: a list element in a list 'fixed' lacks, or too far in one
        ({"process": "fourbar-grashof", "fixed": {"ground": 0}, "vary": {"lengths[0]": [1, 5, 3]}},
         ("vary", "lengths[0]"), "'fixed' has no list 'lengths'"),
        ({"vary": {"chains[3]": [1, 5, 3]}}, ("vary", "chains[3]"),
         r"'chains' in 'fixed' is a list of 2: it has no element \[3\]"),
        ({"fixed": {}, "vary": None, "sample": {"count": 3, "bounds": {"links[0]": [1, 2]}}},
         ("sample", "bounds", "links[0]"), "'fixed' has no list 'links'"),
        ({"vary": {"chains[0].loops[0]": [1, 5, 3]}}, ("vary", "chains[0].loops[0]"),
         r"'fixed' has no list 'chains\[0\].loops'"),
        ({"vary": {"length_unit.cm": [1, 5, 3]}}, ("vary", "length_unit.cm"),
         "'length_unit' in 'fixed' is a text, not a mapping"),
        # two varied paths at one place, or one inside the other
        ({"vary": {"chains[0].lengths[2]": [1, 5, 3], "chains[0].lengths[02]": [1, 2, 2]}},
         ("vary", "chains[0].lengths[02]"), r"names the same input as 'chains\[0\].lengths\[2\]'"),
        ({"vary": {"workspace.tilt_max_deg": [1, 5, 3], "workspace": [1, 2, 2]}},
         ("vary", "workspace"), "holds 'workspace.tilt_max_deg'"),
        ({"vary": {"workspace": [1, 5, 3], "workspace.tilt_max_deg": [1, 2, 2]}},
         ("vary", "workspace.tilt_max_deg"), "lies inside 'workspace'"),
        # fixed and varied at once, at any depth
        ({"vary": {"length_unit": [1, 2, 2]}}, ("vary", "length_unit"), "both fixed and varied"),
        ({"fixed": {"workspace": {"tilt_max_deg": 60}},
          "vary": {"workspace.tilt_max_deg": [1, 2, 2]}},
         ("vary", "workspace.tilt_max_deg"), "both fixed and varied"),
        # a grid axis or a bound that is not two ordered finite numbers (and a count)
        ({"vary": {"chains[0].lengths[2]": [-1e308, 1.7e308, 3]}},
         ("vary", "chains[0].lengths[2]"), "beyond a float"),
        ({"vary": {"chains[0].lengths[2]": [1, "2", 3]}}, ("vary", "chains[0].lengths[2]"),
         "lo and hi must be finite numbers"),
        ({"vary": {"chains[0].lengths[2]": [1, 2, 2.5]}}, ("vary", "chains[0].lengths[2]"),
         "n \\(how many values\\) must be a whole number"),
        ({"vary": {"chains[0].lengths[2]": [1, 2, True]}}, ("vary", "chains[0].lengths[2]"),
         "must be a whole number"),
        ({"vary": {"chains[0].lengths[2]": [1, 2]}}, ("vary", "chains[0].lengths[2]"),
         r"a varied input is \[lo, hi, n\], not \[1, 2\]"),
        ({"vary": None, "sample": {"count": 3, "bounds": {"chains[0].lengths[2]": [2, 1]}}},
         ("sample", "bounds", "chains[0].lengths[2]"), "lo 2 exceeds hi 1"),
        # paths that are no paths, named at themselves
        ({"vary": {"chains[0].lengths[]": [1, 2, 2]}}, ("vary", "chains[0].lengths[]"),
         "result paths only"),
        ({"vary": None, "sample": {"count": 3, "bounds": {"a..b": [1, 2]}}},
         ("sample", "bounds", "a..b"), "is not a path step"),
        ({"objectives": {"chains[].P": "max"}}, ("objectives", "chains[].P"), "reduce them"),
        ({"objectives": {"chains[0].P|median": "max"}}, ("objectives", "chains[0].P|median"),
         "the reduction after '|'"),
        # the design set itself
        ({"vary": None}, ("vary",), "give exactly one of 'vary'"),
        ({"sample": {"count": 3, "bounds": {"chains[0].lengths[1]": [1, 2]}}}, ("sample",),
         "not both"),
        ({"vary": {}}, ("vary",), "at least 1 item"),
        ({"vary": {"chains[0].lengths[1]": [1, 2, 1001], "chains[0].lengths[2]": [1, 2, 1001]}},
         ("vary",), "more than 1,000,000"),
    ],
)  # fmt: skip
def test_a_bad_study_is_refused_at_its_field(
    change: dict[str, Any], loc: tuple[str | int, ...], message: str
) -> None:
    where, said = refusal(**change)
    assert where == loc
    assert re.search(message, said), said


def test_every_design_of_an_accepted_study_can_be_built() -> None:
    """Varied keys may be created (a mapping on the way too); list elements are set."""
    spec = StudySpec.model_validate(
        {**BASE, "vary": {"chains[1].lengths[0]": [5, 9, 2], "workspace.extra": [1, 2, 2]}}
    )
    inputs = design_inputs(spec, (7.0, 1.5))
    assert inputs["chains"][1]["lengths"] == [7.0, 10, 20, 10]
    assert inputs["workspace"] == {"extra": 1.5}
    assert spec.fixed["chains"] == CHAINS  # fixed itself is untouched
