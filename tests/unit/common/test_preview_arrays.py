"""Arrays as a preview's plain JSON values."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from worker.common.preview_arrays import axis_values, grid_values, map_entry

VALUES = st.one_of(st.floats(-1e12, 1e12), st.sampled_from([math.nan, math.inf]))


@given(arrays(np.float64, st.tuples(st.integers(1, 6), st.integers(1, 6)), elements=VALUES))
def test_a_map_keeps_its_shape_and_six_significant_digits(values: np.ndarray) -> None:
    rows = grid_values(values)
    assert len(rows) == values.shape[0] and all(len(r) == values.shape[1] for r in rows)
    for row, expected in zip(rows, values, strict=True):
        for got, want in zip(row, expected, strict=True):
            if not math.isfinite(want):
                assert got is None
            else:
                assert got == pytest.approx(want, rel=1e-5, abs=1e-300)


def test_values_are_rounded_and_the_entry_has_its_labels() -> None:
    assert grid_values(np.array([[1.23456789, np.nan]])) == [[1.23457, None]]
    assert axis_values([0.1 + 0.2, 3]) == [0.3, 3.0]
    entry = map_entry("t", ([0, 1], "x", "m"), ([0], "y", "m"), ([[0.5, np.inf]], "d_z", ""))
    assert entry["z"] == [[0.5, None]] and entry["x_unit"] == "m" and entry["z_label"] == "d_z"
    with pytest.raises(ValueError, match="a map is"):
        grid_values(np.zeros(3))
