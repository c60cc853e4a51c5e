"""d_z of many three-link arms at once: the batched arithmetic of the
``planar3r-dexterity-map`` study kernel (:mod:`worker.families.planar_serial.study`).

Every function takes designs as rows, ``links`` (m, 3) (l1, l2, l3 in one length
unit), and returns one row per design.  The single-design jobs call the same functions
with one row (:func:`~worker.families.planar_serial.jobs.dexterity_evaluation.point_dexterity`,
``grid_dexterity`` there with revolute joints,
:func:`~worker.families.planar_serial.jobs.trajectories.trajectory_summary`), so a study
and a job agree to the bit.  The inputs are trusted: a study's refusals and a job's
validated inputs checked them.  Work is tiled over designs so that temporaries stay
bounded whatever the block: about :data:`TILE_PAIRS` (design, point) pairs at once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from worker.families.planar_serial.kinematics.inputs import FloatArray
from worker.families.planar_serial.kinematics.limited_exact import events_dexterity

__all__ = [
    "FULL_DEXTERITY_TOL",
    "TILE_PAIRS",
    "TrajectoryStatistics",
    "closed_form_dexterity",
    "designs_point_dexterity",
    "designs_regions",
    "trajectory_statistics",
]

#: (design, point) pairs evaluated at once: under exact events about 21 sub-arcs x
#: 100 bytes each, so a tile's temporaries stay near 100 MB at most.
TILE_PAIRS = 2**15
#: d_z within this of 1 counts as full dexterity.
FULL_DEXTERITY_TOL = 1e-12


def closed_form_dexterity(lengths: FloatArray, p: FloatArray) -> FloatArray:
    """The closed-form d_z of revolute joints (``exact_orientation_dexterity`` in
    :mod:`worker.families.planar_serial.kinematics`, which checks its inputs and calls
    this) of inputs already checked: designs ``(..., 3)`` finite and positive, points
    ``(..., 2)`` finite; the shapes broadcast."""
    l1, l2, l3 = lengths[..., 0], lengths[..., 1], lengths[..., 2]
    # Scale-free form: lengths over the full reach, and clamping d at twice the reach
    # (d_z = 0 there anyway) keep every intermediate O(1).
    scale = l1 + l2 + l3
    a, b, c = l1 / scale, l2 / scale, l3 / scale
    d = np.minimum(np.hypot(p[..., 0], p[..., 1]) / scale, 2.0)
    at_origin = np.where((np.abs(l1 - l2) <= l3) & (l3 <= l1 + l2), 1.0, 0.0)
    safe_d = np.where(d > 0.0, d, 1.0)
    with np.errstate(divide="ignore", over="ignore"):
        c_lo = (d * d + c * c - (a + b) ** 2) / (2.0 * safe_d * c)
        c_hi = (d * d + c * c - (a - b) ** 2) / (2.0 * safe_d * c)
    arcs = np.arccos(np.clip(c_lo, -1.0, 1.0)) - np.arccos(np.clip(c_hi, -1.0, 1.0))
    dz = np.clip(arcs / np.pi, 0.0, 1.0)
    return np.asarray(np.where(d > 0.0, dz, at_origin), dtype=np.float64)


def designs_point_dexterity(
    links: FloatArray, points: FloatArray, joint_limits_rad: FloatArray | None
) -> FloatArray:
    """Exact d_z of every design at every point: links (m, 3), points (p, 2) in the
    links' unit, joint limits (3, 2) rad or None (fully revolute joints: the closed
    form).  Returns (m, p) in [0, 1].  Under joint limits, exact events
    (:func:`~.limited_exact.exact_limited_orientation_dexterity`, one design per point),
    tiled over designs so that at most about :data:`TILE_PAIRS` pairs are in flight.

    The inputs are trusted (prior validation assumed): links finite and positive (a
    study's refusals, a job's validated inputs), points finite, limits as
    :func:`~.inputs.checked_joint_limits` requires."""
    m, p = links.shape[0], points.shape[0]
    d_z = np.zeros((m, p), dtype=np.float64)
    if m == 0 or p == 0:
        return d_z
    rows = max(1, TILE_PAIRS // p)
    for start in range(0, m, rows):
        stop = min(start + rows, m)
        block = links[start:stop, None, :]
        if joint_limits_rad is None:
            d_z[start:stop] = closed_form_dexterity(block, points[None])
        else:
            d_z[start:stop] = events_dexterity(block, points[None], joint_limits_rad)
    return d_z


def designs_regions(links: FloatArray, distances: FloatArray) -> FloatArray:
    """The paper's regions 1-4 (§5 Example 1) of every design at distances (p,) from the
    base, (m, p) as floats: 1 up to l3, 2 up to l1 + l2 - l3, 3 up to l1 + l2 + l3, 4
    beyond (the first rule that holds, as
    :func:`~worker.families.planar_serial.kinematics.paper_regions`)."""
    l1, l2, l3 = (links[:, j, None] for j in range(3))
    d = distances[None, :]
    regions = np.select([d <= l3, d <= l1 + l2 - l3, d <= l1 + l2 + l3], [1, 2, 3], default=4)
    return regions.astype(np.float64)


@dataclass(frozen=True)
class TrajectoryStatistics:
    """Eq (4) over a trajectory's samples, one entry per design (m,): the mean d_z (and
    D = d_z / 3), the least d_z and the share of fully dexterous samples."""

    d_z_mean: FloatArray
    D_mean: FloatArray
    d_z_min: FloatArray
    fully_dexterous_fraction: FloatArray


def trajectory_statistics(d_z: FloatArray) -> TrajectoryStatistics:
    """The statistics of every design's samples, d_z (m, s) with s >= 1."""
    mean = np.mean(d_z, axis=1)
    full = np.mean(d_z >= 1.0 - FULL_DEXTERITY_TOL, axis=1)
    return TrajectoryStatistics(mean, mean / 3.0, np.min(d_z, axis=1), full)
