"""Every accepted input computes: ``fourbar-grashof`` and ``chain-parallelism``.

Lengths are drawn log-uniformly across the declared range [1e-6, 1e6] and just outside
it; a chain whose lengths spread more than 1e6 must be refused naming the field; one
that validates must run as the worker runs it (stored JSON validated again, plots on)
and finish with a JSON-clean result and non-empty artifacts. Few run examples, always
the same ones (``DEXLAB_PROPERTY_EXAMPLES=200`` searches longer).
"""

from __future__ import annotations

from typing import Any

import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from tests.unit.families.planar_parallel.test_input_ranges import (
    check_request,
    definition,
    property_settings,
)
from worker.common.numeric_ranges import MAX_LENGTH, MAX_LENGTH_RATIO, MIN_LENGTH
from worker.errors import InvalidInputs
from worker.submission import validate_inputs

FOURBAR = definition("fourbar-grashof")
CHAINS = definition("chain-parallelism")


def lengths(size: int) -> st.SearchStrategy[list[float]]:
    """Lengths log-uniform over [1e-7, 1e7] (a little outside the range both ways),
    plus the range's own ends."""
    one = st.one_of(
        st.floats(-7, 7).map(lambda e: float(10**e)),
        st.sampled_from([MIN_LENGTH, MAX_LENGTH, 1.0]),
    )
    return st.lists(one, min_size=size, max_size=size)


def outside(values: list[float], field: str) -> set[str]:
    """The field, if a value lies outside the range or the values spread too far."""
    if any(not MIN_LENGTH <= v <= MAX_LENGTH for v in values):
        return {field}
    if max(values) / min(values) > MAX_LENGTH_RATIO:
        return {field}
    return set()


@pytest.mark.parametrize(
    ("process_id", "raw", "field"),
    [
        ("fourbar-grashof", {"lengths": [1e308] * 4, "ground": 0}, "inputs.lengths[0]"),
        ("fourbar-grashof", {"lengths": [5e-324] * 4, "ground": 0}, "inputs.lengths[0]"),
        ("fourbar-grashof", {"lengths": [1e-6, 3, 3, 2e6], "ground": 0}, "inputs.lengths[3]"),
        ("fourbar-grashof", {"lengths": [1e-6, 3, 3, 4], "ground": 0}, "inputs.lengths"),
        (
            "chain-parallelism",
            {"chains": [{"name": "a", "lengths": [1e308, 1e308, 1e308, 1e308]}]},
            "inputs.chains[0].lengths[0]",
        ),
        (
            "chain-parallelism",
            {"chains": [{"name": "a", "lengths": [5e-324, 5e-324, 5e-324, 5e-324]}]},
            "inputs.chains[0].lengths[0]",
        ),
        (
            "chain-parallelism",
            {"chains": [{"name": "a", "lengths": [1e-6, 2, 2, 3]}]},
            "inputs.chains[0].lengths",
        ),
    ],
)
def test_the_issue_inputs_are_refused_naming_the_field(
    process_id: str, raw: dict[str, Any], field: str
) -> None:
    process = definition(process_id)
    with pytest.raises(InvalidInputs) as caught:
        validate_inputs(process, raw)
    assert field in [e["field"] for e in caught.value.errors], caught.value.errors


@given(values=lengths(4), ground=st.integers(0, 3))
@example(values=[1e-6, 1e-6, 1e-6, 1e-6], ground=0)
@example(values=[1e6, 1e6, 1e6, 1e6], ground=1)
@example(values=[1.0, 1e6, 1e6, 1e6], ground=2)
@property_settings(12)
def test_fourbar_accepted_lengths_compute(values: list[float], ground: int) -> None:
    raw = {"lengths": values, "ground": ground}
    check_request(FOURBAR, raw, outside(values, "inputs.lengths"), cost_limit=10**9)


@given(first=lengths(5), second=lengths(5))
@example(first=[1e-6] * 5, second=[1e6] * 5)
@example(first=[1.0, 1e6, 1e6, 1e6, 1e6], second=[1e-6, 1e-6, 1e-6, 1e-6, 2e-6])
@property_settings(10)
def test_chain_parallelism_accepted_lengths_compute(
    first: list[float], second: list[float]
) -> None:
    raw = {"chains": [{"name": "a", "lengths": first}, {"name": "b", "lengths": second}]}
    bad = outside(first, "inputs.chains[0].lengths") | outside(second, "inputs.chains[1].lengths")
    check_request(CHAINS, raw, bad, cost_limit=10**9)
