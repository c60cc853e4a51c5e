"""Result entries of the optimisation: one per swept delta, and the chosen design.

Built from :class:`worker.families.planar_parallel.kinematics.SweepRow` (l1 = 1, l2 = delta,
e by eq 12). Values that do not exist (no rectangle at that delta) are JSON null.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.jobs.point_values import finite_or_none

__all__ = ["Design", "design_entry", "rescaled_row", "sweep_entry", "sweep_notes"]


@dataclass(frozen=True)
class Design:
    """The design a result reports: its sweep row and S_max (for S/S_max)."""

    row: pp.SweepRow
    S_max: float


def rescaled_row(row: pp.SweepRow, s_max: float) -> pp.SweepRow:
    """``row`` with S/S_max and eta = (S/S_max) mean 1/kappa recomputed for ``s_max``."""
    if not row.rectangle.found:
        return row
    ratio = row.rectangle.S / s_max
    return replace(row, area_ratio=ratio, eta=ratio * row.mean_inverse_condition)


def sweep_entry(row: pp.SweepRow) -> dict[str, Any]:
    """One delta of the sweep: delta, e, h, b, H_prime, S, S_over_S_max,
    mean_inverse_condition, eta, min_pressure_angle_deg, found."""
    rect = row.rectangle
    return {
        "delta": row.delta,
        "e": row.e,
        "h": finite_or_none(rect.h),
        "b": finite_or_none(rect.b),
        "H_prime": finite_or_none(rect.H_prime),
        "S": finite_or_none(rect.S),
        "S_over_S_max": finite_or_none(row.area_ratio),
        "mean_inverse_condition": finite_or_none(row.mean_inverse_condition),
        "eta": finite_or_none(row.eta),
        "min_pressure_angle_deg": finite_or_none(row.min_pressure_angle_deg),
        "found": rect.found,
    }


def design_entry(design: Design) -> dict[str, Any] | None:
    """The chosen design: delta, e, b, h, H_prime, S, mean_inverse_condition, eta,
    min_pressure_angle_deg, plus l1 = 1, l2 = delta, H (eq 12), S_over_S_max and the
    rectangle's boundary check. None when no rectangle was found."""
    row = design.row
    rect = row.rectangle
    if not rect.found:
        return None
    return {
        "delta": row.delta,
        "e": row.e,
        "b": rect.b,
        "h": rect.h,
        "H_prime": rect.H_prime,
        "S": rect.S,
        "mean_inverse_condition": row.mean_inverse_condition,
        "eta": row.eta,
        "min_pressure_angle_deg": row.min_pressure_angle_deg,
        "S_over_S_max": row.area_ratio,
        "l1": 1.0,
        "l2": row.delta,
        "H": math.sqrt(0.5) * (1.0 + row.delta),
        "boundary_min_inverse_condition": rect.boundary_min_inverse_condition,
        "rectangle_message": rect.message,
    }


def sweep_notes(rows: tuple[pp.SweepRow, ...]) -> list[str]:
    """Rectangles not found, or shrunk / cut by the search span, as notes."""
    notes = []
    missing = [row for row in rows if not row.rectangle.found]
    if missing:
        shown = ", ".join(f"{row.delta:.6g}" for row in missing[:8])
        more = f" and {len(missing) - 8} more" if len(missing) > 8 else ""
        notes.append(
            f"No rectangle W_lambda fits W_kappa0 at {len(missing)} of the {len(rows)} deltas "
            f"({shown}{more}): {missing[0].rectangle.message}. Their sizes, means and eta are "
            "null."
        )
    for marker in ("shrunk", "end of the searched span"):
        hit = [row for row in rows if row.rectangle.found and marker in row.rectangle.message]
        if hit:
            detail = hit[0].rectangle.message.split("; ")[-1]
            notes.append(f"At delta = {', '.join(f'{r.delta:.6g}' for r in hit[:8])}: {detail}.")
    return notes
