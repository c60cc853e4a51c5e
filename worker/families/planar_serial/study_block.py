"""The numbers of one block of ``planar3r-dexterity-map`` designs
(:mod:`worker.families.planar_serial.study`), each computed when a study reads it and
only for the designs the process accepts (NaN for the others and where the process
reports null)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from worker.common.grids import WorkspaceGrid
from worker.families.planar_serial.jobs.dexterity_evaluation import (
    RADIAL_ANGLE_DEG,
    RADIAL_SAMPLES,
    grid_dexterity,
    point_dexterity,
    workspace_grid,
)
from worker.families.planar_serial.jobs.map_statistics import map_areas, map_summary
from worker.families.planar_serial.kinematics.inputs import Arm
from worker.families.planar_serial.kinematics.study_kernel import (
    TILE_PAIRS,
    TrajectoryStatistics,
    closed_form_dexterity,
    designs_point_dexterity,
    designs_regions,
    trajectory_statistics,
)
from worker.families.planar_serial.result_paths import MAP_PATHS

if TYPE_CHECKING:
    from worker.families.planar_serial.study_plan import DexterityMapPlan

__all__ = ["BlockNumbers"]

FloatArray = NDArray[np.float64]


def _ignore_progress(done: int, total: int) -> None:
    """A design's own progress is not the study's."""


@dataclass(eq=False)
class BlockNumbers:
    """The plan, the block's links (m, 3) and the accepted designs' rows."""

    plan: DexterityMapPlan
    links: FloatArray
    accepted: NDArray[np.intp]

    def read(self, path: str) -> FloatArray:
        """The numbers (m, *L) at a covered declared path."""
        return self._readers()[path]()

    def _readers(self) -> dict[str, Callable[[], FloatArray]]:
        plan, links = self.plan, self.links
        task, grid = plan.task_xy, plan.template.grid
        samples = np.nan if plan.path_xy is None else float(len(plan.path_xy))
        return {
            "links[]": lambda: links.copy(),
            "discretisation.grid.bounds[]": lambda: plan.bounds(links),
            "discretisation.grid.points_per_axis": self._constant(grid.points_per_axis),
            "discretisation.grid.step[]": lambda: plan.steps(plan.bounds(links)),
            "discretisation.radial_section.angle_deg": self._constant(RADIAL_ANGLE_DEG),
            "discretisation.radial_section.samples": self._constant(RADIAL_SAMPLES),
            "discretisation.radial_section.d_to": lambda: plan.half_widths(links),
            "task_points[].x": self._constant(task[:, 0].tolist()),
            "task_points[].y": self._constant(task[:, 1].tolist()),
            "task_points[].distance": self._constant(self._distances.tolist()),
            "task_points[].d_z": lambda: self._task_d_z,
            "task_points[].D": lambda: self._task_d_z / 3.0,
            "task_points[].region": lambda: designs_regions(links, self._distances),
            "trajectory.samples": self._constant(samples),
            **{f"trajectory.{name}": self._trajectory(name)
               for name in ("d_z_mean", "D_mean", "d_z_min", "fully_dexterous_fraction")},
            **{path: self._on_the_map(path) for path in MAP_PATHS},
        }  # fmt: skip

    def _spread(self, rows: FloatArray) -> FloatArray:
        """The accepted designs' rows in a block of NaN (m, ...)."""
        full = np.full((len(self.links), *rows.shape[1:]), np.nan)
        full[self.accepted] = rows
        return full

    def _constant(self, value: float | list[float]) -> Callable[[], FloatArray]:
        row = np.asarray(value, dtype=np.float64)
        return lambda: np.broadcast_to(row, (len(self.links), *row.shape)).copy()

    @cached_property
    def _distances(self) -> FloatArray:
        task = self.plan.task_xy
        return np.asarray(np.hypot(task[:, 0], task[:, 1]), dtype=np.float64)

    def _d_z(self, points: FloatArray) -> FloatArray:
        """d_z (accepted, p) of the accepted designs at ``points``, as the job."""
        links, limited = self.links[self.accepted], self.plan.limited
        if limited is None or not limited.sampled:
            limits = None if limited is None else limited.joint_limits_rad
            return designs_point_dexterity(links, points, limits)
        rows = [point_dexterity(Arm(*row), points, limited) for row in links.tolist()]
        return np.asarray(rows, dtype=np.float64).reshape(len(links), len(points))

    @cached_property
    def _task_d_z(self) -> FloatArray:
        return self._spread(self._d_z(self.plan.task_xy))

    @cached_property
    def _path_statistics(self) -> TrajectoryStatistics | None:
        if self.plan.path_xy is None:
            return None
        return trajectory_statistics(self._d_z(self.plan.path_xy))

    def _trajectory(self, name: str) -> Callable[[], FloatArray]:
        def read() -> FloatArray:
            stats = self._path_statistics
            if stats is None:
                return np.full(len(self.links), np.nan)
            return self._spread(np.asarray(getattr(stats, name), dtype=np.float64))

        return read

    def _on_the_map(self, path: str) -> Callable[[], FloatArray]:
        return lambda: self._spread(self._map_numbers[path])

    @cached_property
    def _map_numbers(self) -> dict[str, FloatArray]:
        """Each accepted design's map over its grid and the numbers the job reports
        about it (:mod:`~.jobs.map_statistics`): per path of MAP_PATHS an array
        (accepted,), NaN where the job reports null.  With revolute joints the maps of
        a tile of designs are one closed-form evaluation (elementwise, so each node's
        d_z is the job's to the bit); under joint limits each design's map is computed
        as the job computes it."""
        links = self.links[self.accepted]
        numbers = {path: np.full(len(links), np.nan) for path in MAP_PATHS}
        arms = [Arm(*row) for row in links.tolist()]  # accepted: the refusals checked them
        grids = [workspace_grid(self.plan.template.grid, arm) for arm in arms]
        nodes = self.plan.template.grid.points_per_axis**2
        rows = max(1, TILE_PAIRS // nodes) if self.plan.limited is None else 1
        for start in range(0, len(arms), rows):
            stop = min(start + rows, len(arms))
            for n, d_z in enumerate(self._maps(links[start:stop], grids[start:stop]), start):
                found = {"summary": map_summary(d_z),
                         "areas": map_areas(arms[n], grids[n], self.plan.limited, d_z)}  # fmt: skip
                for path in MAP_PATHS:
                    numbers[path][n] = _number_at(found, path)
        return numbers

    def _maps(self, links: FloatArray, grids: list[WorkspaceGrid]) -> FloatArray:
        """The maps (r, ny, nx) of designs ``links`` (r, 3) over their grids."""
        if self.plan.limited is None:
            points = np.stack([grid.points() for grid in grids])
            return closed_form_dexterity(links[:, None, None, :], points)
        arm, grid = Arm(*links[0].tolist()), grids[0]
        return grid_dexterity(arm, grid, self.plan.limited, _ignore_progress)[None]


def _number_at(document: dict[str, Any], path: str) -> float:
    """The number at a dotted path of ``document``; NaN where it is null."""
    node: Any = document
    for part in path.split("."):
        node = None if node is None else node.get(part)
    return np.nan if node is None else float(node)
