"""Notes on the paper's printed errors, for requests that are recognisably its examples.

docs/methods/planar-parallel.md lists what re-computation found wrong in Huang et al.'s
Table I and text.  Each note gives the paper's printed value next to the value this job
computed, so the difference is visible in every result that reproduces the paper.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from worker.families.planar_parallel import kinematics as pp
from worker.families.planar_parallel.examples import PAPER_ASPECT_RATIO, TABLE_I, TableIColumn
from worker.families.planar_parallel.specs import (
    DEFAULT_DELTA_RANGE,
    ConditioningMapSpec,
    OptimisationSpec,
)

__all__ = [
    "conditioning_map_errata_notes",
    "optimisation_errata_notes",
    "paper_rectangle_minimum",
    "table_column",
]

#: Mesh (nodes a side) on which the paper's printed rectangles are checked.
CHECK_MESH = 401
#: docs/methods/planar-parallel.md: [beta] that would give the paper's 0.581.
BETA_FOR_0581 = "35.3-35.4°"
#: §IV on Fig. 8: the mean 1/kappa over delta in [1, 2.5] "varies between" these, per [beta].
PAPER_MEAN_RANGES = {30.0: (0.74, 0.80), 35.0: (0.77, 0.83)}
#: Half a unit in the last place of the paper's two-decimal range.
PAPER_MEAN_ROUNDING = 0.005


def table_column(spec: OptimisationSpec) -> tuple[TableIColumn, bool] | None:
    """The Table I column the request reproduces and whether it starts from the paper's
    inputs ([beta]) rather than its printed limit; None for other requests."""
    if spec.aspect_ratio != PAPER_ASPECT_RATIO:
        return None
    for column in TABLE_I:
        if spec.allowable_pressure_angle_deg == column.allowable_pressure_angle_deg:
            return column, True
        if spec.inverse_condition_limit == column.inverse_condition_limit:
            return column, False
    return None


def paper_rectangle_minimum(column: TableIColumn) -> tuple[float, float, float]:
    """(min 1/kappa, x, y) over the paper's printed rectangle of ``column`` on a
    :data:`CHECK_MESH` x :data:`CHECK_MESH` mesh (its own e by eq 12)."""
    arch = pp.isotropic_architecture(column.delta)
    xs = np.linspace(-column.b / 2, column.b / 2, CHECK_MESH)
    ys = np.linspace(-column.H_prime - column.h / 2, -column.H_prime + column.h / 2, CHECK_MESH)
    values = pp.conditioning_map(arch, xs, ys).inverse_condition
    filled = np.nan_to_num(values, nan=0.0)
    iy, ix = np.unravel_index(int(np.argmin(filled)), filled.shape)
    return float(filled[iy, ix]), float(xs[ix]), float(ys[iy])


def _e_note(column: TableIColumn) -> str | None:
    e = math.sqrt(0.5) * (column.delta - 1.0)
    if round(e, 4) == column.e:
        return None
    return (f"Table I prints e = {column.e:.4f} for delta = {column.delta:g}; eq (12) gives "
            f"e = (√2/2)(delta - 1) = {e:.4f}.")  # fmt: skip


def _rectangle_note(column: TableIColumn) -> str:
    low, x, y = paper_rectangle_minimum(column)
    inside = low >= column.inverse_condition_limit
    verdict = "lies inside" if inside else "does not lie inside"
    return (
        f"The paper's printed rectangle for [beta] = {column.allowable_pressure_angle_deg:g}° "
        f"(delta = {column.delta:g}, h = {column.h:g}, b = 4h, H' = {column.H_prime:g}) "
        f"{verdict} its W_kappa0: min 1/kappa on it is {low:.4f} at ({x:.4f}, {y:.4f}) vs "
        f"the limit {column.inverse_condition_limit:g} ({CHECK_MESH}² mesh)."
    )


def conditioning_map_errata_notes(spec: ConditioningMapSpec) -> list[str]:
    """Table I's e for the isotropic designs it prints, and whether its printed rectangle
    lies in W_kappa0 when the map uses that design's printed limit."""
    if spec.architecture != "isotropic" or spec.l1 != 1.0:
        return []
    notes = []
    for column in TABLE_I:
        if spec.l2 != column.delta:
            continue
        if (note := _e_note(column)) is not None:
            notes.append(note)
        if spec.inverse_condition_limit == column.inverse_condition_limit:
            notes.append(_rectangle_note(column))
    return notes


def _row_at(rows: tuple[pp.SweepRow, ...], delta: float) -> pp.SweepRow | None:
    return next((r for r in rows if abs(r.delta - delta) < 1e-9 and r.rectangle.found), None)


def _row_note(column: TableIColumn, row: pp.SweepRow, mesh: int, prefix: str) -> str:
    rect = row.rectangle
    note = (
        f"{prefix}Table I prints h = {column.h:.4f}, H' = {column.H_prime:.4f}, S = "
        f"{column.S:.4f}, mean 1/kappa = {column.mean_inverse_condition:.4f}, eta = "
        f"{column.eta:.4f} at delta = {column.delta:g}; this job finds h = {rect.h:.4f}, "
        f"H' = {rect.H_prime:.4f}, S = {rect.S:.4f}, mean 1/kappa = "
        f"{row.mean_inverse_condition:.4f} ({mesh} x {mesh} mesh), eta = {row.eta:.4f}."
    )
    implied_h = math.sqrt(column.S / PAPER_ASPECT_RATIO)
    if abs(implied_h - column.h) > 5e-4:
        note += (f" The paper's own S implies h = {implied_h:.4f} (4 x {column.h:g}² = "
                 f"{PAPER_ASPECT_RATIO * column.h**2:.4f} ≠ S).")  # fmt: skip
    return note


def _pair_note(column: TableIColumn) -> str | None:
    if column.eta > column.mean_inverse_condition:
        return (
            f"Table I's eta = {column.eta:.4f} exceeds its mean 1/kappa = "
            f"{column.mean_inverse_condition:.4f}; eta = (S/S_max) mean <= mean must hold."
        )
    if column.eta == column.mean_inverse_condition:
        return (f"Table I prints mean 1/kappa = eta = {column.eta:.4f}; with S < S_max that "
                "cannot be, and the paper's text puts the mean at 0.77-0.83 with its minimum "
                "near the optimum: the mean looks copied from eta.")  # fmt: skip
    return None


def _limit_note(column: TableIColumn, result: dict[str, Any]) -> str:
    note = (f"The paper gives 1/kappa0 = {column.inverse_condition_limit:g} for [beta] = "
            f"{column.allowable_pressure_angle_deg:g}°; eq (17) + eq (7) give "
            f"{result['inverse_condition_limit']:.5f} (max at delta = "
            f"{result['inverse_condition_limit_delta']:.4f}).")  # fmt: skip
    if column.inverse_condition_limit == 0.581:
        note += f" 0.581 would need [beta] ≈ {BETA_FOR_0581}."
    return note


def _optimum_note(column: TableIColumn, result: dict[str, Any]) -> str | None:
    optimum, window = result["optimum"], result["window"]
    if optimum is None or window is None:
        return None
    note = (f"The paper's optimum delta = {column.delta:g}; eta is flat: within 0.001 of its "
            f"maximum on [{window[0]:.4g}, {window[1]:.4g}], max at delta = "
            f"{optimum['delta']:.4g} (eta = {optimum['eta']:.4f}).")  # fmt: skip
    peak = result["inverse_condition_limit_delta"]
    if peak is not None and not window[0] <= peak <= window[1]:
        note += (f" 1/kappa0 of eq (17) peaks at delta = {peak:.4f}, outside that window: "
                 "the paper's §IV says the two maxima coincide.")  # fmt: skip
    return note


def _mean_range_note(
    column: TableIColumn, spec: OptimisationSpec, rows: tuple[pp.SweepRow, ...]
) -> str | None:
    """The paper's range of the mean 1/kappa over its delta range (§IV, Fig. 8) vs the
    sweep's; only for sweeps over that range."""
    if spec.delta is not None or spec.sweep_range != DEFAULT_DELTA_RANGE:
        return None
    found = [r for r in rows if r.rectangle.found and math.isfinite(r.mean_inverse_condition)]
    if not found:
        return None
    low = min(found, key=lambda r: r.mean_inverse_condition)
    high = max(found, key=lambda r: r.mean_inverse_condition)
    paper_low, paper_high = PAPER_MEAN_RANGES[column.allowable_pressure_angle_deg]
    panel = "ab"[TABLE_I.index(column)]
    note = (
        f"The paper's text (Fig. 8({panel})) puts the mean 1/kappa between {paper_low:.2f} "
        f"and {paper_high:.2f} over delta in [1, 2.5]; this sweep finds "
        f"{low.mean_inverse_condition:.4f} (delta = {low.delta:.4g}) to "
        f"{high.mean_inverse_condition:.4f} (delta = {high.delta:.4g}) on {spec.mean_mesh} x "
        f"{spec.mean_mesh} nodes"
    )
    if (abs(low.mean_inverse_condition - paper_low) > PAPER_MEAN_ROUNDING
            or abs(high.mean_inverse_condition - paper_high) > PAPER_MEAN_ROUNDING):  # fmt: skip
        note += (", beyond the paper's two-decimal rounding (the mean grows with the mesh, "
                 "docs/methods/planar-parallel.md)")  # fmt: skip
    return note + "."


def optimisation_errata_notes(
    spec: OptimisationSpec, result: dict[str, Any], rows: tuple[pp.SweepRow, ...]
) -> list[str]:
    """The paper's Table I errata that concern this request (docs/methods/planar-parallel.md),
    and its §IV statements on Fig. 8 (the optimum, the range of the mean) next to this
    sweep's, as notes.

    Requests starting from [beta] (a Table I column's angle, lambda = 4) and sweeps or the
    printed delta at a printed limit get them; other requests none."""
    match = table_column(spec)
    if match is None:
        return []
    column, from_inputs = match
    if not from_inputs and spec.delta is not None and spec.delta != column.delta:
        return []  # the printed limit at another single delta: no Table I row to compare
    notes = [_limit_note(column, result)] if from_inputs else []
    for note in (_optimum_note(column, result), _mean_range_note(column, spec, rows)):
        if note is not None:
            notes.append(note)
    if (row := _row_at(rows, column.delta)) is not None:
        prefix = (f"At the paper's delta = {column.delta:g} with 1/kappa0 = "
                  f"{result['inverse_condition_limit']:.5f}: " if from_inputs else "")  # fmt: skip
        notes.append(_row_note(column, row, spec.mean_mesh, prefix))
    if (note := _e_note(column)) is not None:
        notes.append(note)
    if (note := _pair_note(column)) is not None:
        notes.append(note)
    notes.append(_rectangle_note(column))
    return notes
