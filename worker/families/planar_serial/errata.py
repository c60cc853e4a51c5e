"""Notes on the paper's printed errors, for requests that are recognisably its examples.

docs/methods/planar-serial.md lists what re-computation found wrong in Patel & Sobh's
Examples 1 and 2.  Those corrections are only worth a note when the request is the
paper's example (the same cubic, or the same seven task points); the jobs return them as
``JobOutcome.errata`` (the result's ``paper_errata``).  General corrections (Region 2,
the claimed orderings) are noted for every design by
:mod:`worker.families.planar_serial.jobs.design_checks`.
"""

from __future__ import annotations

import math
from typing import Any

from worker.families.planar_serial import kinematics as planar_serial
from worker.families.planar_serial.examples import (
    EXAMPLE_1_CUBIC,
    EXAMPLE_1_DESIGN,
    EXAMPLE_1_L3,
    EXAMPLE_1_SWAPPED_DESIGN,
    EXAMPLE_1_X_RANGE,
    EXAMPLE_2_DESIGN,
    EXAMPLE_2_L3,
    EXAMPLE_2_LABELS,
    EXAMPLE_2_TASK_POINTS,
    PAPER_JOINT_LIMITS_DEG,
)
from worker.families.planar_serial.jobs.dexterity_evaluation import FULL_DEXTERITY_TOL
from worker.families.planar_serial.jobs.regions import describe_bands
from worker.families.planar_serial.kinematics.inputs import Arm
from worker.families.planar_serial.specs import (
    DexterityMapSpec,
    PolynomialTrajectory,
    SynthesisSpec,
)

__all__ = [
    "dexterity_map_errata_notes",
    "is_example_1",
    "is_example_2",
    "synthesis_errata_notes",
]

Point = tuple[float, float]


def is_example_1(spec: SynthesisSpec) -> bool:
    """The trajectory is Example 1's cubic (eq 12) between x = 8 and x = 14."""
    trajectory = spec.trajectory
    return (
        isinstance(trajectory, PolynomialTrajectory)
        and trajectory.polynomial == EXAMPLE_1_CUBIC
        and {trajectory.x_start, trajectory.x_end} == set(EXAMPLE_1_X_RANGE)
    )


def _example_2_points(points: tuple[Point, ...] | None) -> bool:
    return points is not None and sorted(points) == sorted(EXAMPLE_2_TASK_POINTS)


def is_example_2(spec: SynthesisSpec) -> bool:
    """The task points are Example 2's seven points (in any order), with no trajectory."""
    return spec.trajectory is None and _example_2_points(spec.task_points)


def synthesis_errata_notes(spec: SynthesisSpec, result: dict[str, Any]) -> list[str]:
    """The paper's errata that concern this synthesis request, as notes."""
    if is_example_1(spec):
        return _example_1_notes(spec, result)
    if is_example_2(spec):
        return _example_2_notes(spec, result)
    return []


def dexterity_map_errata_notes(spec: DexterityMapSpec, result: dict[str, Any]) -> list[str]:
    """The paper's errata that concern this map: its Example 1 Case 2 arm, or its
    Example 2 design under the paper's limits at the Example 2 task points."""
    notes = []
    if spec.links == EXAMPLE_1_SWAPPED_DESIGN:
        notes.append(_swapped_band_note(EXAMPLE_1_SWAPPED_DESIGN, EXAMPLE_1_DESIGN))
    if (
        spec.links == EXAMPLE_2_DESIGN
        and spec.joint_limits_deg == PAPER_JOINT_LIMITS_DEG
        and _example_2_points(spec.task_points)
    ):
        notes.append(_three_points_note(result["task_points"]))
    return notes


def _design(links: tuple[float, ...] | list[float]) -> str:
    return "(" + ", ".join(f"{v:.6g}" for v in links) + ")"


def _fully_dexterous_fraction(links: tuple[float, float, float]) -> float:
    inner, outer = planar_serial.reach_radii(links)
    area = planar_serial.band_area(planar_serial.full_dexterity_bands(links))
    return area / (math.pi * (outer**2 - inner**2))


def _swapped_band_note(
    swapped: tuple[float, float, float], ideal: tuple[float, float, float]
) -> str:
    """Example 1, Case 2: the paper's band for the swapped arm vs the exact one."""
    swapped, ideal = Arm(*swapped), Arm(*ideal)  # the paper's designs: positive lengths
    return (
        "Example 1, Case 2: the paper gives the high-dexterity band of the arm with l2 and l3 "
        "swapped as 8 < d <= 16 (eq 13; another extraction of the paper reads 8 < d <= 9); "
        f"with {_design(swapped)} d_z = 1 only for d in "
        f"{describe_bands(planar_serial.full_dexterity_bands(swapped))} (fully dexterous "
        f"fraction of the reachable area {_fully_dexterous_fraction(swapped):.6f} vs "
        f"{_fully_dexterous_fraction(ideal):.6f} for {_design(ideal)})."
    )


def _three_points_note(entries: list[dict[str, Any]]) -> str:
    """Example 2, Case 3: 'three task points in the most dexterous region' vs the count."""
    ranked = sorted(entries, key=lambda e: -e["d_z"])
    full = [e["label"] for e in ranked if e["d_z"] >= 1.0 - FULL_DEXTERITY_TOL]
    rest = ", ".join(
        f"{e['label']} {e['d_z']:.4f}" for e in ranked if e["d_z"] < 1.0 - FULL_DEXTERITY_TOL
    )
    verb = "has" if len(full) == 1 else "have"
    return (
        "Example 2, Case 3: the paper says three task points lie in the most dexterous region "
        f"under the joint limits; {len(full)} ({', '.join(full) or 'none'}) {verb} d_z = 1 "
        f"(the others: {rest or 'none'})."
    )


def _example_1_notes(spec: SynthesisSpec, result: dict[str, Any]) -> list[str]:
    links = result["links"]
    note = (
        "Example 1: the paper reads 10 <= d <= 20 off the cubic (eq 12); the exact range is "
        f"d_min = {result['d_min']:.4f} (x = {result['d_min_at'][0]:.4f}) to d_max = "
        f"{result['d_max']:.4f} (x = {result['d_max_at'][0]:.4f}). The printed cubic misses "
        f"A (14, 14): y(14) = {result['d_max_at'][1]:.4f}."
    )
    if tuple(links) == EXAMPLE_1_DESIGN:
        note += " Rounded outward to 10 and 20, eqs (10)-(11) give the paper's (15, 14, 8)."
    else:
        note += (
            f" Eqs (10)-(11) give {_design(links)}; the paper's (15, 14, 8) comes from "
            "rounding the range outward (round_distances with l3 = 8)."
        )
    notes = [note]
    if spec.l3 == EXAMPLE_1_L3:
        l1, l2, l3 = links
        notes.append(_swapped_band_note((l1, l3, l2), (l1, l2, l3)))
    return notes


def _example_2_notes(spec: SynthesisSpec, result: dict[str, Any]) -> list[str]:
    paper_label = dict(zip(EXAMPLE_2_TASK_POINTS, EXAMPLE_2_LABELS, strict=True))
    at_min = paper_label.get(tuple(result["d_min_at"]), "?")
    at_max = paper_label.get(tuple(result["d_max_at"]), "?")
    note = (
        "Example 2: the paper gives the minimum and maximum distances as '29 (Point F) and "
        f"18 (Point B)'; they are swapped: d_min = {result['d_min']:.6g} ({at_min}), "
        f"d_max = {result['d_max']:.6g} ({at_max})."
    )
    if spec.l3 == EXAMPLE_2_L3:
        note += f" With l3 = 15 eqs (10)-(11) give {_design(result['links'])} as printed."
    notes = [note]
    limited = [c for c in result["cases"] if c["case"] == 3]
    if limited and spec.joint_limits_deg == PAPER_JOINT_LIMITS_DEG:
        notes.append(_three_points_note(limited[0]["task_points"]))
    return notes
