"""The non-dominated filter against a brute-force pairwise check."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from worker.studies import pareto
from worker.studies.pareto import non_dominated


def brute_force(values: np.ndarray, maximise: np.ndarray) -> list[int]:
    signs = np.where(maximise, -1.0, 1.0)
    kept = []
    for i, row in enumerate(values):
        if np.isnan(row).any():
            continue
        a = row * signs
        dominated = False
        for j, other in enumerate(values):
            if j == i or np.isnan(other).any():
                continue
            b = other * signs
            if (b <= a).all() and (b < a).any():
                dominated = True
                break
        if not dominated:
            kept.append(i)
    return kept


def test_two_objectives_by_hand() -> None:
    values = [[1, 5], [2, 4], [2, 4], [3, 4], [4, 1], [np.nan, 0], [5, 5]]
    # minimise both: [3, 4] is dominated by [2, 4], [5, 5] by everything; ties both stay
    assert non_dominated(values, [False, False]).tolist() == [0, 1, 2, 4]
    # maximise the second: [1, 5] is best on both, so it alone is left
    assert non_dominated(values, [False, True]).tolist() == [0]
    # maximise both: [5, 5] dominates every other row
    assert non_dominated(values, [True, True]).tolist() == [6]


@settings(max_examples=150, deadline=None, derandomize=True)
@given(
    arrays(np.float64, st.tuples(st.integers(0, 60), st.integers(1, 3)),
           elements=st.one_of(st.integers(0, 6).map(float), st.just(np.nan))),
    st.data(),
)  # fmt: skip
def test_matches_brute_force(values: np.ndarray, data: st.DataObject) -> None:
    maximise = np.array(data.draw(st.lists(st.booleans(), min_size=values.shape[1],
                                           max_size=values.shape[1])))  # fmt: skip
    assert non_dominated(values, maximise).tolist() == brute_force(values, maximise)


def test_blocks_change_nothing(monkeypatch: pytest.MonkeyPatch) -> None:
    rng = np.random.default_rng(3)
    values = rng.integers(0, 40, (700, 3)).astype(float)
    whole = non_dominated(values, [True, False, True])
    monkeypatch.setattr(pareto, "BLOCK", 7)
    np.testing.assert_array_equal(non_dominated(values, [True, False, True]), whole)
    assert whole.tolist() == brute_force(values, np.array([True, False, True]))
