"""Whether SPM designs reach a prescribed workspace at all, batched over designs.

A design reaches the workspace when its legs close (eq 12) at some orientation of it.
``spm-conditioning-map`` refuses a design that does not (every map would be empty); it
looks on three grids in turn (:class:`ReachGrids`): the boundary-inclusive grid of the
closed workspace (:func:`~.sampling.boundary_grid`, 22,464 orientations), the default
equal-weight samples (144) and, before refusing, a grid ten times denser (214,272).
The refusal and a design study's batched check both call :func:`reaching`, so they
agree design by design. Angles are in radians.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np

from worker.families.spherical_parallel.kinematics.indices import SampleSet
from worker.families.spherical_parallel.kinematics.model import BoolArray, FloatArray, Workspace
from worker.families.spherical_parallel.kinematics.sampling import (
    boundary_grid,
    orientation_samples,
)
from worker.families.spherical_parallel.kinematics.study_kernel import (
    TILE_POSES,
    closing_orientations,
    design_trig,
)

__all__ = ["DENSE_REACH_GRID", "REACH_GRID_SIZES", "ReachGrids", "reaching"]

#: (azimuth, tilt, torsion) of the dense grid looked at before a refusal.
DENSE_REACH_GRID = (48, 31, 144)
#: Orientations of the three grids, in the order they are looked at.
REACH_GRID_SIZES = (24 * 13 * 72, 144, 48 * 31 * 144)


@dataclass(frozen=True, eq=False)
class ReachGrids:
    """The three grids of one workspace: the first two built when first looked at and
    kept, the dense one looked at piece by piece (its terms whole would take 30 MB)."""

    ws: Workspace
    _built: dict[int, SampleSet] = field(default_factory=dict, repr=False)

    def __len__(self) -> int:
        return 3

    def grid(self, k: int) -> SampleSet:
        """Grid 0 (the boundary grid) or 1 (the default samples), kept."""
        if k not in self._built:
            points = boundary_grid(self.ws) if k == 0 else orientation_samples(self.ws)[0]
            self._built[k] = SampleSet.from_samples(points, "ReachGrids")
        return self._built[k]

    def pieces(self, k: int) -> Iterator[FloatArray]:
        """Grid ``k``'s frame terms, :data:`TILE_POSES` orientations at a time."""
        if k < 2:
            terms = self.grid(k).frame_terms
            for start in range(0, terms.shape[-1], TILE_POSES):
                yield terms[..., start : start + TILE_POSES]
            return
        points = boundary_grid(self.ws, *DENSE_REACH_GRID)
        for start in range(0, len(points), TILE_POSES):
            yield SampleSet.from_samples(points[start : start + TILE_POSES]).frame_terms


def _reaches_on(pieces: Iterator[FloatArray], angles: FloatArray) -> BoolArray:
    """(m,) whether each design closes somewhere on one grid, looked at in pieces; a
    design stops being looked at once it closes."""
    reached = np.zeros(len(angles), dtype=bool)
    for terms in pieces:
        open_ = np.flatnonzero(~reached)
        if open_.size == 0:
            break
        designs = max(1, TILE_POSES // terms.shape[-1])
        for first in range(0, open_.size, designs):
            rows = open_[first : first + designs]
            closes = closing_orientations(terms, design_trig(angles[rows])).any(axis=-1)
            reached[rows[closes]] = True
    return reached


def reaching(angles: FloatArray, grids: ReachGrids, known: BoolArray | None = None) -> BoolArray:
    """(m,) whether designs ``(m, 4)`` rad reach the workspace of ``grids`` (legs
    closing at some orientation of one of its three grids); ``known``: designs already
    known to reach it (not looked at again)."""
    arr = np.asarray(angles, dtype=np.float64).reshape(-1, 4)
    reached = np.zeros(len(arr), dtype=bool) if known is None else np.array(known, dtype=bool)
    for k in range(len(grids)):
        open_ = np.flatnonzero(~reached)
        if open_.size == 0:
            break
        reached[open_] = _reaches_on(grids.pieces(k), arr[open_])
    return reached
