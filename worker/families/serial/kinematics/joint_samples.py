"""Joint samples within the joint limits for the workspace map, drawn in chunks.

Three samplers (docs/methods/serial.md, "Workspace map"): ``sobol`` (scrambled Sobol'
points, scipy.stats.qmc, seeded), ``uniform`` (numpy's PCG64 Generator, seeded) and
``grid`` (a tensor grid of ``m = floor(count^(1/n))`` cell-centred values per joint, visited
in a seeded random order).  Every sampler is a *sequence*: the first k samples of a run
with ``count`` samples are the samples of a run with k (sobol, uniform), so statistics
taken at prefixes of one run equal those of shorter runs.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterator, Sequence
from typing import Literal

import numpy as np
from numpy.typing import NDArray
from scipy.stats import qmc

__all__ = ["Sampler", "grid_points_per_joint", "joint_sample_chunks", "sample_count"]

FloatArray = NDArray[np.float64]
Sampler = Literal["sobol", "uniform", "grid"]


def grid_points_per_joint(count: int, joints: int) -> int:
    """Values per joint of the ``grid`` sampler: the largest m with m**joints <= count."""
    m = max(1, int(np.floor(count ** (1.0 / joints))))
    while (m + 1) ** joints <= count:
        m += 1
    while m > 1 and m**joints > count:
        m -= 1
    return m


def sample_count(count: int, joints: int, sampler: Sampler) -> int:
    """The samples a run draws: ``count``, or m**joints for the grid."""
    return grid_points_per_joint(count, joints) ** joints if sampler == "grid" else count


def _unit_chunks(
    count: int, joints: int, sampler: Sampler, seed: int, stops: Sequence[int]
) -> Iterator[FloatArray]:
    """Points of [0, 1)^joints: chunks ending at each of the increasing ``stops``."""
    start = 0
    if sampler == "sobol":
        engine = qmc.Sobol(d=joints, scramble=True, seed=seed)
        for stop in stops:
            with warnings.catch_warnings():
                # prefixes of any length are wanted (the convergence report); the balance
                # of a power-of-two count is not needed for a map
                warnings.filterwarnings("ignore", message=".*balance properties.*")
                yield np.asarray(engine.random(stop - start), dtype=np.float64)
            start = stop
    elif sampler == "uniform":
        generator = np.random.default_rng(seed)
        for stop in stops:
            yield generator.random((stop - start, joints))
            start = stop
    else:
        m = grid_points_per_joint(count, joints)
        order = np.random.default_rng(seed).permutation(m**joints)
        for stop in stops:
            cells = np.unravel_index(order[start:stop], (m,) * joints)
            yield (np.stack(cells, axis=-1).astype(np.float64) + 0.5) / m
            start = stop


def joint_sample_chunks(
    lower: FloatArray,
    upper: FloatArray,
    sampler: Sampler,
    seed: int,
    stops: Sequence[int],
) -> Iterator[FloatArray]:
    """Joint values (rad or length units) in chunks of shape (stop_k - stop_{k-1}, n).

    ``lower``, ``upper``: (n,) joint limits; ``stops``: increasing sample counts ending at
    :func:`sample_count` (the last is the total).  Values lie in [lower, upper).
    """
    span = upper - lower
    for unit in _unit_chunks(stops[-1], lower.shape[0], sampler, seed, stops):
        yield lower + unit * span
