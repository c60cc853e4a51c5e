"""Per-orientation entries of ``spm-conditioning-map``: the given orientations and the samples.

Given orientations go through the single-pose route of the kinematics
(``inverse_kinematics`` -> ``jacobian`` -> ``condition_number``); the samples come from
the vectorised :func:`~worker.families.spherical_parallel.kinematics.workspace_indices`. Angles
in degrees; ``null`` for a leg that does not close or an infinite kappa.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.jobs.design_entries import finite
from worker.families.spherical_parallel.jobs.workspace_sampling import FloatArray

__all__ = [
    "MAX_LISTED_SAMPLES",
    "PosePoints",
    "orientation_entries",
    "pose_points",
    "sample_entries",
]

#: Per-sample entries are listed in the result up to this many samples (all are in the CSV).
MAX_LISTED_SAMPLES = 2000


def _angles(theta: FloatArray) -> list[float | None]:
    return [None if not math.isfinite(t) else round(math.degrees(t), 10) for t in theta]


@dataclass(frozen=True, eq=False)
class PosePoints:
    """Single-pose values at m orientations: theta (m, 3) rad (nan where a leg does not
    close), real (m,), kappa, 1/kappa and det(A) (m,) (nan where not real)."""

    theta: FloatArray
    real: NDArray[np.bool_]
    kappa: FloatArray
    inverse: FloatArray
    det_a: FloatArray


def pose_points(design: sp.SpmDesign, psi_deg: FloatArray, branch: int) -> PosePoints:
    """Inverse kinematics, kappa, 1/kappa and det(A) at orientations psi_deg (m, 3)."""
    psi = np.radians(psi_deg.reshape(-1, 3))
    theta, real = sp.inverse_kinematics(design, psi, branch)
    m = len(psi)
    kappa, inverse, det_a = np.full(m, np.nan), np.full(m, np.nan), np.full(m, np.nan)
    if real.any():
        a, _, j = sp.jacobian(design, theta[real], psi[real])
        kappa[real] = sp.condition_number(j)
        inverse[real] = sp.inverse_condition_number(j)
        det_a[real] = np.linalg.det(a)
    return PosePoints(theta, real, kappa, inverse, det_a)


def orientation_entries(
    design: sp.SpmDesign, orientations_deg: Sequence[tuple[float, float, float]], branch: int
) -> list[dict[str, Any]]:
    """One entry per given orientation, in order."""
    if not orientations_deg:
        return []
    psi_deg = np.asarray(orientations_deg, dtype=np.float64)
    poses = pose_points(design, psi_deg, branch)
    return [
        {
            "psi_deg": [float(v) for v in psi_deg[i]],
            "real": bool(poses.real[i]),
            "joint_angles_deg": _angles(poses.theta[i]),
            "condition_number": finite(poses.kappa[i]),
            "inverse_condition": finite(poses.inverse[i]),
            "det_a": finite(poses.det_a[i]),
        }
        for i in range(len(psi_deg))
    ]


def sample_entries(indices: sp.Indices, samples: FloatArray) -> dict[str, Any]:
    """Inverse kinematics at every sample: counts, the unreachable samples and (up to
    :data:`MAX_LISTED_SAMPLES` samples) one entry each."""
    n = len(samples)
    unreachable = np.flatnonzero(~indices.real)
    listed = n <= MAX_LISTED_SAMPLES
    entries = None
    if listed:
        psi_deg = np.degrees(samples)
        entries = [
            {
                "psi_deg": [round(float(v), 10) for v in psi_deg[i]],
                "real": bool(indices.real[i]),
                "joint_angles_deg": _angles(indices.theta[i]),
                "inverse_condition": finite(indices.inverse_condition[i]),
                "det_a": finite(indices.det_a[i]),
            }
            for i in range(n)
        ]
    return {
        "samples": n,
        "real": int(n - unreachable.size),
        "unreachable": [int(i) for i in unreachable[:MAX_LISTED_SAMPLES]],
        "unreachable_psi_deg": [
            [round(math.degrees(float(v)), 10) for v in samples[i]]
            for i in unreachable[:MAX_LISTED_SAMPLES]
        ],
        "listed": listed,
        "entries": entries,
    }
