"""The paper's four regions (§5, eq 13) next to what the exact d_z says about them.

Patel & Sobh split the workspace by the distance d from the base at l3, l1 + l2 - l3 and
l1 + l2 + l3 and describe each piece; docs/methods/planar-serial.md corrects the
descriptions (Region 1 can be fully dexterous, Region 2 is not entirely so).  Both are
reported, with the exact full-dexterity bands and the range of d_z along a ray: with
unlimited joints d_z depends on d only; under joint limits the table describes the
limited arm along one ray, from the exact events
(:func:`~worker.families.planar_serial.kinematics.ray.ray_dexterity`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import minimize_scalar

from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.jobs.dexterity_evaluation import (
    FULL_DEXTERITY_TOL,
    FloatArray,
    Links,
)
from worker.families.planar_serial.kinematics.ray import ray_dexterity

__all__ = [
    "PAPER_REGION_CLAIMS",
    "REGION_NAMES",
    "Bands",
    "LimitedRay",
    "describe_bands",
    "limited_ray_profile",
    "region_2_note",
    "region_table",
]

REGION_NAMES = {
    1: "inner disk",
    2: "paper's high-dexterity band",
    3: "outer band",
    4: "beyond reach",
}
PAPER_REGION_CLAIMS = {
    1: "0 <= d <= l3: the virtual link d is the shortest link; points have limited inverse "
    "kinematic solutions (low dexterity)",
    2: "l3 < d <= l1 + l2 - l3 (eq 13): Grashof's criterion holds for every d, the "
    "end-effector turns fully, maximum dexterity (d_z = 1)",
    3: "l1 + l2 - l3 < d <= l1 + l2 + l3: non-Grashof; dexterity falls towards the edge "
    "of the workspace",
    4: "d > l1 + l2 + l3: beyond the reach of the end-effector (printed as a second 'Region 3')",
}
#: Closed radius intervals (lo, hi), sorted and disjoint (``full_dexterity_bands``).
Bands = tuple[tuple[float, float], ...]
#: Distances sampled per region to find the range of d_z along a ray.
RAY_SAMPLES = 4001


def describe_bands(bands: Bands) -> str:
    """'[0, 7] ∪ [9, 21]' (lengths with up to 6 significant digits), or 'nowhere'."""
    if not bands:
        return "nowhere"
    return " ∪ ".join(f"[{lo:.6g}, {hi:.6g}]" for lo, hi in bands)


def _dz_range(links: Links, lo: float, hi: float) -> tuple[float, float, float]:
    """(min d_z, its distance, max d_z) over [lo, hi] with unlimited joints."""
    distances = np.linspace(lo, hi, RAY_SAMPLES)
    points = np.stack([distances, np.zeros_like(distances)], axis=-1)
    d_z = planar_serial.exact_orientation_dexterity(links, points)
    i = int(np.argmin(d_z))
    best_d, best = float(distances[i]), float(d_z[i])
    left, right = distances[max(i - 1, 0)], distances[min(i + 1, RAY_SAMPLES - 1)]
    if right > left:
        refined = minimize_scalar(
            lambda d: float(planar_serial.exact_orientation_dexterity(links, [[d, 0.0]])[0]),
            bounds=(float(left), float(right)),
            method="bounded",
            options={"xatol": 1e-9 * max(1.0, hi)},
        )
        if refined.fun < best:
            best_d, best = float(refined.x), float(refined.fun)
    return best, best_d, float(np.max(d_z))


@dataclass(frozen=True)
class LimitedRay:
    """The joint-limited arm along the radial section's ray: per region 1-3 the least
    d_z, where, and the largest (exact events, certified to 1e-10), and the closed
    distance intervals of [0, l1 + l2 + l3] where d_z = 1."""

    angle_deg: float
    spans: tuple[tuple[float, float, float], ...]
    bands: tuple[tuple[float, float], ...]


def _region_edges(links: Links) -> list[float]:
    """0 and the ends of regions 1-3; the first matching rule wins (paper_regions), so
    an inverted region is empty."""
    r1, r2, r3 = planar_serial.region_radii(links)
    return [0.0, r1, max(r1, r2), max(r1, r2, r3)]


def limited_ray_profile(links: Links, joint_limits_rad: FloatArray, angle_deg: float) -> LimitedRay:
    """The limited arm's d_z along the ray at ``angle_deg`` over the paper's regions."""
    profile = ray_dexterity(links, joint_limits_rad, math.radians(angle_deg), _region_edges(links))
    spans = tuple((r.d_z_min, r.d_z_min_at, r.d_z_max) for r in profile.ranges)
    return LimitedRay(angle_deg, spans, profile.bands)


def _finding(
    lo: float,
    hi: float,
    bands: tuple[tuple[float, float], ...],
    span: tuple[float, float, float],
    where: str,
) -> tuple[str, dict[str, Any]]:
    # Regions 2-3 are open at d_from: a band ending exactly there lies in the region below.
    closed_below = lo == 0.0
    inside = tuple(
        (max(a, lo), min(b, hi)) for a, b in bands if a <= hi and (b > lo or closed_below)
    )
    d_z_min, d_min_at, d_z_max = span
    facts: dict[str, Any] = {
        "fully_dexterous_bands": [list(band) for band in inside],
        "d_z_min": d_z_min,
        "d_z_min_at": d_min_at,
        "d_z_max": d_z_max,
    }
    if d_z_min >= 1.0 - FULL_DEXTERITY_TOL:
        return f"{where}d_z = 1 throughout", facts
    at = f"min d_z = {d_z_min:.6f} at d = {d_min_at:.4g}, max {d_z_max:.6f}"
    if not inside:
        return f"{where}d_z < 1 throughout ({at})", facts
    return f"{where}d_z = 1 only on {describe_bands(inside)}; elsewhere below 1 ({at})", facts


def _along(limited: LimitedRay) -> str:
    return f"with these joint limits, along the ray at {limited.angle_deg:g}°: "


def region_table(
    links: Links, limited: LimitedRay | None = None, *, bands: Bands | None = None
) -> list[dict[str, Any]]:
    """The paper's regions 1-4 with their claims and the exact findings.

    Each entry: region, name, d_from, d_to (None for region 4), paper, corrected, and the
    facts behind ``corrected``: fully_dexterous_bands (the exact d_z = 1 radii inside the
    region), d_z_min, d_z_min_at, d_z_max (along a ray over the closed interval
    [d_from, d_to]; None for an empty region).  Without ``limited`` they are the
    unlimited arm's (d_z depends on d only); with it, the joint-limited arm's along its
    ray, and ``paper`` says that the claim was made for unlimited joints.  ``bands``:
    the unlimited arm's full-dexterity bands, if the caller has them already.
    """
    edges = _region_edges(links)
    if limited is None:
        bands = planar_serial.full_dexterity_bands(links) if bands is None else bands
        where, claimed = "", ""
    else:
        bands, where, claimed = limited.bands, _along(limited), "; claimed for unlimited joints"
    table: list[dict[str, Any]] = []
    for region in (1, 2, 3):
        lo, hi = edges[region - 1], edges[region]
        entry: dict[str, Any] = {
            "region": region,
            "name": REGION_NAMES[region],
            "d_from": lo,
            "d_to": hi,
            "paper": PAPER_REGION_CLAIMS[region] + claimed,
        }
        if hi > lo:
            span = _dz_range(links, lo, hi) if limited is None else limited.spans[region - 1]
            corrected, facts = _finding(lo, hi, bands, span, where)
        else:
            corrected = "empty for these links (l1 + l2 - l3 <= l3)"
            facts = dict.fromkeys(("d_z_min", "d_z_min_at", "d_z_max"))
            facts["fully_dexterous_bands"] = []
        table.append({**entry, "corrected": corrected, **facts})
    table.append(
        {
            "region": 4,
            "name": REGION_NAMES[4],
            "d_from": edges[3],
            "d_to": None,
            "paper": PAPER_REGION_CLAIMS[4],
            "corrected": "unreachable: d_z = 0",
            "fully_dexterous_bands": [],
            "d_z_min": 0.0,
            "d_z_min_at": None,
            "d_z_max": 0.0,
        }
    )
    return table


def region_2_note(
    links: Links,
    table: list[dict[str, Any]] | None = None,
    limited: LimitedRay | None = None,
    *,
    bands: Bands | None = None,
) -> str:
    """A note contrasting the paper's Region 2 with the exact full-dexterity bands
    (``table``: :func:`region_table` of these links and ``limited``, and ``bands``: the
    unlimited arm's, if already computed); under joint limits, the limited arm's along
    its ray."""
    l1, l2, l3 = links
    if bands is None:
        bands = planar_serial.full_dexterity_bands(links)
    unlimited = describe_bands(bands)
    arm = f"({l1:.6g}, {l2:.6g}, {l3:.6g})"
    source = "docs/methods/planar-serial.md"
    if limited is None:
        found = f"for {arm} with unlimited joints d_z = 1 exactly for d in {unlimited} ({source})"
    else:
        found = (
            f"for {arm} {_along(limited).removesuffix(': ')}, d_z = 1 exactly for d in "
            f"{describe_bands(limited.bands)} (with unlimited joints {unlimited}; {source})"
        )
    note = (
        f"The paper's Region 2 (l3 < d <= l1 + l2 - l3 = {l1 + l2 - l3:.6g}, eq 13) is not the "
        f"fully dexterous set: {found}"
    )
    regions = region_table(links, limited, bands=bands) if table is None else table
    inner = [r for r in regions[:2] if r["d_z_min"] is not None]
    dip = min(inner, key=lambda r: float(r["d_z_min"]))
    if dip["d_z_min"] < 1.0 - FULL_DEXTERITY_TOL:
        note += (
            f"; for d <= l1 + l2 - l3 it falls to {dip['d_z_min']:.6f} at "
            f"d = {dip['d_z_min_at']:.4g}"
        )
    return note + "."
