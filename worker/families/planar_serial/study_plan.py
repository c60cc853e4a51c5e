"""One study of ``planar3r-dexterity-map`` designs through its kernel
(:mod:`worker.families.planar_serial.study`): the template's task points, trajectory
samples and joint limits prepared once, then every block of links refused as the
process refuses them and evaluated at once."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from worker.common.numeric_ranges import MAX_LENGTH, MAX_LENGTH_RATIO, MIN_LENGTH
from worker.families.planar_serial.jobs.dexterity_evaluation import (
    DEFAULT_GRID_MARGIN,
    RADIAL_ANGLE_DEG,
    RADIAL_SAMPLES,
    LimitedJoints,
    limited_joints,
    point_dexterity,
)
from worker.families.planar_serial.jobs.trajectories import trajectory_samples
from worker.families.planar_serial.kinematics.study_kernel import (
    designs_point_dexterity,
    designs_regions,
    trajectory_statistics,
)
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
        accepted = np.flatnonzero(refused < 0)
        found = self._values(links, accepted)
        return KernelBlock({path: found[path]() for path in self.wanted}, refused, refusals)

    def _d_z(self, links: FloatArray, points: FloatArray) -> FloatArray:
        """d_z (m, p) of the accepted designs ``links`` at ``points``, as the job."""
        if self.limited is None or not self.limited.sampled:
            limits = None if self.limited is None else self.limited.joint_limits_rad
            return designs_point_dexterity(links, points, limits)
        rows = [point_dexterity((l1, l2, l3), points, self.limited)
                for l1, l2, l3 in links.tolist()]  # fmt: skip
        return np.asarray(rows, dtype=np.float64).reshape(len(links), len(points))

    def _values(
        self, links: FloatArray, accepted: NDArray[np.intp]
    ) -> dict[str, Callable[[], FloatArray]]:
        """Each covered path's numbers (m, *L), computed when asked for (NaN where a
        design is refused or the process reports null)."""
        m = len(links)
        cache: dict[str, FloatArray] = {}

        def spread(rows: FloatArray) -> FloatArray:
            full = np.full((m, *rows.shape[1:]), np.nan)
            full[accepted] = rows
            return full

        def constant(value: float | list[float]) -> Callable[[], FloatArray]:
            row = np.asarray(value, dtype=np.float64)
            return lambda: np.broadcast_to(row, (m, *row.shape)).copy()

        def task_d_z() -> FloatArray:
            if "task" not in cache:
                cache["task"] = spread(self._d_z(links[accepted], self.task_xy))
            return cache["task"]

        def trajectory(name: str) -> Callable[[], FloatArray]:
            def read() -> FloatArray:
                if self.path_xy is None:
                    return np.full(m, np.nan)
                if "path" not in cache:
                    cache["path"] = self._d_z(links[accepted], self.path_xy)
                stats = trajectory_statistics(cache["path"])
                return spread(np.asarray(getattr(stats, name), dtype=np.float64))

            return read

        task = self.task_xy
        distance = np.hypot(task[:, 0], task[:, 1])
        samples = np.nan if self.path_xy is None else float(len(self.path_xy))
        grid = self.template.grid
        return {
            "links[]": lambda: links.copy(),
            "discretisation.grid.bounds[]": lambda: self._bounds(links),
            "discretisation.grid.points_per_axis": constant(grid.points_per_axis),
            "discretisation.grid.step[]": lambda: self._steps(self._bounds(links)),
            "discretisation.radial_section.angle_deg": constant(RADIAL_ANGLE_DEG),
            "discretisation.radial_section.samples": constant(RADIAL_SAMPLES),
            "discretisation.radial_section.d_to": lambda: self._half_widths(links),
            "task_points[].x": constant(task[:, 0].tolist()),
            "task_points[].y": constant(task[:, 1].tolist()),
            "task_points[].distance": constant(distance.tolist()),
            "task_points[].d_z": task_d_z,
            "task_points[].D": lambda: task_d_z() / 3.0,
            "task_points[].region": lambda: designs_regions(links, distance),
            "trajectory.samples": constant(samples),
            "trajectory.d_z_mean": trajectory("d_z_mean"),
            "trajectory.D_mean": trajectory("D_mean"),
            "trajectory.d_z_min": trajectory("d_z_min"),
            "trajectory.fully_dexterous_fraction": trajectory("fully_dexterous_fraction"),
        }

    @staticmethod
    def _half_widths(links: FloatArray) -> FloatArray:
        """1.05 (l1 + l2 + l3) per design, summed exactly (as the job's math.fsum)."""
        return np.array([DEFAULT_GRID_MARGIN * math.fsum(row) for row in links.tolist()])

    def _bounds(self, links: FloatArray) -> FloatArray:
        """The grid's bounds (m, 4): the given ones, or the square ±1.05 (l1 + l2 + l3)."""
        if self.template.grid.bounds is not None:
            row = np.asarray(self.template.grid.bounds, dtype=np.float64)
            return np.broadcast_to(row, (len(links), 4)).copy()
        half = self._half_widths(links)
        return np.stack([-half, half, -half, half], axis=1)

    def _steps(self, bounds: FloatArray) -> FloatArray:
        """The grid's spacing (m, 2), as :attr:`WorkspaceGrid.step`."""
        n = self.template.grid.points_per_axis - 1
        return np.stack([(bounds[:, 1] - bounds[:, 0]) / n, (bounds[:, 3] - bounds[:, 2]) / n],
                        axis=1)  # fmt: skip
