"""One study of ``planar2dof-conditioning-map`` designs through its kernel
(:mod:`worker.families.planar_parallel.study`): the template's fixed inputs, the varied
columns, the refusals and the numbers of every wanted path."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from worker.common.numeric_ranges import MAX_LENGTH, MAX_LENGTH_RATIO, MIN_LENGTH
from worker.families.planar_parallel.costs import BOUNDARY_SEARCH_COST
from worker.families.planar_parallel.discretisation import BOUNDARY_COLUMNS, BOUNDARY_ROWS
from worker.families.planar_parallel.kinematics.study_kernel import (
    default_bounds,
    grid_axes,
    kappa_region_areas,
    map_summary,
)
from worker.families.planar_parallel.optimisation_spec import MIN_INVERSE_CONDITION_LIMIT
from worker.families.planar_parallel.result_paths import GRID_PATHS, REGION_PATHS
from worker.study_kernels import KernelBlock, KernelRequest, Refusal

if TYPE_CHECKING:
    from worker.families.planar_parallel.specs import ConditioningMapSpec

__all__ = ["ConditioningMapPlan"]

FloatArray = NDArray[np.float64]
#: The inputs a study may vary, in the order of the input model's fields.
INPUTS = ("l1", "l2", "e", "inverse_condition_limit")
HALF_SQRT2 = math.sqrt(0.5)
_AT_LEAST = "Input should be greater than or equal to {:g}"
_AT_MOST = "Input should be less than or equal to {:g}"
#: The fields of RegionNumbers behind each of REGION_PATHS, in order.
_REGION_FIELDS = ("area", "rectangle_region_area", "largest", "largest_x", "largest_y")
_RATIO = f"l1, l2 and e: the longest is more than {MAX_LENGTH_RATIO:g} times the shortest"


def _first(refused: NDArray[np.intp], refusals: list[Refusal], hit: NDArray[np.bool_],
           refusal: Refusal) -> None:  # fmt: skip
    """Refuse the designs ``hit`` not refused yet, for ``refusal``."""
    hit = hit & (refused < 0)
    if hit.any():
        refused[hit] = len(refusals)
        refusals.append(refusal)


@dataclass(frozen=True, eq=False)
class ConditioningMapPlan:
    """One study's designs over one template (see :mod:`.study`)."""

    template: ConditioningMapSpec
    columns: Mapping[str, int]  # varied input -> column of the designs
    wanted: frozenset[str]

    @classmethod
    def of(cls, request: KernelRequest) -> ConditioningMapPlan:
        columns = {str(path[0]): j for j, path in enumerate(request.varied)}
        return cls(request.template, columns, request.wanted)

    @property
    def cost(self) -> float:
        """1/kappa evaluations per design: the grid's nodes for a number of the map, the
        W_kappa0 search (as the process prices it) for its areas; at least 1."""
        nodes = self.template.grid.points_per_axis**2 if self.wanted & set(GRID_PATHS) else 0
        search = BOUNDARY_SEARCH_COST if self.wanted & set(REGION_PATHS) else 0
        return float(max(nodes + search, 1))

    def inputs(self, values: FloatArray) -> FloatArray:
        """The designs' (l1, l2, e, inverse_condition_limit) (m, 4) as given: the
        template's, the varied ones set; NaN where not given."""
        t = self.template
        fixed = [t.l1, t.l2, t.e, t.inverse_condition_limit]
        row = [math.nan if v is None else float(v) for v in fixed]
        given = np.tile(np.asarray(row, dtype=np.float64), (len(values), 1))
        for name, column in self.columns.items():
            given[:, INPUTS.index(name)] = values[:, column]
        return given

    def lengths(self, given: FloatArray) -> FloatArray:
        """(l1, l2, e) (m, 3) of the job's Architecture: l2 defaults to l1, e to 0, and
        eq (12)'s e = (√2/2)(l2 - l1) for the isotropic architecture."""
        l1, l2, e = given[:, 0], given[:, 1], given[:, 2]
        l2 = np.where(np.isnan(l2), l1, l2)
        if self.template.architecture == "isotropic":
            e = HALF_SQRT2 * (l2 - l1)
        else:
            e = np.where(np.isnan(e), 0.0, e)
        return np.stack([l1, l2, e], axis=-1)

    def refusals(self, given: FloatArray) -> tuple[NDArray[np.intp], tuple[Refusal, ...]]:
        """Each design's first refusal (see :mod:`.study`); -1: accepted."""
        refused = np.full(len(given), -1, dtype=np.intp)
        found: list[Refusal] = []
        bounds = {"l1": (MIN_LENGTH, MAX_LENGTH), "l2": (MIN_LENGTH, MAX_LENGTH),
                  "e": (0.0, MAX_LENGTH)}  # fmt: skip
        for k, name in enumerate(INPUTS):
            if name not in self.columns:
                continue  # the template's value passed
            v = given[:, k]
            if name == "inverse_condition_limit":
                _first(
                    refused,
                    found,
                    v < MIN_INVERSE_CONDITION_LIMIT,
                    Refusal((name,), _AT_LEAST.format(MIN_INVERSE_CONDITION_LIMIT)),
                )
                _first(refused, found, v >= 1.0, Refusal((name,), "Input should be less than 1"))
                continue  # fmt: skip
            lo, hi = bounds[name]
            _first(refused, found, v < lo, Refusal((name,), _AT_LEAST.format(lo)))
            _first(refused, found, v > hi, Refusal((name,), _AT_MOST.format(hi)))
            if name == "e":
                _first(refused, found, (v > 0.0) & (v < MIN_LENGTH), Refusal(
                    ("e",), f"Value error, e is 0 (coincident actuated joints) or a length in "
                    f"[{MIN_LENGTH:g}, {MAX_LENGTH:g}]"))  # fmt: skip
        self._model_refusals(given, refused, found)
        return refused, tuple(found)

    def _model_refusals(self, given: FloatArray, refused: NDArray[np.intp],
                        found: list[Refusal]) -> None:  # fmt: skip
        """The model validator's dimension checks, in its order."""
        t = self.template
        l1, l2, e = given[:, 0], given[:, 1], given[:, 2]
        if t.actuation == "proximal-arm":
            if t.architecture == "isotropic":
                _first(refused, found, l2 < l1, Refusal((), "architecture 'isotropic' needs "
                                                        "l2 >= l1 (eq 12)"))  # fmt: skip
            self._ratio_refusals(given[:, :3], refused, found)
            _first(refused, found, e >= l1 + l2, Refusal(("e",), "the two chains can never "
                                                         "meet: it needs e < l1 + l2"))  # fmt: skip
            l2_ = np.where(np.isnan(l2), l1, l2)
            third = np.where(np.isnan(e), HALF_SQRT2 * (l2_ - l1), e)
            size = np.maximum(np.maximum(l1, l2_), third)
        elif t.actuation == "linear-drive":
            size = np.where(np.isnan(l2), 0.0, l2)
        else:
            size = np.where(np.isnan(e), 0.0, e)
        if t.grid.bounds is None:
            return
        x_min, x_max, y_min, y_max = t.grid.bounds
        for side in (x_max - x_min, y_max - y_min):
            out = (size > 0) & ~(
                (size / MAX_LENGTH_RATIO <= side) & (side <= size * MAX_LENGTH_RATIO)
            )
            _first(refused, found, out, Refusal(("grid", "bounds"), "the grid's side and the "
                                                "robot's longest length differ by more than a "
                                                f"factor {MAX_LENGTH_RATIO:g}"))  # fmt: skip

    @staticmethod
    def _ratio_refusals(lengths: FloatArray, refused: NDArray[np.intp],
                        found: list[Refusal]) -> None:  # fmt: skip
        """l1, l2, e (those given and positive): the longest at most MAX_LENGTH_RATIO
        times the shortest, refused at e if it is the shortest or the longest, else at
        l2, else l1 (the shortest first among equals, the longest last)."""
        present = np.isfinite(lengths) & (lengths > 0)
        low = np.where(present, lengths, np.inf)
        high = np.where(present, lengths, -np.inf)
        shortest = np.argmin(low, axis=1)
        longest = 2 - np.argmax(high[:, ::-1], axis=1)
        with np.errstate(invalid="ignore", divide="ignore"):
            spread = (present.sum(axis=1) >= 2) & (
                high.max(axis=1) / low.min(axis=1) > MAX_LENGTH_RATIO
            )
        for index, name in ((2, "e"), (1, "l2"), (0, "l1")):
            named = (shortest == index) | (longest == index)
            _first(refused, found, spread & named, Refusal((name,), _RATIO))

    def evaluate(self, values: FloatArray) -> KernelBlock:
        given = self.inputs(values)
        refused, refusals = self.refusals(given)
        accepted = np.flatnonzero(refused < 0)
        numbers = self._numbers(given[accepted])
        out: dict[str, FloatArray] = {}
        for path in self.wanted:
            column = numbers[path]
            full = np.full((len(values), *column.shape[1:]), np.nan)
            full[accepted] = column
            out[path] = full
        return KernelBlock(out, refused, refusals)

    def _numbers(self, given: FloatArray) -> dict[str, FloatArray]:
        """Every wanted path's numbers for accepted designs ``given`` (m, 4)."""
        t = self.template
        m, n = len(given), t.grid.points_per_axis
        lengths = self.lengths(given)
        limit = given[:, 3]
        if t.grid.bounds is not None:
            bounds = np.tile(np.asarray(t.grid.bounds, dtype=np.float64), (m, 1))
        else:
            bounds = default_bounds(t.actuation, lengths)
        step = np.stack([(bounds[:, 1] - bounds[:, 0]) / (n - 1),
                         (bounds[:, 3] - bounds[:, 2]) / (n - 1)], axis=-1)  # fmt: skip
        cell = step[:, 0] * step[:, 1]
        no_limit = np.isnan(limit)
        found: dict[str, FloatArray] = {
            "l1": given[:, 0], "l2": given[:, 1],
            "e": given[:, 2] if t.actuation == "linear-drive" else lengths[:, 2],
            "delta": lengths[:, 1] / lengths[:, 0] if t.actuation == "proximal-arm"
            else np.full(m, np.nan),
            "working_mode[]": np.tile(np.asarray(t.working_mode, dtype=np.float64), (m, 1)),
            "w_kappa0.inverse_condition_limit": limit,
            "discretisation.grid.bounds[]": bounds, "discretisation.grid.step[]": step,
            "discretisation.grid.points_per_axis": np.full(m, float(n)),
        }  # fmt: skip
        if self.wanted & set(GRID_PATHS):
            axes = grid_axes(bounds, n)
            summary = map_summary(t.actuation, t.working_mode, lengths, axes,
                                  np.where(no_limit, np.inf, limit))  # fmt: skip
            found |= {
                "summary.reachable_points": summary.reachable,
                "summary.reachable_area_grid": summary.reachable * cell,
                "summary.inverse_condition.min": summary.minimum,
                "summary.inverse_condition.max": summary.maximum,
                "summary.inverse_condition.mean": summary.mean,
                "w_kappa0.area_grid": np.where(no_limit, np.nan, summary.inside * cell),
            }
        if self.wanted & set(REGION_PATHS):
            region = np.full((5, m), np.nan)
            searched = np.flatnonzero(~no_limit)
            numbers = kappa_region_areas(
                t.actuation, t.working_mode, lengths[searched], limit[searched],
                (BOUNDARY_COLUMNS, BOUNDARY_ROWS),
            )  # fmt: skip
            for row, name in enumerate(REGION_PATHS):
                region[row, searched] = getattr(numbers, _REGION_FIELDS[row])
                found[name] = region[row]
        return {path: found[path] for path in self.wanted}
