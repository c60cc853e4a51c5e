"""Three-link planar serial arms (RRR): kinematics, orientation dexterity and synthesis.

Patel & Sobh, "Optimal Design of Three-Link Planar Manipulators Using Grashof's
Criterion" (2012), restated in docs/methods/planar-serial.md, which wins where the two disagree.

Conventions: links ``(l1, l2, l3)`` run from the base (at the origin) to the
end-effector, in any one length unit; angles are in radians; the end-effector
orientation is ``phi = th1 + th2 + th3``. The dexterity index about z is
``d_z(p) = |{phi in [0, 2 pi) reachable at p}| / (2 pi)`` (eqs 2-5; planar, so
``d_x = d_y = 0`` and ``D = d_z / 3``). Functions are batched on the leading axes of
their point/angle argument and return an array for it, never a scalar.

The joint-limited sampling kernel lives in :mod:`.joint_limits`, the
per-point reference sampler in :mod:`.reference_sampler` and the
input checks in :mod:`.inputs`; their public functions are
re-exported here, so this module stays the one to import.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from worker.common.parameter_errors import bad_parameter
from worker.families.planar_serial.kinematics.inputs import Arm as Arm
from worker.families.planar_serial.kinematics.inputs import BoolArray as BoolArray
from worker.families.planar_serial.kinematics.inputs import FloatArray as FloatArray
from worker.families.planar_serial.kinematics.inputs import Links as Links
from worker.families.planar_serial.kinematics.inputs import (
    checked_array,
    checked_link_rows,
    checked_links,
    checked_points,
)
from worker.families.planar_serial.kinematics.joint_limits import (
    limited_orientation_dexterity,
    orientation_samples,
)
from worker.families.planar_serial.kinematics.reference_sampler import sampled_orientation_dexterity
from worker.families.planar_serial.kinematics.study_kernel import closed_form_dexterity

__all__ = [
    "band_area",
    "exact_orientation_dexterity",
    "forward_kinematics",
    "full_dexterity_bands",
    "limited_orientation_dexterity",
    "orientation_samples",
    "paper_regions",
    "reach_radii",
    "region_radii",
    "sampled_orientation_dexterity",
    "synthesise_links",
]


# --- closed forms (unlimited joints) --------------------------------------------------


def forward_kinematics(links: ArrayLike, joint_angles: ArrayLike) -> FloatArray:
    """End-effector pose from joint angles, eqs (8)-(9).

    links: (3,) lengths; joint_angles: (..., 3) radians ``(th1, th2, th3)``.
    Returns (..., 3): ``[x, y, phi]`` with ``phi = th1 + th2 + th3`` (not wrapped).
    """
    l1, l2, l3 = checked_links(links, "forward_kinematics")
    q = checked_array(
        joint_angles,
        "joint_angles",
        "forward_kinematics",
        "finite angles (rad) of shape (..., 3)",
        lambda a: a.ndim >= 1 and a.shape[-1] == 3,
    )
    absolute = np.cumsum(q, axis=-1)
    lengths = np.array([l1, l2, l3])
    x = np.sum(lengths * np.cos(absolute), axis=-1)
    y = np.sum(lengths * np.sin(absolute), axis=-1)
    return np.stack([x, y, absolute[..., 2]], axis=-1)


def reach_radii(links: ArrayLike) -> tuple[float, float]:
    """(inner, outer) radius of the reachable annulus with unlimited joints.

    outer = l1 + l2 + l3; inner = max(0, 2 max(l) - sum(l)).
    """
    lengths = checked_links(links, "reach_radii")
    total = sum(lengths)
    return max(0.0, 2.0 * max(lengths) - total), total


def exact_orientation_dexterity(links: ArrayLike, points: ArrayLike) -> FloatArray:
    """Closed-form d_z with unlimited joints (docs/methods/planar-serial.md; eqs 3 and 5).

    links: (3,), or designs (..., 3) broadcast against the points' leading axes;
    points: (..., 2) in the links' unit. Returns d_z in [0, 1], of the points' shape
    (broadcast with the designs'):
    ``d_z = [acos(clip(c_lo)) - acos(clip(c_hi))] / pi`` with
    ``c_lo = (d^2 + l3^2 - (l1+l2)^2) / (2 d l3)``, ``c_hi = (d^2 + l3^2 - (l1-l2)^2) / (2 d l3)``,
    ``d = |p|``; at d = 0, d_z = 1 if |l1 - l2| <= l3 <= l1 + l2, else 0.
    """
    lengths = checked_link_rows(links, "exact_orientation_dexterity")
    p = checked_points(points, "exact_orientation_dexterity")
    return closed_form_dexterity(lengths, p)


def full_dexterity_bands(links: ArrayLike) -> tuple[tuple[float, float], ...]:
    """Closed radius intervals where d_z == 1 with unlimited joints (docs/methods/planar-serial.md).

    ``[0, min(l3 - |l1-l2|, l1+l2-l3)]`` ∪ ``[l3 + |l1-l2|, l1+l2-l3]``; empty pieces
    dropped, sorted, touching or overlapping pieces merged. This corrects the paper's
    Region 2 (eq 13), e.g. (15, 14, 8) -> ((0, 7), (9, 21)).
    """
    l1, l2, l3 = checked_links(links, "full_dexterity_bands")
    gap = abs(l1 - l2)
    pieces = [(0.0, min(l3 - gap, l1 + l2 - l3)), (l3 + gap, l1 + l2 - l3)]
    bands: list[tuple[float, float]] = []
    for lo, hi in sorted(piece for piece in pieces if piece[0] <= piece[1]):
        if bands and lo <= bands[-1][1]:
            bands[-1] = (bands[-1][0], max(bands[-1][1], hi))
        else:
            bands.append((lo, hi))
    return tuple(bands)


def band_area(bands: Sequence[tuple[float, float]]) -> float:
    """Area of a union of disjoint annuli: sum of pi (b^2 - a^2) over the bands (a, b)."""
    arr = checked_array(
        list(bands),
        "bands",
        "band_area",
        "radius pairs (a, b) with 0 <= a <= b",
        lambda a: (
            a.size == 0
            or (
                a.ndim == 2
                and a.shape[1] == 2
                and bool(np.all((a[:, 0] >= 0) & (a[:, 0] <= a[:, 1])))
            )
        ),
    ).reshape(-1, 2)
    return float(np.pi * np.sum(arr[:, 1] ** 2 - arr[:, 0] ** 2))


def region_radii(links: ArrayLike) -> tuple[float, float, float]:
    """The paper's region boundaries (§5 Example 1): (l3, l1 + l2 - l3, l1 + l2 + l3)."""
    l1, l2, l3 = checked_links(links, "region_radii")
    return l3, l1 + l2 - l3, l1 + l2 + l3


def paper_regions(links: ArrayLike, distances: ArrayLike) -> NDArray[np.int8]:
    """The paper's regions 1-4 (§5 Example 1, eq 13) for distances (...) from the base.

    1: 0 <= d <= l3; 2: l3 < d <= l1+l2-l3; 3: l1+l2-l3 < d <= l1+l2+l3; 4: beyond reach.
    The first matching rule wins (region 2 is empty when l1 + l2 < 2 l3). The paper's
    labels are kept as printed: region 1 is not "low dexterity" and region 2 is not the
    full-dexterity set; use :func:`full_dexterity_bands` for that.
    """
    r1, r2, r3 = region_radii(links)
    d = checked_array(
        distances,
        "distances",
        "paper_regions",
        "finite non-negative distances",
        lambda a: bool(np.all(a >= 0)),
    )
    regions = np.select([d <= r1, d <= r2, d <= r3], [1, 2, 3], default=4)
    return regions.astype(np.int8)


def synthesise_links(d_min: float, d_max: float, l3: float) -> Arm:
    """Link lengths by eqs (10)-(11): l1 = (d_max + l3)/2 + 1, l2 = (d_max + l3)/2.

    The "+1" (in the task's length unit) makes |l1 - l2| = 1, so full dexterity at d_min
    needs l3 + 1 <= d_min, not only the paper's l3 < d_min (docs/methods/planar-serial.md); callers
    check that. Returns (l1, l2, l3) as an :class:`~.inputs.Arm` (checked once).
    """
    if not (math.isfinite(l3) and l3 > 0):
        raise bad_parameter("l3", "synthesise_links", "a finite positive length", l3)
    if not (math.isfinite(d_min) and d_min >= 0):
        raise bad_parameter("d_min", "synthesise_links", "a finite non-negative distance", d_min)
    if not (math.isfinite(d_max) and d_max >= d_min):
        raise bad_parameter(
            "d_max", "synthesise_links", f"a finite distance >= d_min = {d_min}", d_max
        )
    half = (d_max + l3) / 2.0
    return Arm(half + 1.0, half, float(l3))  # positive: checked once, here
