"""One study of ``planar3r-dexterity-map`` designs through its kernel
(:mod:`worker.families.planar_serial.study`): the template's task points, trajectory
samples and joint limits prepared once, then every block of links refused as the
process refuses them and evaluated at once."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from worker.common.numeric_ranges import MAX_LENGTH, MAX_LENGTH_RATIO, MIN_LENGTH
from worker.families.planar_serial.jobs.dexterity_evaluation import (
    DEFAULT_GRID_MARGIN,
    LimitedJoints,
    limited_joints,
)
from worker.families.planar_serial.jobs.trajectories import trajectory_samples
from worker.families.planar_serial.result_paths import MAP_PATHS
from worker.families.planar_serial.study_block import BlockNumbers
from worker.study_kernels import KernelBlock, KernelRequest, Refusal

if TYPE_CHECKING:
    from worker.families.planar_serial.specs import DexterityMapSpec

__all__ = ["DexterityMapPlan"]

FloatArray = NDArray[np.float64]
#: pydantic's words for a link outside [MIN_LENGTH, MAX_LENGTH].
TOO_SHORT = f"Input should be greater than or equal to {MIN_LENGTH:f}".rstrip("0")
TOO_LONG = f"Input should be less than or equal to {MAX_LENGTH:.0f}"
_SPREAD = Refusal(("links",), f"links: the longest is more than {MAX_LENGTH_RATIO:g} times "
                  "the shortest")  # fmt: skip
_NO_REACH = Refusal(("grid", "bounds"), "the grid holds no reachable point")


@dataclass(frozen=True, eq=False)
class DexterityMapPlan:
    """The template, the varied links (link -> column of the designs), the wanted
    paths, the joint limits (None: revolute joints), the task points (p, 2) and the
    trajectory's samples (s, 2) or None."""

    template: DexterityMapSpec
    columns: Mapping[int, int]
    wanted: frozenset[str]
    limited: LimitedJoints | None
    task_xy: FloatArray
    path_xy: FloatArray | None

    @classmethod
    def of(cls, request: KernelRequest) -> DexterityMapPlan:
        t: DexterityMapSpec = request.template
        columns = {int(path[1]): j for j, path in enumerate(request.varied)}
        limited = limited_joints(t.joint_limits_deg, t.orientation_step_deg, t.method)
        task_xy = np.asarray(t.task_points or (), dtype=np.float64).reshape(-1, 2)
        path_xy = None if t.trajectory is None else trajectory_samples(t.trajectory)
        return cls(t, columns, request.wanted, limited, task_xy, path_xy)

    @property
    def cost(self) -> float:
        """Points evaluated (task points, trajectory samples) x orientations tested at
        each (1 for revolute joints), plus one for the rest."""
        per_point = 1 if self.limited is None else self.limited.evaluations_per_point
        points = 0
        if self.wanted & {"task_points[].d_z", "task_points[].D"}:
            points += len(self.task_xy)
        if self.path_xy is not None and any(p.startswith("trajectory.") for p in self.wanted):
            points += len(self.path_xy)
        if self.wanted & set(MAP_PATHS):
            points += self.template.grid.points_per_axis**2
        return float(points * per_point + 1)

    def links(self, values: FloatArray) -> FloatArray:
        """The designs' links (m, 3): the template's, the varied ones set."""
        links = np.tile(np.asarray(self.template.links, dtype=np.float64), (len(values), 1))
        for link, column in self.columns.items():
            links[:, link] = values[:, column]
        return links

    def refusals(self, links: FloatArray) -> tuple[NDArray[np.intp], tuple[Refusal, ...]]:
        """Each design's first refusal (see the module doc of :mod:`.study`); -1: none."""
        refused = np.full(len(links), -1, dtype=np.intp)
        found: list[Refusal] = []

        def refuse(bad: NDArray[np.bool_], refusal: Refusal) -> None:
            hit = bad & (refused < 0)
            if hit.any():
                refused[hit] = len(found)
                found.append(refusal)

        for link in sorted(self.columns):
            refuse(links[:, link] < MIN_LENGTH, Refusal(("links", link), TOO_SHORT))
            refuse(links[:, link] > MAX_LENGTH, Refusal(("links", link), TOO_LONG))
        with np.errstate(all="ignore"):
            ratio = links.max(axis=1) / links.min(axis=1)
        refuse(ratio > MAX_LENGTH_RATIO, _SPREAD)
        if self.template.grid.bounds is not None:
            refuse(self._misses_the_grid(links), _NO_REACH)
        return refused, tuple(found)

    def _misses_the_grid(self, links: FloatArray) -> NDArray[np.bool_]:
        """Designs whose reachable annulus the given grid misses (the process's check)."""
        assert self.template.grid.bounds is not None
        x_min, x_max, y_min, y_max = self.template.grid.bounds
        outer = links[:, 0] + links[:, 1] + links[:, 2]
        inner = np.maximum(0.0, 2.0 * links.max(axis=1) - outer)
        nearest = math.hypot(max(x_min, 0.0, -x_max), max(y_min, 0.0, -y_max))
        farthest = math.hypot(max(abs(x_min), abs(x_max)), max(abs(y_min), abs(y_max)))
        return np.asarray((nearest >= outer) | (farthest <= inner), dtype=bool)

    def evaluate(self, values: FloatArray) -> KernelBlock:
        links = self.links(values)
        refused, refusals = self.refusals(links)
        numbers = BlockNumbers(self, links, np.flatnonzero(refused < 0))
        return KernelBlock({path: numbers.read(path) for path in self.wanted}, refused, refusals)

    @staticmethod
    def half_widths(links: FloatArray) -> FloatArray:
        """1.05 (l1 + l2 + l3) per design, summed exactly (as the job's math.fsum)."""
        return np.array([DEFAULT_GRID_MARGIN * math.fsum(row) for row in links.tolist()])

    def bounds(self, links: FloatArray) -> FloatArray:
        """The grid's bounds (m, 4): the given ones, or the square ±1.05 (l1 + l2 + l3)."""
        if self.template.grid.bounds is not None:
            row = np.asarray(self.template.grid.bounds, dtype=np.float64)
            return np.broadcast_to(row, (len(links), 4)).copy()
        half = self.half_widths(links)
        return np.stack([-half, half, -half, half], axis=1)

    def steps(self, bounds: FloatArray) -> FloatArray:
        """The grid's spacing (m, 2), as :attr:`WorkspaceGrid.step`."""
        n = self.template.grid.points_per_axis - 1
        return np.stack([(bounds[:, 1] - bounds[:, 0]) / n, (bounds[:, 3] - bounds[:, 2]) / n],
                        axis=1)  # fmt: skip
