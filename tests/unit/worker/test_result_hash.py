"""result_hash: numbers to 12 significant digits, execution metadata left out, NPZ data
arrays in and their description entries out."""

from __future__ import annotations

import io
import json
import math
import zipfile
from typing import Any

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from worker.contract import Artifact
from worker.provenance.result_hash import (
    array_digest,
    canonical_number,
    canonical_values,
    npz_arrays_digest,
    result_hash,
    significands,
)
from worker.provenance.stamp import NPZ_DESCRIPTION_ENTRIES, NPZ_MEDIA_TYPE, stamp_outcome

finite = st.floats(allow_nan=False, allow_infinity=False, min_value=-1e30, max_value=1e30)


def _far_from_a_rounding_edge(x: float) -> bool:
    """True unless relative noise of 1e-14 can carry ``x`` across a 12-digit rounding
    boundary or the 1e-12 zero threshold (rounding must round somewhere: values that
    close to an edge may round either way, as the docs say)."""
    if abs(x) < 1e-11:
        return abs(abs(x) - 1e-12) > 1e-21
    scaled = abs(x) / 10 ** (math.floor(math.log10(abs(x))) - 11)
    return abs(scaled - math.floor(scaled) - 0.5) > 2e-14 * scaled + 1e-3


def _noisy(x: float, noise: float) -> float:
    return x * (1 + noise)


@pytest.mark.parametrize(
    ("value", "text"),
    [(1.5, "150000000000e-11"), (2, "200000000000e-11"), (2.0, "200000000000e-11"),
     (-0.0, "0e0"), (1e-13, "0e0"), (-3e-13, "0e0"), (1e-12, "100000000000e-23"),
     (0.1 + 0.2, "300000000000e-12"), (999999999999.7, "100000000000e1"),
     (1000.0, "100000000000e-8"), (float("nan"), "0e32767"),
     (float("inf"), "0e32766"), (float("-inf"), "0e32765")],
)  # fmt: skip
def test_canonical_numbers(value: float, text: str) -> None:
    assert canonical_number(value) == text


@given(finite, st.floats(min_value=-1e-14, max_value=1e-14))
def test_a_number_is_canonical_through_relative_noise_of_1e14(x: float, noise: float) -> None:
    assume(_far_from_a_rounding_edge(x))
    assert canonical_number(_noisy(x, noise)) == canonical_number(x)


@given(st.floats(min_value=1e-6, max_value=1e6), st.floats(min_value=1e-9, max_value=1e-3))
def test_a_real_change_changes_the_number(x: float, change: float) -> None:
    assert canonical_number(x * (1 + change)) != canonical_number(x)


@given(
    st.lists(finite, min_size=1, max_size=30),
    st.floats(min_value=-1e-14, max_value=1e-14),
    st.integers(min_value=0, max_value=29),
)
def test_the_hash_survives_noise_and_sees_a_real_change(
    values: list[float], noise: float, which: int
) -> None:
    assume(all(_far_from_a_rounding_edge(v) for v in values))
    result = {"values": values, "summary": {"max": max(values), "label": "x"}}
    noisy = {"values": [_noisy(v, noise) for v in values],
             "summary": {"max": _noisy(max(values), noise), "label": "x"}}  # fmt: skip
    assert result_hash(result, {}) == result_hash(noisy, {})
    changed = list(values)
    i = which % len(values)
    changed[i] = values[i] * 1.001 + 1.0
    assert result_hash({**result, "values": changed}, {}) != result_hash(result, {})


def test_execution_metadata_is_left_out_and_key_order_is_irrelevant() -> None:
    result = {"a": 1, "b": [1.0, {"c": True, "d": None}]}
    decorated = {"b": [1, {"d": None, "c": True, "job_id": "x"}], "a": 1.0,
                 "provenance": {"backend": "y"}, "result_hash": "z", "reused_from": True,
                 "missing_chunks": ["q"]}  # fmt: skip
    assert result_hash(result, {}) == result_hash(decorated, {})
    assert canonical_values(decorated) == canonical_values(result)
    assert result_hash({**result, "e": "text"}, {}) != result_hash(result, {})


@given(
    st.lists(finite, min_size=1, max_size=40),
    st.floats(min_value=-1e-14, max_value=1e-14),
)
def test_array_significands_match_the_scalar_ones(values: list[float], noise: float) -> None:
    assume(all(_far_from_a_rounding_edge(v) for v in values))
    a = np.asarray(values)
    significand, exponent = significands(a)
    assert [f"{s}e{e}" for s, e in zip(significand, exponent, strict=True)] == [
        canonical_number(v) for v in values
    ]
    assert array_digest(a) == array_digest(a * (1 + noise))


def test_an_array_digest_sees_shape_kind_and_values() -> None:
    a = np.arange(6.0).reshape(2, 3)
    assert array_digest(a) != array_digest(a.reshape(3, 2))
    assert array_digest(a) != array_digest(a.astype(np.int64))
    assert array_digest(a) != array_digest(a + 1e-6)
    assert array_digest(np.array([np.nan, 1.0])) != array_digest(np.array([np.inf, 1.0]))
    assert array_digest(np.array(["a", "b"])) != array_digest(np.array(["a", "c"]))


def _npz(arrays: dict[str, Any], metadata: dict[str, Any]) -> bytes:
    buffer = io.BytesIO()
    np.savez_compressed(buffer, **arrays, axes=np.array("{}"), units=np.array("{}"),
                        metadata=np.array(json.dumps(metadata)))  # fmt: skip
    return buffer.getvalue()


def test_npz_data_arrays_count_and_their_description_does_not() -> None:
    x = np.linspace(0, 1, 5)
    one = npz_arrays_digest(_npz({"x": x}, {"job": "a"}), NPZ_DESCRIPTION_ENTRIES)
    two = npz_arrays_digest(_npz({"x": x * (1 + 1e-15)}, {"job": "b"}), NPZ_DESCRIPTION_ENTRIES)
    three = npz_arrays_digest(_npz({"x": x + 0.01}, {"job": "a"}), NPZ_DESCRIPTION_ENTRIES)
    assert list(one) == ["x"] and one == two and one != three


def test_a_stamped_outcome_carries_provenance_in_the_result_and_the_npz() -> None:
    provenance = {"backend": "b", "result_key": "k"}
    npz = Artifact("m.npz", NPZ_MEDIA_TYPE, _npz({"x": np.ones(3)}, {"process": "p"}))
    csv = Artifact("m.csv", "text/csv", b"x [mm]\n1\n")
    result, artifacts = stamp_outcome({"v": 1.0}, [npz, csv], provenance)
    assert result["provenance"] == provenance and result["v"] == 1.0
    assert result["result_hash"] == result_hash(
        {"v": 1.0}, {"m.npz": {"x": array_digest(np.ones(3))}}
    )
    assert artifacts[1] == csv
    with np.load(io.BytesIO(artifacts[0].data)) as archive:
        metadata = json.loads(str(archive["metadata"]))
        assert metadata == {"process": "p", "provenance": provenance,
                            "result_hash": result["result_hash"]}  # fmt: skip
        assert np.array_equal(archive["x"], np.ones(3))
    again = Artifact("m.npz", NPZ_MEDIA_TYPE, _npz({"x": np.ones(3)}, {"process": "p"}))
    assert stamp_outcome({"v": 1.0}, [again], provenance)[1][0].data == artifacts[0].data
    with zipfile.ZipFile(io.BytesIO(artifacts[0].data)) as archive:  # no time of the job's
        assert {info.date_time for info in archive.infolist()} == {(1980, 1, 1, 0, 0, 0)}
