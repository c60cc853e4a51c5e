"""The designs of a study: a grid over input paths, or a low-discrepancy sample.

A design space has a ``count`` and hands out any block of designs by index, as an
array (stop - start, d) of the varied inputs in ``names`` order, without building the
whole set first (a grid is unravelled, a Sobol sequence fast-forwarded, a Latin
hypercube's strata permuted design by design: :mod:`.hypercube`).  The same
space always gives the same designs: a chunk job rebuilds exactly its own block.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from worker.studies.hypercube import latin_hypercube_block

__all__ = ["DesignSpace", "GridSpace", "SampleSpace"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class GridSpace:
    """Every combination of ``n`` evenly spaced values in [lo, hi] per input path (the
    last path varies fastest); n = 1 takes lo."""

    axes: tuple[tuple[str, float, float, int], ...]

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(name for name, *_ in self.axes)

    @property
    def count(self) -> int:
        return math.prod(n for *_, n in self.axes)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(n for *_, n in self.axes)

    def values(self, axis: int) -> FloatArray:
        """The ``n`` values of one axis."""
        _, lo, hi, n = self.axes[axis]
        return np.linspace(lo, hi, n) if n > 1 else np.array([lo])

    def block(self, start: int, stop: int) -> FloatArray:
        indices = np.unravel_index(np.arange(start, stop), self.shape)
        columns = [self.values(axis)[index] for axis, index in enumerate(indices)]
        return np.stack(columns, axis=-1).astype(np.float64).reshape(stop - start, len(self.axes))


@dataclass(frozen=True)
class SampleSpace:
    """``count`` designs of a scrambled Sobol sequence or a Latin hypercube over the
    bounds [lo, hi] of each input path, seeded."""

    method: Literal["sobol", "latin_hypercube"]
    bounds: tuple[tuple[str, float, float], ...]
    count: int
    seed: int

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(name for name, *_ in self.bounds)

    def block(self, start: int, stop: int) -> FloatArray:
        d = len(self.bounds)
        if self.method == "sobol":
            from scipy.stats import qmc  # here: loading the registry must not load scipy

            engine = qmc.Sobol(d, scramble=True, rng=np.random.default_rng(self.seed))
            if start:
                engine.fast_forward(start)
            with warnings.catch_warnings():  # balance needs powers of two; any count is fine
                warnings.simplefilter("ignore", UserWarning)
                unit = engine.random(stop - start)
        else:  # keyed permutations of the strata: the block alone (.hypercube)
            unit = latin_hypercube_block(self.count, d, self.seed, start, stop)
        lo = np.array([b[1] for b in self.bounds])
        hi = np.array([b[2] for b in self.bounds])
        return np.asarray(lo + unit * (hi - lo), dtype=np.float64)


DesignSpace = GridSpace | SampleSpace


def grid_space(vary: Mapping[str, Sequence[float]]) -> GridSpace:
    """From ``{"path": [lo, hi, n], ...}`` (order kept)."""
    return GridSpace(
        tuple((name, float(lo), float(hi), int(n)) for name, (lo, hi, n) in vary.items())
    )
