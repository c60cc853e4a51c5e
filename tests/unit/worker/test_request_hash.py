"""Canonical request hashes: the identity behind Idempotency-Key."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from worker.request_hash import canonical_json, request_hash


def test_integral_numbers_are_one_value_and_key_order_is_irrelevant() -> None:
    assert request_hash("p", {"a": 2, "b": [1, 2.5]}) == request_hash(
        "p", {"b": [1.0, 2.5], "a": 2.0}
    )
    assert request_hash("p", {"a": 2}) != request_hash("p", {"a": 2.5})
    assert request_hash("p", {"a": 1}) != request_hash("q", {"a": 1})
    assert request_hash("p", {"a": True}) != request_hash("p", {"a": 1})
    assert canonical_json({"x": 1e300}) == '{"x":1e+300}'


@given(st.dictionaries(st.text(max_size=5), st.integers(-(2**52), 2**52), max_size=6))
def test_ints_hash_like_their_float_twins(values: dict[str, int]) -> None:
    as_floats = {k: float(v) for k, v in reversed(values.items())}
    assert request_hash("p", values) == request_hash("p", as_floats)
