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


@settings(max_examples=300, deadline=None, derandomize=True)
@given(
    arrays(np.float64, st.tuples(st.integers(0, 60), st.integers(1, 4)),
           elements=st.one_of(st.integers(-3, 6).map(float), st.just(np.nan),
                              st.just(-0.0))),
    st.data(),
)  # fmt: skip
def test_matches_brute_force(values: np.ndarray, data: st.DataObject) -> None:
    maximise = np.array(data.draw(st.lists(st.booleans(), min_size=values.shape[1],
                                           max_size=values.shape[1])))  # fmt: skip
    assert non_dominated(values, maximise).tolist() == brute_force(values, maximise)


def test_blocks_change_nothing(monkeypatch: pytest.MonkeyPatch) -> None:
    """Four objectives go block by block (a study has at most three)."""
    rng = np.random.default_rng(3)
    values = rng.integers(0, 12, (700, 4)).astype(float)
    whole = non_dominated(values, [True, False, True, False])
    monkeypatch.setattr(pareto, "BLOCK", 7)
    np.testing.assert_array_equal(non_dominated(values, [True, False, True, False]), whole)
    assert whole.tolist() == brute_force(values, np.array([True, False, True, False]))


@pytest.mark.slow
@pytest.mark.parametrize("k", [2, 3])
def test_a_million_designs_take_seconds(k: int) -> None:
    """O(n log n) for two objectives, the staircase sweep for three: 10^6 designs with a
    front of thousands (points near a sphere) in a few seconds, where checking every
    design against the front took minutes; the front is right where brute force can
    check it (a sample of its rows and of the others)."""
    import time

    rng = np.random.default_rng(7)
    values = rng.random((1_000_000, k)) / np.sqrt(k - 1)
    values[:, -1] = np.sqrt(1.0 - (values[:, :-1] ** 2).sum(axis=1))  # on the unit sphere
    lifted = rng.random(len(values)) < 0.3  # off the sphere, above: dominated
    values[lifted, -1] += rng.random(int(lifted.sum())) * 0.1
    values[::97] = np.nan
    start = time.perf_counter()
    front = non_dominated(values, [False] * k)
    assert time.perf_counter() - start < 30.0  # a busy 2-core machine: ~2 s and ~8 s
    assert 100_000 < front.size < 800_000
    clean = values[~np.isnan(values).any(axis=1)]
    on_front = set(front.tolist())
    for row in rng.choice(len(values), 60, replace=False).tolist():
        if np.isnan(values[row]).any():
            assert row not in on_front
            continue
        dominated = bool(((clean <= values[row]).all(axis=1)
                          & (clean < values[row]).any(axis=1)).any())  # fmt: skip
        assert (row in on_front) is not dominated
