"""Conditioning indices of an SPM over workspace samples, vectorised (eqs 24, 25, 28).

One pass over all samples: rotations (fixed per sample set), platform axes, the three
legs' closed-form inverse kinematics, and 1/kappa through
:func:`~.legs.inverse_condition_rows` (no per-sample
inverse). :class:`SampleSet` keeps the rotations so that an optimisation re-uses them
for every design. Angles are in radians.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from worker.common.parameter_errors import bad_parameter
from worker.families.spherical_parallel.kinematics.model import (
    BoolArray,
    FloatArray,
    SpmDesign,
    Workspace,
    checked_branch,
    checked_design,
    checked_orientations,
    checked_workspace,
)
from worker.families.spherical_parallel.kinematics.sampling import boundary_grid
from worker.families.spherical_parallel.kinematics.study_kernel import (
    PoseArrays,
    design_trig,
    evaluate_poses,
    least_inverse_condition,
    summarise,
)

__all__ = [
    "Indices",
    "PoseBatch",
    "SampleSet",
    "WorkspaceMinimum",
    "indices_from_batch",
    "workspace_indices",
    "workspace_minimum",
]


class PoseBatch(NamedTuple):
    """Per-sample results: 1/kappa (n,) (nan where a leg does not close), whether all
    legs close (n,), input angles (n, 3) rad and det(A) (n,) (eq 30)."""

    inverse_condition: FloatArray
    real: BoolArray
    theta: FloatArray
    det_a: FloatArray


_ETA = 2.0 * np.pi * np.arange(3) / 3.0


@dataclass(frozen=True, eq=False)
class SampleSet:
    """Orientation samples (n, 3) rad, with what every design re-uses of them.

    In the right-handed leg frame (k_i, h_i, e3), h_i = [-sin eta_i, cos eta_i, 0],
    k_i = [cos eta_i, sin eta_i, 0], the design's axes are v_i* = sin(b) h_i + cos(b) e3,
    u_i = (0, sin g, -cos g), e1_i = (0, cos g, sin g), e2_i = (1, 0, 0); so all a design
    needs of Q = Rz(psi1) Ry(psi2) Rz(psi3 - psi1) are the leg-frame coordinates of
    Q h_i and Q e3: ``frame_terms`` (6, 3, n) = (Qh.k, Qh.h, Qh.z, Qe3.k, Qe3.h, Qe3.z),
    with f1 = eta_i - psi1, f2 = eta_i + psi3 - psi1: Qh.k = sin f1 cos f2 - cos(psi2)
    cos f1 sin f2, Qh.h = cos f1 cos f2 + cos(psi2) sin f1 sin f2, Qh.z = sin(psi2) sin f2,
    Qe3.k = sin(psi2) cos f1, Qe3.h = -sin(psi2) sin f1, Qe3.z = cos(psi2).
    """

    samples: FloatArray
    frame_terms: FloatArray

    @classmethod
    def from_samples(cls, samples: ArrayLike, function: str = "SampleSet") -> SampleSet:
        arr = checked_orientations(samples, "samples", function)
        if arr.ndim != 2 or arr.shape[0] == 0:
            raise bad_parameter(
                "samples", function, "a non-empty array of shape (n, 3) in rad", samples
            )
        arr = arr.copy()
        f1 = _ETA[:, None] - arr[:, 0]
        f2 = f1 + arr[:, 2]
        s1, c1, s2, c2 = np.sin(f1), np.cos(f1), np.sin(f2), np.cos(f2)
        st, ct = np.sin(arr[:, 1]), np.cos(arr[:, 1])
        terms = np.stack([
            s1 * c2 - ct * c1 * s2, c1 * c2 + ct * s1 * s2, st * s2,
            st * c1, -st * s1, np.broadcast_to(ct, f1.shape),
        ])  # fmt: skip
        arr.flags.writeable = False
        terms.flags.writeable = False
        return cls(arr, terms)

    def evaluate(self, design: SpmDesign, branch: int) -> PoseBatch:
        """1/kappa, closure, theta and det(A) at every sample (no input checks): the
        batched kernel (:func:`~.study_kernel.evaluate_poses`) with one design."""
        angles = np.array([[design.alpha1, design.alpha2, design.beta, design.gamma]])
        poses = evaluate_poses(self.frame_terms, design_trig(angles), branch)
        assert poses.theta is not None
        return PoseBatch(poses.inverse_condition[0], poses.real[0], poses.theta[0],
                         poses.det_a[0])  # fmt: skip


@dataclass(frozen=True, eq=False)
class Indices:
    """Conditioning of one design over n equal-weight samples (docs/methods/spherical-parallel.md).

    rms_inverse_condition: C_n = sqrt(mean(1/kappa^2)) (eq 25, the quadratic mean);
    mean_square_inverse_condition: mean(1/kappa^2) (eq 28, the objective, and what the
    paper prints as "C_n"); gci: mean(1/kappa) (eq 24); min_/max_inverse_condition over
    the samples; min_abs_det_a: min |det A| (eq 30 asks det(A)^2 >= lambda). The
    summaries are nan unless all_real (every leg closes at every sample): a design that
    misses part of the workspace is never scored. Per-sample arrays (read-only):
    inverse_condition (n,), real (n,), theta (n, 3) rad, det_a (n,).
    """

    rms_inverse_condition: float
    mean_square_inverse_condition: float
    gci: float
    min_inverse_condition: float
    max_inverse_condition: float
    min_abs_det_a: float
    all_real: bool
    branch: int
    inverse_condition: FloatArray
    real: BoolArray
    theta: FloatArray
    det_a: FloatArray


def indices_from_batch(batch: PoseBatch, branch: int) -> Indices:
    """Summarise a :class:`PoseBatch` into :class:`Indices` (by the batched
    :func:`~.study_kernel.summarise`, with one design)."""
    for arr in batch:
        arr.flags.writeable = False
    poses = PoseArrays(batch.inverse_condition[None], batch.real[None], None,
                       batch.det_a[None])  # fmt: skip
    s = summarise(poses)
    return Indices(
        float(s.rms_inverse_condition[0]), float(s.mean_square_inverse_condition[0]),
        float(s.gci[0]), float(s.min_inverse_condition[0]), float(s.max_inverse_condition[0]),
        float(s.min_abs_det_a[0]), bool(s.all_real[0]), branch, *batch,
    )  # fmt: skip


def workspace_indices(design: SpmDesign, samples: ArrayLike, branch: int = -1) -> Indices:
    """C_n (eq 25), mean(1/kappa^2) (eq 28), GCI (eq 24) and extremes over samples.

    samples: (n, 3) rad orientations, taken as equal-weight (e.g. from
    :func:`~.sampling.orientation_samples`); branch: the sign
    of (u_i x w_i) . v_i (eq 29). Vectorised over the samples.
    """
    function = "workspace_indices"
    checked_design(design, function)
    sign = checked_branch(branch, function)
    sample_set = SampleSet.from_samples(samples, function)
    return indices_from_batch(sample_set.evaluate(design, sign), sign)


class WorkspaceMinimum(NamedTuple):
    """The least 1/kappa found on a boundary-inclusive grid of the closed workspace, where
    (psi (3,) rad), and whether every leg closed at every grid point."""

    inverse_condition: float
    psi: FloatArray
    all_real: bool
    grid_size: int


def workspace_minimum(
    design: SpmDesign,
    ws: Workspace,
    branch: int = -1,
    grid: tuple[int, int, int] = (24, 13, 72),
) -> WorkspaceMinimum:
    """Least 1/kappa over the closed workspace, boundary included.

    grid: (azimuth, tilt, torsion) counts of
    :func:`~.sampling.boundary_grid` (the default steps
    psi1 and psi3 by 5° over a full turn, psi2 by T/12). Designs on the edge of the design
    space reach 1/kappa = 0 on the workspace boundary even when every sample is well
    conditioned, e.g. (60°, 90°, 90°) at tilt 60° with psi3 - psi1 = 90° mod 120°. Only
    real grid points count; ``all_real`` says whether some were not.
    """
    function = "workspace_minimum"
    checked_design(design, function)
    checked_workspace(ws, function)
    sign = checked_branch(branch, function)
    points = boundary_grid(ws, *grid)
    batch = SampleSet.from_samples(points, function).evaluate(design, sign)
    poses = PoseArrays(batch.inverse_condition[None], batch.real[None], None,
                       batch.det_a[None])  # fmt: skip
    least, at = least_inverse_condition(poses)
    best = int(at[0])
    return WorkspaceMinimum(float(least[0]), points[best].copy(), bool(np.all(batch.real)),
                            len(points))  # fmt: skip
