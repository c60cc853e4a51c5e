"""One block of designs through the ``spm-conditioning-map`` study kernel
(:mod:`worker.families.spherical_parallel.study`): refusals, the indices over the
process's samples, the least 1/kappa on its boundary grid, the reach check where it
can change feasibility, and the numbers of every wanted path."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.jobs.workspace_sampling import (
    kinematic_workspace,
    workspace_samples,
)
from worker.families.spherical_parallel.kinematics.reach import ReachGrids, reaching
from worker.families.spherical_parallel.kinematics.study_kernel import (
    IndexArrays,
    design_tiles,
    design_trig,
    evaluate_poses,
    least_inverse_condition,
    summarise,
)
from worker.study_kernels import KernelBlock, Refusal

if TYPE_CHECKING:
    from worker.families.spherical_parallel.specs import ConditioningMapSpec
    from worker.families.spherical_parallel.study import SpmPlan

__all__ = ["BlockContext", "evaluate_block"]

FloatArray = NDArray[np.float64]
_ANGLES = ("alpha1_deg", "alpha2_deg", "beta_deg", "gamma_deg")
_INDEX_NAMES = (
    "rms_inverse_condition", "mean_square_inverse_condition", "gci", "min_inverse_condition",
    "max_inverse_condition", "min_abs_det_a",
)  # fmt: skip
_UNREACHABLE = Refusal(
    ("workspace",),
    "the design cannot reach the prescribed workspace at all: its legs close (eq 12) at "
    "none of the workspace's orientations",
)


@dataclass(frozen=True, eq=False)
class BlockContext:
    """What every block of one study shares: the samples (and whether they are the
    reach check's second grid, the default sampling), their layout, the reach grids
    (the first is the boundary grid of ``workspace_minimum``) and the branch."""

    samples: sp.SampleSet
    layout: sp.SampleLayout
    default_sampling: bool
    grids: ReachGrids
    branch: int

    @classmethod
    def of(cls, spec: ConditioningMapSpec) -> BlockContext:
        ws = kinematic_workspace(spec.workspace)
        points, layout = workspace_samples(spec.workspace)
        grids = ReachGrids(ws)
        default = points.shape == grids.grid(1).samples.shape and bool(
            np.array_equal(points, grids.grid(1).samples)
        )
        samples = sp.SampleSet.from_samples(points, "spm study kernel")
        return cls(samples, layout, default, grids, spec.branch)

    @property
    def boundary_points(self) -> int:
        return int(self.grids.grid(0).samples.shape[0])


def _radians(deg: FloatArray) -> FloatArray:
    """deg -> rad one angle at a time, as :meth:`SpmDesign.from_degrees` converts."""
    rad = [math.radians(v) for v in deg.ravel().tolist()]
    return np.asarray(rad, dtype=np.float64).reshape(deg.shape)


def _indices(context: BlockContext, angles: FloatArray) -> IndexArrays:
    """The indices of designs (v, 4) rad over the samples, tile by tile."""
    terms = context.samples.frame_terms
    parts = [
        summarise(evaluate_poses(terms, design_trig(angles[tile]), context.branch, theta=False))
        for tile in design_tiles(len(angles), terms.shape[-1])
    ]
    if not parts:
        empty = np.zeros(0)
        return IndexArrays(*(empty,) * 6, np.zeros(0, dtype=bool), empty)
    return IndexArrays(*(np.concatenate(column) for column in zip(*parts, strict=True)))


def _minimum(context: BlockContext, angles: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Least 1/kappa on the boundary grid (v,) and where (v, 3) rad, as
    :func:`~.kinematics.indices.workspace_minimum` finds them."""
    grid = context.grids.grid(0)
    least = np.full(len(angles), np.nan)
    where = np.zeros((len(angles), 3))
    for tile in design_tiles(len(angles), grid.samples.shape[0]):
        poses = evaluate_poses(grid.frame_terms, design_trig(angles[tile]), context.branch,
                               theta=False)  # fmt: skip
        least[tile], at = least_inverse_condition(poses)
        where[tile] = grid.samples[at]
    return least, where


def _rounded_degrees(rad: FloatArray) -> FloatArray:
    """Angles as a result reports them: rad -> deg, rounded to 1e-10 deg."""
    shown = [round(math.degrees(v), 10) for v in rad.ravel().tolist()]
    return np.asarray(shown, dtype=np.float64).reshape(rad.shape)


def evaluate_block(plan: SpmPlan, values: FloatArray) -> KernelBlock:
    """The kernel's answer for designs ``(m, d)`` (see the module doc)."""
    context: BlockContext = plan.context
    m = len(values)
    deg = plan.angles_deg(values)
    refused, refusals = plan.field_refusals(deg)
    valid = np.flatnonzero(refused < 0)
    angles = _radians(deg[valid])
    found: dict[str, FloatArray] = {}
    indices = _indices(context, angles)
    for name in _INDEX_NAMES:
        found[f"indices.{name}"] = getattr(indices, name)
    found["indices.real_samples"] = indices.real_samples
    known = context.default_sampling & (indices.real_samples > 0)
    if plan.wanted & {"workspace_minimum.inverse_condition", "workspace_minimum.psi_deg[]"}:
        least, where = _minimum(context, angles)
        found["workspace_minimum.inverse_condition"] = least
        found["workspace_minimum.psi_deg[]"] = _rounded_degrees(where)
        known |= np.isfinite(least)
    out: dict[str, FloatArray] = {}
    for path in plan.wanted:
        column: FloatArray
        if path in found:
            column = found[path]
        elif path.startswith("design."):
            column = _rounded_degrees(_radians(deg[valid, _ANGLES.index(path[7:])]))
        elif path == "indices.samples":
            column = np.full(len(valid), float(context.samples.samples.shape[0]))
        elif path == "indices.branch":
            column = np.full(len(valid), float(context.branch))
        else:
            constant = plan.constants[path]
            column = np.broadcast_to(constant, (len(valid), *constant.shape))
        full = np.full((m, *column.shape[1:]), np.nan)
        full[valid] = column
        out[path] = full
    # A design with a value for every path read may still be refused for its reach.
    candidates = np.ones(len(valid), dtype=bool)
    for column in out.values():
        width = int(np.prod(column.shape[1:]))
        candidates &= np.isfinite(column[valid].reshape(len(valid), width)).all(axis=1)
    check = candidates & ~known
    if check.any():
        reached = reaching(angles[check], context.grids)
        rows = valid[np.flatnonzero(check)[~reached]]
        if rows.size:
            refused[rows] = len(refusals)
            refusals = (*refusals, _UNREACHABLE)
    return KernelBlock(out, refused, refusals)
