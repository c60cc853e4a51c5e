"""The conditioning index across one sub-design space (the paper's Fig. 6).

For one (beta, gamma), designs on a p x p grid of (s, t) in [-1, 1]^2, with
a1 - a2 = s D1 and a1 + a2 - 180 = t D2 (the rectangle of eq 19), each scored by
mean(1/kappa^2) (eq 28) over the workspace samples. Angles in degrees outside,
radians inside the kinematics.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.jobs.design_entries import (
    design_entry,
    finite,
    indices_entry,
)
from worker.families.spherical_parallel.jobs.workspace_sampling import FloatArray

__all__ = ["TIE", "IndexDistribution", "index_distribution", "index_distribution_entry"]

#: Grid designs within this of the best value are all reported as best (twins tie).
TIE = 1e-9


@dataclass(frozen=True, eq=False)
class IndexDistribution:
    """mean(1/kappa^2) (p, p) over the designs alpha1_deg, alpha2_deg (p, p) of one
    (beta, gamma); NaN where a design misses part of the workspace. degenerate: the
    rectangle has no interior (the grid collapses onto a line or a point)."""

    beta_deg: float
    gamma_deg: float
    branch: int
    alpha1_deg: FloatArray
    alpha2_deg: FloatArray
    values: FloatArray
    degenerate: bool


def index_distribution(
    ws: sp.Workspace, samples: FloatArray, beta_deg: float, gamma_deg: float, points: int,
    branch: int,
) -> IndexDistribution:  # fmt: skip
    """Score every design of the (s, t) grid of one (beta, gamma) rectangle."""
    d1, d2 = sp.design_widths(ws, math.radians(beta_deg), math.radians(gamma_deg))
    s, t = np.meshgrid(np.linspace(-1.0, 1.0, points), np.linspace(-1.0, 1.0, points))
    a1 = 0.5 * (math.pi + s * d1 + t * d2)
    a2 = 0.5 * (math.pi + t * d2 - s * d1)
    values = np.full(a1.shape, np.nan)
    beta, gamma = math.radians(beta_deg), math.radians(gamma_deg)
    for index in np.ndindex(a1.shape):
        if 0.0 < a1[index] < math.pi and 0.0 < a2[index] < math.pi:
            design = sp.SpmDesign(float(a1[index]), float(a2[index]), beta, gamma)
            indices = sp.workspace_indices(design, samples, branch)
            values[index] = indices.mean_square_inverse_condition
    degenerate = min(d1, d2) <= sp.EDGE_TOLERANCE
    return IndexDistribution(beta_deg, gamma_deg, branch, np.degrees(a1), np.degrees(a2),
                             values, degenerate)  # fmt: skip


def best_designs(dist: IndexDistribution) -> list[tuple[float, float]]:
    """(alpha1, alpha2) in degrees of the grid designs tying for the best value."""
    if not np.isfinite(dist.values).any():
        return []
    top = float(np.nanmax(dist.values))
    where = np.argwhere(dist.values >= top - TIE)
    pairs = {(round(float(dist.alpha1_deg[i, j]), 9), round(float(dist.alpha2_deg[i, j]), 9))
             for i, j in where}  # fmt: skip
    return sorted(pairs)


def index_distribution_entry(dist: IndexDistribution, samples: FloatArray) -> dict[str, Any]:
    """The map's summary: grid, range, and the best grid designs with their indices."""
    finite_values = dist.values[np.isfinite(dist.values)]
    best = []
    for a1, a2 in best_designs(dist):
        design = sp.SpmDesign.from_degrees(a1, a2, dist.beta_deg, dist.gamma_deg)
        best.append({**design_entry(design),
                     "indices": indices_entry(sp.workspace_indices(design, samples,
                                                                   dist.branch))})  # fmt: skip
    return {
        "beta_deg": dist.beta_deg,
        "gamma_deg": dist.gamma_deg,
        "branch": dist.branch,
        "points_per_side": int(dist.values.shape[0]),
        "grid": "a1 - a2 = s D1, a1 + a2 - 180 = t D2, s and t evenly spaced over [-1, 1]",
        "index": "mean(1/kappa^2) over the workspace samples (eq 28)",
        "degenerate": dist.degenerate,
        "min": finite(finite_values.min()) if finite_values.size else None,
        "max": finite(finite_values.max()) if finite_values.size else None,
        "unscored_designs": int(dist.values.size - finite_values.size),
        "best": best,
    }
