"""Checks of a synthesised design: Grashof, the paper's claims, the real condition.

The paper (§4) claims eqs (10)-(11) give l1 > l2 > d > l3 and l1 + l3 > l2 + d at both
d_min and d_max; docs/methods/planar-serial.md shows the ordering fails in both examples
and that full dexterity over [d_min, d_max] needs the range inside the band
[l3 + |l1 - l2|, l1 + l2 - l3], i.e. l3 + 1 <= d_min for this design.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from worker.common import grashof
from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.jobs.dexterity_evaluation import Links
from worker.families.planar_serial.jobs.regions import region_2_note
from worker.families.planar_serial.kinematics.trajectory import DistanceRange
from worker.families.planar_serial.specs import SynthesisSpec

__all__ = [
    "design_notes",
    "full_dexterity_condition",
    "grashof_checks",
    "paper_conditions",
    "wrist_radii",
]

ORDERING = "l1 > l2 > d > l3"
SUM_CLAIM = "l1 + l3 > l2 + d"
LOWER_EDGE = "l3 + |l1 - l2| <= d_min"
UPPER_EDGE = "d_max + l3 <= l1 + l2"


def _json(value: Any) -> Any:
    if isinstance(value, tuple | list):
        return [_json(v) for v in value]
    if isinstance(value, bool | str) or value is None:
        return value
    if isinstance(value, int | float):
        return value if isinstance(value, int) else float(value)
    return value.item() if hasattr(value, "item") else value


def _grashof_at(links: Links, d: float) -> dict[str, Any]:
    check = grashof.four_bar_check((*links, d), names=("l1", "l2", "l3", "d"))
    entry = {key: _json(value) for key, value in dataclasses.asdict(check).items()}
    entry["d"] = d
    entry["end_effector_fully_rotatable"] = bool(grashof.end_effector_fully_rotatable(links, d))
    return entry


def grashof_checks(links: Links, d_min: float, d_max: float) -> dict[str, dict[str, Any]]:
    """Grashof's criterion on the virtual four-bar (l1, l2, l3, d) at d_min and d_max."""
    return {"d_min": _grashof_at(links, d_min), "d_max": _grashof_at(links, d_max)}


def paper_conditions(links: Links, d_min: float, d_max: float) -> dict[str, dict[str, Any]]:
    """The paper's claimed orderings (§4, after eq 11), evaluated at d_min and d_max."""
    l1, l2, l3 = links
    return {
        key: {"d": d, ORDERING: bool(l1 > l2 > d > l3), SUM_CLAIM: bool(l1 + l3 > l2 + d)}
        for key, d in (("d_min", d_min), ("d_max", d_max))
    }


def full_dexterity_condition(links: Links, d_min: float, d_max: float) -> dict[str, Any]:
    """Whether every distance in [d_min, d_max] is fully dexterous (unlimited joints).

    ``band`` is [l3 + |l1 - l2|, l1 + l2 - l3] (docs/methods/planar-serial.md);
    ``d_range_fully_dexterous`` also accepts a range inside the central disk
    [0, min(l3 - |l1-l2|, l1 + l2 - l3)].
    """
    l1, l2, l3 = links
    bands = planar_serial.full_dexterity_bands(links)
    return {
        "band": [l3 + abs(l1 - l2), l1 + l2 - l3],
        LOWER_EDGE: bool(l3 + abs(l1 - l2) <= d_min),
        UPPER_EDGE: bool(d_max + l3 <= l1 + l2),
        "l3 < d_min (paper)": bool(l3 < d_min),
        "d_range_fully_dexterous": any(lo <= d_min and d_max <= hi for lo, hi in bands),
    }


def wrist_radii(links: Links, th2_limits_deg: tuple[float, float]) -> tuple[float, float]:
    """(inner, outer) wrist distance |w| reachable by th2 in [lo, hi] (wrapped, degrees)."""
    l1, l2, _ = links
    lo, hi = th2_limits_deg
    farthest_from_zero = math.radians(max(abs(lo), abs(hi)))
    nearest_to_zero = 0.0 if lo <= 0.0 <= hi else math.radians(min(abs(lo), abs(hi)))

    def radius(th2: float) -> float:
        return math.sqrt(max(0.0, l1 * l1 + l2 * l2 + 2.0 * l1 * l2 * math.cos(th2)))

    return radius(farthest_from_zero), radius(nearest_to_zero)


def design_notes(
    spec: SynthesisSpec,
    links: Links,
    distances: DistanceRange,
    d_min_used: float,
    d_max_used: float,
) -> list[str]:
    """Notes on the design itself: the choice of l3, the real condition, the paper's claims."""
    l1, l2, l3 = links
    d_min, d_max = distances.d_min, distances.d_max
    notes: list[str] = []
    if spec.round_distances:
        notes.append(
            f"Distances rounded outward before eqs (10)-(11): [{d_min:.4f}, {d_max:.4f}] -> "
            f"[{d_min_used:g}, {d_max_used:g}]."
        )
    if not l3 < d_min:
        notes.append(f"l3 = {l3:g} is not below d_min = {d_min:.4f}, as the paper's step 2 asks.")
    condition = full_dexterity_condition(links, d_min, d_max)
    if not condition["d_range_fully_dexterous"]:
        lo, hi = condition["band"]
        notes.append(
            f"The design is not fully dexterous over [{d_min:.4f}, {d_max:.4f}]: with unlimited "
            f"joints d_z = 1 needs d in [{lo:.6g}, {hi:.6g}] (l3 + |l1 - l2| <= d_min, i.e. "
            f"l3 <= d_min - 1 here; the paper's l3 < d_min is not enough)."
        )
    claims = paper_conditions(links, d_min, d_max)
    failed = [
        f"'{claim}' at d_{end} = {claims[f'd_{end}']['d']:.4f}"
        for end in ("min", "max")
        for claim in (ORDERING, SUM_CLAIM)
        if not claims[f"d_{end}"][claim]
    ]
    if failed:
        notes.append(
            "The paper's claims after eq (11) do not hold for this design: "
            + "; ".join(failed)
            + f" (l1 = {l1:.6g}, l2 = {l2:.6g}, l3 = {l3:.6g}). They are not needed: see "
            "'full_dexterity_condition'."
        )
    notes.append(region_2_note(links))
    if spec.joint_limits_deg is not None:
        notes += _th2_limit_notes(links, spec.joint_limits_deg[1])
    return notes


def _th2_limit_notes(links: Links, th2_limits_deg: tuple[float, float]) -> list[str]:
    """What the elbow limits alone do to full dexterity (a necessary condition)."""
    l1, l2, l3 = links
    inner, outer = wrist_radii(links, th2_limits_deg)
    lo, hi = th2_limits_deg
    notes = []
    if inner > abs(l1 - l2) + 1e-12:
        notes.append(
            f"Case 3: the th2 limits [{lo:g}, {hi:g}]° raise the wrist's inner radius from "
            f"|l1 - l2| = {abs(l1 - l2):.6g} to {inner:.4f}, so full dexterity there needs "
            f"d >= l3 + {inner:.4f} = {l3 + inner:.4f} (necessary, not sufficient: th1 and th3 "
            "are limited too)."
        )
    if outer < l1 + l2 - 1e-12:
        notes.append(
            f"Case 3: the th2 limits [{lo:g}, {hi:g}]° lower the wrist's outer radius from "
            f"l1 + l2 = {l1 + l2:.6g} to {outer:.4f}, so full dexterity there needs "
            f"d <= {outer:.4f} - l3 = {outer - l3:.4f}."
        )
    return notes
