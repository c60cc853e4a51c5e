"""The study kernel of ``spm-conditioning-map`` (:mod:`worker.study_kernels`).

A design study varying the design angles (alpha1, alpha2, beta, gamma) evaluates every
design's conditioning over the process's own samples at once
(:mod:`~worker.families.spherical_parallel.kinematics.study_kernel`): every number
under ``indices``, optionally the least 1/kappa on the same boundary grid the process
uses (``workspace_minimum``), and the numbers that echo the inputs (``design``,
``branch``, ``workspace``, ``sampling``).  The maps, sweeps and given orientations
are not computed: a study never reads them.

Refusals, exactly as the process makes them: an angle outside its range (the first in
the order alpha1, alpha2, beta, gamma: pydantic's), then a design that reaches no
orientation of the workspace (:func:`~.kinematics.reach.reaching`, at
``inputs.workspace``).  The reach check is skipped where it cannot change feasibility:
a design with a value for every objective read is known to reach the workspace when
one of the process's default samples is real (the default sampling is the reach
check's second grid) or when its least 1/kappa on the boundary grid (the check's first
grid) is finite; a design some objective has no value for is infeasible either way.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from worker.families.spherical_parallel.costs import WORKSPACE_MINIMUM_COST
from worker.families.spherical_parallel.workspace_spec import ANGLE_MARGIN_DEG, MAX_ANGLE_DEG
from worker.study_kernels import KernelBlock, KernelRequest, Refusal, StudyKernel

if TYPE_CHECKING:
    from worker.families.spherical_parallel.specs import ConditioningMapSpec

__all__ = ["CONDITIONING_MAP_KERNEL", "SpmPlan"]

FloatArray = NDArray[np.float64]

_ANGLES = ("alpha1_deg", "alpha2_deg", "beta_deg", "gamma_deg")
_INDICES = (
    "rms_inverse_condition", "mean_square_inverse_condition", "gci", "min_inverse_condition",
    "max_inverse_condition", "min_abs_det_a",
)  # fmt: skip
_ECHOES = (
    "branch", "workspace.tilt_max_deg", "workspace.cone_opening_deg", "workspace.torsion_deg[]",
    "sampling.n", "sampling.counts.azimuth", "sampling.counts.tilt", "sampling.counts.torsion",
    "sampling.psi1_deg[]", "sampling.psi2_deg[]", "sampling.psi3_deg[]",
)  # fmt: skip
_MINIMUM = (
    "workspace_minimum.inverse_condition",
    "workspace_minimum.psi_deg[]",
    "workspace_minimum.grid_points",
)
COVERS = (
    *(f"design.{name}" for name in _ANGLES),
    *_ECHOES,
    *(f"indices.{name}" for name in (*_INDICES, "samples", "real_samples", "branch")),
    *_MINIMUM,
)
#: Seconds per pose evaluation per design, batched (about 0.2 µs on the 2-core test
#: machine at 144 samples, 26 µs a design; bench/design_study.py measures it).
SECONDS_PER_POSE = 2e-7
#: Orientations the reach check may look at before it refuses a design, and its grid of
#: the default samples.
REACH_COST = 24 * 13 * 72 + 144 + 48 * 31 * 144
DEFAULT_SAMPLES = 144


def _lower(name: str) -> float:
    return 0.0 if name == "gamma_deg" else ANGLE_MARGIN_DEG


def _walk(document: Any, path: str) -> FloatArray:
    """The numbers at a declared path of a result document (one design's constants)."""
    node = document
    for part in path.split("."):
        node = node[part.removesuffix("[]")]
    return np.asarray(node, dtype=np.float64)


@dataclass(frozen=True, eq=False)
class SpmPlan:
    """One study's designs over one template (see the module doc)."""

    template: ConditioningMapSpec
    columns: Mapping[int, int]  # angle index (alpha1 .. gamma) -> column of the designs
    wanted: frozenset[str]
    constants: Mapping[str, FloatArray]
    context: Any  # the kinematic workspace, samples and grids, built once

    @property
    def cost(self) -> float:
        """Poses per design: the samples; the boundary grid for ``workspace_minimum``;
        the reach check where it may change feasibility: all three grids for a path
        reported whether or not the design reaches its workspace (an echo, a count),
        the default samples (its second grid) for indices over other samples."""
        samples = float(self.template.workspace.samples.count)
        minimum = WORKSPACE_MINIMUM_COST if self.wanted & set(_MINIMUM[:2]) else 0
        summaries = {f"indices.{name}" for name in _INDICES}
        if self.wanted - summaries - {_MINIMUM[0]}:
            reach = REACH_COST
        elif self.wanted & summaries and not self.context.default_sampling:
            reach = DEFAULT_SAMPLES
        else:
            reach = 0
        return samples + minimum + reach

    def evaluate(self, values: FloatArray) -> KernelBlock:
        # lazy: the kernel's arithmetic (scipy) loads when a study runs, not with the registry
        from worker.families.spherical_parallel.study_block import evaluate_block

        return evaluate_block(self, values)

    def angles_deg(self, values: FloatArray) -> FloatArray:
        """The designs' angles (m, 4) deg: the template's, the varied ones set."""
        t = self.template
        fixed = [t.alpha1_deg, t.alpha2_deg, t.beta_deg, t.gamma_deg]
        deg = np.tile(np.asarray(fixed, dtype=np.float64), (len(values), 1))
        for angle, column in self.columns.items():
            deg[:, angle] = values[:, column]
        return deg

    def field_refusals(self, deg: FloatArray) -> tuple[NDArray[np.intp], tuple[Refusal, ...]]:
        """Each design's first angle out of its range, as pydantic names it; -1: none."""
        refused = np.full(len(deg), -1, dtype=np.intp)
        refusals: list[Refusal] = []
        for angle in sorted(self.columns):
            name = _ANGLES[angle]
            lo = _lower(name)
            for bad, message in (
                (deg[:, angle] < lo, f"Input should be greater than or equal to {lo:g}"),
                (deg[:, angle] > MAX_ANGLE_DEG,
                 f"Input should be less than or equal to {MAX_ANGLE_DEG:.10g}"),
            ):  # fmt: skip
                hit = bad & (refused < 0)
                if hit.any():
                    refused[hit] = len(refusals)
                    refusals.append(Refusal((name,), message))
        return refused, tuple(refusals)


def _prepare(request: KernelRequest) -> SpmPlan:
    # lazy: the kernel's arithmetic (scipy) loads when a study runs, not with the registry
    from worker.families.spherical_parallel.jobs.workspace_sampling import (
        sampling_entry,
        workspace_entry,
    )
    from worker.families.spherical_parallel.study_block import BlockContext

    template: ConditioningMapSpec = request.template
    columns = {_ANGLES.index(str(path[0])): j for j, path in enumerate(request.varied)}
    context = BlockContext.of(template)
    document = {
        "branch": template.branch,
        "workspace": workspace_entry(template.workspace),
        "sampling": sampling_entry(context.layout),
        "workspace_minimum": {"grid_points": context.boundary_points},
    }
    constants = {
        path: _walk(document, path)
        for path in (*_ECHOES, "workspace_minimum.grid_points")
        if path in request.wanted
    }
    return SpmPlan(template, columns, request.wanted, constants, context)


CONDITIONING_MAP_KERNEL = StudyKernel(
    covers=COVERS,
    varies={"alpha1_deg": 90.0, "alpha2_deg": 90.0, "beta_deg": 90.0, "gamma_deg": 0.0},
    prepare=_prepare,
    seconds_per_cost=SECONDS_PER_POSE,
    description="Every design's indices over the process's own samples, batched over "
    "designs; the least 1/kappa on the process's boundary grid when asked for; the "
    "design angles varied.",
)
