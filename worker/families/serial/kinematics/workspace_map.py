"""The workspace map of a serial arm: reached voxels, reachability index and per-voxel
statistics of the dexterity indices, accumulated over joint samples in chunks
(docs/methods/serial.md, "Workspace map").

Samples are taken in order from one sequence (:mod:`.joint_samples`) in chunks of at most
``chunk`` samples (memory bounded by the chunk and the grid, not by the sample count); at
the prefixes N/8, N/4, N/2 and N the reached volume and the mean reachability index are
recorded, so the convergence report costs nothing extra and a rerun with 2N samples
repeats the N run's numbers at its own prefixes.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from itertools import pairwise

import numpy as np
from numpy.typing import NDArray

from worker.families.serial.kinematics.arm import SerialArm
from worker.families.serial.kinematics.joint_samples import (
    Sampler,
    joint_sample_chunks,
    sample_count,
)
from worker.families.serial.kinematics.map_kinematics import gram_indices, map_poses, z_axis_form
from worker.families.serial.kinematics.voxel_grid import VoxelGrid, tool_angle_bins, tool_axis_bins

__all__ = [
    "CONVERGENCE_FRACTIONS",
    "DEFAULT_CHUNK",
    "MapSettings",
    "WorkspaceAccumulator",
    "WorkspaceMap",
    "checkpoints",
    "relative_changes",
    "workspace_map",
]

FloatArray = NDArray[np.float64]
DEFAULT_CHUNK = 16_384
#: The prefixes of the sample sequence where the convergence report snapshots.
CONVERGENCE_FRACTIONS = (8, 4, 2, 1)


@dataclass(frozen=True)
class MapSettings:
    """What a map samples: ``samples`` (requested count), ``sampler``, ``seed``,
    ``orientation_bins``, ``characteristic_length`` (None: unscaled)."""

    samples: int
    sampler: Sampler
    seed: int
    orientation_bins: int
    characteristic_length: float | None = None


@dataclass(eq=False)
class WorkspaceAccumulator:
    """Per-voxel running statistics over ``voxels`` cells and ``bins`` orientation bins.

    ``bins_reached`` (voxels, bins) bool; ``count`` (voxels,) samples; ``*_min``,
    ``*_max``, ``*_sum`` of manipulability and inverse condition per voxel."""

    voxels: int
    bins: int
    bins_reached: NDArray[np.bool_] = field(init=False)
    count: NDArray[np.int64] = field(init=False)
    stats: dict[str, FloatArray] = field(init=False)

    def __post_init__(self) -> None:
        self.bins_reached = np.zeros((self.voxels, self.bins), dtype=bool)
        self.count = np.zeros(self.voxels, dtype=np.int64)
        self.stats = {}
        for name in ("manipulability", "inverse_condition"):
            self.stats[f"{name}_min"] = np.full(self.voxels, np.inf)
            self.stats[f"{name}_max"] = np.full(self.voxels, -np.inf)
            self.stats[f"{name}_sum"] = np.zeros(self.voxels)

    def add(self, voxel: NDArray[np.int64], orientation_bin: NDArray[np.int64],
            values: dict[str, FloatArray]) -> None:  # fmt: skip
        """Add samples (B,): voxel index (-1: outside, dropped), bin, index values."""
        inside = voxel >= 0
        v, o = voxel[inside], orientation_bin[inside]
        self.bins_reached.reshape(-1)[v * self.bins + o] = True
        self.count += np.bincount(v, minlength=self.voxels)
        for name, value in values.items():
            x = value[inside]
            np.minimum.at(self.stats[f"{name}_min"], v, x)
            np.maximum.at(self.stats[f"{name}_max"], v, x)
            self.stats[f"{name}_sum"] += np.bincount(v, weights=x, minlength=self.voxels)

    def reached(self) -> NDArray[np.bool_]:
        """(voxels,) at least one sample in the voxel."""
        return self.count > 0

    def reachability_index(self) -> FloatArray:
        """(voxels,) fraction of orientation bins reached."""
        index: FloatArray = self.bins_reached.sum(axis=1) / float(self.bins)
        return index

    def snapshot(self) -> tuple[int, float]:
        """(reached voxels, mean reachability index over them; 0 if none)."""
        reached = self.reached()
        n = int(reached.sum())
        return n, float(self.reachability_index()[reached].mean()) if n else 0.0


@dataclass(frozen=True, eq=False)
class WorkspaceMap:
    """A map on ``grid``: per voxel (grid shape) ``reached``, ``reachability_index``,
    ``samples`` and ``statistics`` (manipulability/inverse_condition min, mean, max;
    NaN where not reached); ``samples_used`` and the convergence ``prefixes``
    (sample counts) with ``reached_voxels`` and ``mean_index`` at each."""

    grid: VoxelGrid
    reached: NDArray[np.bool_]
    reachability_index: FloatArray
    samples: NDArray[np.int64]
    statistics: dict[str, FloatArray]
    samples_used: int
    prefixes: tuple[int, ...]
    reached_voxels: tuple[int, ...]
    mean_index: tuple[float, ...]


def checkpoints(total: int) -> tuple[int, ...]:
    """The convergence prefixes of ``total`` samples: N/8, N/4, N/2, N (floors)."""
    return tuple(max(1, total // f) for f in CONVERGENCE_FRACTIONS)


def relative_changes(values: tuple[float, ...]) -> list[float]:
    """|v_k - v_{k-1}| / |v_k| between successive prefixes (0 when both are 0, 1 when
    only the later is)."""
    out = []
    for before, after in pairwise(values):
        if after == 0.0:
            out.append(0.0 if before == 0.0 else 1.0)
        else:
            out.append(abs(after - before) / abs(after))
    return out


def _stops(total: int, chunk: int) -> list[int]:
    """Chunk ends: every checkpoint is a stop, no chunk longer than ``chunk``."""
    stops: list[int] = []
    start = 0
    for end in sorted(set(checkpoints(total))):
        stops.extend(range(start + chunk, end, chunk))
        stops.append(end)
        start = end
    return stops


def workspace_map(
    arm: SerialArm,
    grid: VoxelGrid,
    settings: MapSettings,
    *,
    chunk: int = DEFAULT_CHUNK,
    on_chunk: Callable[[int, int], None] | None = None,
) -> WorkspaceMap:
    """Sample the joint space and accumulate the map (module docstring).

    A planar arm (``len(grid.axes) == 2``) bins the tool angle φ; a spatial arm bins
    the tool axis on the sphere. ``on_chunk(done, total)`` after each chunk."""
    planar = len(grid.axes) == 2
    total = sample_count(settings.samples, arm.joints, settings.sampler)
    zarm = z_axis_form(arm)
    acc = WorkspaceAccumulator(int(np.prod(grid.shape)), settings.orientation_bins)
    marks = set(checkpoints(total))
    snapshots: list[tuple[int, float]] = []
    stops = _stops(total, chunk)
    chunks = joint_sample_chunks(arm.lower, arm.upper, settings.sampler, settings.seed, stops)
    for stop, q in zip(stops, chunks, strict=True):
        poses = map_poses(zarm, q)
        if planar:
            voxel = grid.flat_index(poses.position[:, :2])
            phi = np.arctan2(poses.rotation[:, 1, 0], poses.rotation[:, 0, 0])
            orientation = tool_angle_bins(phi, settings.orientation_bins)
        else:
            voxel = grid.flat_index(poses.position)
            orientation = tool_axis_bins(poses.rotation[:, :, 2], settings.orientation_bins)
        measure, kappa = gram_indices(poses.jacobian, planar, settings.characteristic_length)
        acc.add(voxel, orientation, {"manipulability": measure, "inverse_condition": kappa})
        if stop in marks:
            snapshots.append(acc.snapshot())
        if on_chunk is not None:
            on_chunk(stop, total)
    reached = acc.reached()
    statistics: dict[str, FloatArray] = {}
    with np.errstate(invalid="ignore", divide="ignore"):
        for name in ("manipulability", "inverse_condition"):
            statistics[f"{name}_min"] = np.where(reached, acc.stats[f"{name}_min"], np.nan)
            statistics[f"{name}_mean"] = np.where(reached, acc.stats[f"{name}_sum"] / acc.count,
                                                  np.nan)  # fmt: skip
            statistics[f"{name}_max"] = np.where(reached, acc.stats[f"{name}_max"], np.nan)
    shape = grid.shape
    return WorkspaceMap(
        grid=grid,
        reached=reached.reshape(shape),
        reachability_index=acc.reachability_index().reshape(shape),
        samples=acc.count.reshape(shape),
        statistics={k: v.reshape(shape) for k, v in statistics.items()},
        samples_used=total,
        prefixes=tuple(sorted(marks)),
        reached_voxels=tuple(s[0] for s in snapshots),
        mean_index=tuple(s[1] for s in snapshots),
    )
