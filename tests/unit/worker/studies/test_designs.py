"""The designs of a study: grids and seeded samples, any block rebuilt alone."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from worker.studies.designs import GridSpace, SampleSpace, grid_space


def test_grid_is_every_combination_last_path_fastest() -> None:
    space = grid_space({"alpha1_deg": [30, 150, 3], "alpha2_deg": [0, 1, 2]})
    assert space.count == 6 and space.names == ("alpha1_deg", "alpha2_deg")
    np.testing.assert_allclose(
        space.block(0, 6), [[30, 0], [30, 1], [90, 0], [90, 1], [150, 0], [150, 1]]
    )
    single = grid_space({"delta": [1.5, 9, 1]})
    np.testing.assert_array_equal(single.block(0, 1), [[1.5]])


@settings(max_examples=50, deadline=None, derandomize=True)
@given(
    st.lists(st.integers(1, 6), min_size=1, max_size=3),
    st.integers(0, 200),
    st.integers(0, 200),
)
def test_any_grid_block_is_the_slice_of_the_whole(ns: list[int], a: int, b: int) -> None:
    space = GridSpace(tuple((f"p{i}", 0.0, float(i + 1), n) for i, n in enumerate(ns)))
    whole = space.block(0, space.count)
    start, stop = sorted((a % (space.count + 1), b % (space.count + 1)))
    np.testing.assert_array_equal(space.block(start, stop), whole[start:stop])


@pytest.mark.parametrize("method", ["sobol", "latin_hypercube"])
def test_samples_are_seeded_bounded_and_rebuilt_by_block(method: str) -> None:
    space = SampleSpace(method, (("a", -1.0, 1.0), ("b", 10.0, 20.0)), count=300, seed=5)  # type: ignore[arg-type]
    whole = space.block(0, 300)
    assert whole.shape == (300, 2)
    assert (whole[:, 0] >= -1).all() and (whole[:, 0] <= 1).all()
    assert (whole[:, 1] >= 10).all() and (whole[:, 1] <= 20).all()
    np.testing.assert_array_equal(space.block(0, 300), whole)
    np.testing.assert_allclose(space.block(123, 200), whole[123:200])
    other = SampleSpace(method, space.bounds, count=300, seed=6)  # type: ignore[arg-type]
    assert not np.allclose(other.block(0, 300), whole)


def test_latin_hypercube_fills_every_stratum() -> None:
    space = SampleSpace("latin_hypercube", (("a", 0.0, 1.0),), count=50, seed=1)
    strata = np.floor(space.block(0, 50)[:, 0] * 50).astype(int)
    assert sorted(strata.tolist()) == list(range(50))


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.integers(1, 3000), st.integers(1, 4), st.integers(0, 2**32 - 1), st.data())
def test_a_latin_hypercube_block_is_drawn_alone(
    count: int, d: int, seed: int, data: st.DataObject
) -> None:
    """Every stratum of every input holds exactly one design, and any block computed on
    its own is that slice of the whole sample (a chunk draws only its own designs)."""
    from worker.studies.hypercube import latin_hypercube_block

    whole = latin_hypercube_block(count, d, seed, 0, count)
    assert whole.shape == (count, d) and (whole >= 0).all() and (whole <= 1).all()
    for axis in range(d):
        strata = np.minimum(np.floor(whole[:, axis] * count), count - 1).astype(int)
        assert sorted(strata.tolist()) == list(range(count))
    start = data.draw(st.integers(0, count - 1))
    stop = data.draw(st.integers(start + 1, count))
    np.testing.assert_array_equal(latin_hypercube_block(count, d, seed, start, stop),
                                  whole[start:stop])  # fmt: skip


def test_a_latin_hypercube_block_of_a_million_costs_only_its_block() -> None:
    """A block of 1,000 of a 10^6-design sample takes well under a millisecond a
    design and no array of the whole sample (scipy's drew all 10^6 for every chunk)."""
    import time
    import tracemalloc

    bounds = tuple((f"x{k}", 0.0, 1.0) for k in range(6))
    space = SampleSpace("latin_hypercube", bounds, count=1_000_000, seed=7)
    tracemalloc.start()
    start = time.perf_counter()
    block = space.block(500_000, 501_000)
    elapsed = time.perf_counter() - start
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert block.shape == (1000, 6) and elapsed < 0.5
    assert peak < 2_000_000  # bytes: a 10^6 x 6 sample would take 48 MB
