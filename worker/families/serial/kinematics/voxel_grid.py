"""The workspace map's grids: node-centred voxels (pixels for a planar arm) and
orientation bins (docs/methods/serial.md, "Workspace map").

Voxel nodes sit at integer multiples of ``voxel_size`` along each axis; a point belongs to
the voxel of its nearest node (a cube of side ``voxel_size`` centred on it).  Without
``bounds`` the grid covers the ball of the arm's reach bound about the base origin.

Orientation bins: a planar arm's tool angle φ in ``bins`` equal bins over [-180°, 180°);
a spatial arm's tool axis (the tool frame's z) in ``bins`` equal-area cells on the unit
sphere: ``bands`` latitude bands equal in z (equal area, Archimedes) times ``cells``
longitude cells, ``bands x cells = bins`` with ``bands`` the divisor of ``bins`` nearest
sqrt(bins / 2) (cells about square).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from worker.families.serial.kinematics.arm import SerialArm

__all__ = [
    "VoxelGrid",
    "reach_bound",
    "sphere_bin_layout",
    "tool_angle_bins",
    "tool_axis_bins",
    "voxel_grid",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class VoxelGrid:
    """Node coordinates per axis ``axes`` (2 for pixels, 3 for voxels), spacing ``size``."""

    axes: tuple[FloatArray, ...]
    size: float

    @property
    def shape(self) -> tuple[int, ...]:
        """Nodes per axis."""
        return tuple(a.shape[0] for a in self.axes)

    @property
    def cell_measure(self) -> float:
        """Area (pixels) or volume (voxels) of one cell."""
        return float(self.size ** len(self.axes))

    def flat_index(self, points: FloatArray) -> IntArray:
        """The voxel holding each point, flat C-order index, -1 outside: (...,) from
        points (..., d) (d = the grid's dimension)."""
        first = np.array([a[0] for a in self.axes])
        k = np.rint((points - first) / self.size).astype(np.int64)
        shape = np.array(self.shape)
        inside = np.all((k >= 0) & (k < shape), axis=-1)
        flat = np.ravel_multi_index(tuple(np.moveaxis(np.where(inside[..., None], k, 0), -1, 0)),
                                    self.shape)  # fmt: skip
        return np.where(inside, flat, -1).astype(np.int64)


def reach_bound(arm: SerialArm) -> tuple[FloatArray, float]:
    """(centre (3,), radius): every tool point lies within radius of the base origin —
    the sum of the fixed translations' lengths and the prismatic joints' largest travel."""
    centre = arm.fixed[0][:3, 3].copy()
    radius = float(np.sum(np.linalg.norm(arm.fixed[1:, :3, 3], axis=-1)))
    travel = np.maximum(np.abs(arm.lower), np.abs(arm.upper))
    radius += float(np.sum(np.where(arm.prismatic, travel, 0.0)))
    return centre, radius


def voxel_grid(
    arm: SerialArm,
    voxel_size: float,
    bounds: tuple[tuple[float, float], ...] | None,
    planar: bool,
) -> VoxelGrid:
    """Nodes at multiples of ``voxel_size`` covering ``bounds`` ([lo, hi] per axis: x, y
    and, for a spatial arm, z) or else the reach ball; 2-D pixels for a planar arm."""
    dims = 2 if planar else 3
    if bounds is None:
        centre, radius = reach_bound(arm)
        ranges = [(centre[i] - radius, centre[i] + radius) for i in range(dims)]
    else:
        ranges = [(float(b[0]), float(b[1])) for b in bounds[:dims]]
    axes = []
    for lo, hi in ranges:
        # the nodes whose cells meet [lo, hi]
        first, last = math.floor(lo / voxel_size + 0.5), math.ceil(hi / voxel_size - 0.5)
        axes.append(np.arange(first, max(last, first) + 1, dtype=np.float64) * voxel_size)
    return VoxelGrid(axes=tuple(axes), size=voxel_size)


def sphere_bin_layout(bins: int) -> tuple[int, int]:
    """(bands, cells) of the equal-area sphere bins: bands x cells = bins."""
    target = math.sqrt(bins / 2.0)
    divisors = [b for b in range(1, bins + 1) if bins % b == 0]
    bands = min(divisors, key=lambda b: (abs(b - target), b))
    return bands, bins // bands


def tool_axis_bins(axis: FloatArray, bins: int) -> IntArray:
    """The sphere bin of unit directions (..., 3): band (by z) x cells + cell (by
    longitude from -180°), in [0, bins)."""
    bands, cells = sphere_bin_layout(bins)
    band = np.clip(np.floor((axis[..., 2] + 1.0) * 0.5 * bands), 0, bands - 1)
    longitude = np.arctan2(axis[..., 1], axis[..., 0])
    return (band * cells + tool_angle_bins(longitude, cells)).astype(np.int64)


def tool_angle_bins(phi: FloatArray, bins: int) -> IntArray:
    """The bin of angles φ (...,) rad: bin k holds [-π + 2πk/bins, -π + 2π(k+1)/bins)."""
    k = np.floor((phi + np.pi) * (bins / (2.0 * np.pi))).astype(np.int64)
    return np.mod(k, bins)
