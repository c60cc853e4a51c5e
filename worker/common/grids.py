"""The rectangular evaluation grid shared by the map jobs (nodes on both axes, ends included)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["WorkspaceGrid"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class WorkspaceGrid:
    """A rectangular grid of ``points_per_axis``² nodes, ends included.

    ``bounds`` = (x_min, x_max, y_min, y_max).
    """

    bounds: tuple[float, float, float, float]
    points_per_axis: int

    @property
    def x(self) -> FloatArray:
        """Node x coordinates, (nx,)."""
        return np.linspace(self.bounds[0], self.bounds[1], self.points_per_axis)

    @property
    def y(self) -> FloatArray:
        """Node y coordinates, (ny,)."""
        return np.linspace(self.bounds[2], self.bounds[3], self.points_per_axis)

    @property
    def step(self) -> tuple[float, float]:
        """Node spacing (dx, dy)."""
        n = self.points_per_axis - 1
        return (self.bounds[1] - self.bounds[0]) / n, (self.bounds[3] - self.bounds[2]) / n

    @property
    def cell_area(self) -> float:
        """dx * dy: the area each node stands for in grid area estimates."""
        dx, dy = self.step
        return dx * dy

    def points(self) -> FloatArray:
        """Node coordinates, (ny, nx, 2)."""
        xx, yy = np.meshgrid(self.x, self.y)
        return np.stack([xx, yy], axis=-1)

    def describe(self) -> dict[str, object]:
        """The grid as reported in a result's ``discretisation``."""
        return {
            "bounds": list(self.bounds),
            "points_per_axis": self.points_per_axis,
            "step": list(self.step),
        }
