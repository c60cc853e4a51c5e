"""1/kappa on plain orientation grids: maps over tilt x azimuth and torsion sweeps.

The maps are the paper's Fig. 6 style (1/kappa over the pointing cone at a fixed
torsion), the sweeps its Fig. 7 (1/kappa along a full torsion turn at fixed psi1, psi2).
Neither grid is equal-weight: they are for looking, not for means. Angles in degrees
here, radians inside the kinematics; NaN marks a pose with no real inverse kinematics.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from worker.families.spherical_parallel import kinematics as sp
from worker.families.spherical_parallel.jobs.workspace_sampling import FloatArray
from worker.families.spherical_parallel.specs import SWEEP_POINTS

__all__ = [
    "SWEEP_POINTS",
    "InverseConditionMaps",
    "TorsionSweeps",
    "inverse_condition_maps",
    "sweep_start",
    "torsion_sweeps",
]


@dataclass(frozen=True, eq=False)
class InverseConditionMaps:
    """1/kappa (k, nt, na) over tilt_deg (nt,) x azimuth_deg (na,) at torsions_deg (k,)."""

    azimuth_deg: FloatArray
    tilt_deg: FloatArray
    torsions_deg: FloatArray
    values: FloatArray


@dataclass(frozen=True, eq=False)
class TorsionSweeps:
    """1/kappa (s, m) along psi3_deg (m,) at the (psi1, psi2) of azimuth_tilt_deg (s, 2)."""

    psi3_deg: FloatArray
    azimuth_tilt_deg: FloatArray
    values: FloatArray


def _inverse_condition(design: sp.SpmDesign, psi_deg: FloatArray, branch: int) -> FloatArray:
    indices = sp.workspace_indices(design, np.radians(psi_deg.reshape(-1, 3)), branch)
    values = np.where(indices.real, indices.inverse_condition, np.nan)
    return np.asarray(values, dtype=np.float64).reshape(psi_deg.shape[:-1])


def inverse_condition_maps(
    design: sp.SpmDesign,
    branch: int,
    torsions_deg: Sequence[float],
    tilt_max_deg: float,
    grid: tuple[int, int],
) -> InverseConditionMaps:
    """1/kappa over psi1 in [0, 360] (grid[0] values) x psi2 in [0, T] (grid[1] values)
    at each torsion."""
    azimuth = np.linspace(0.0, 360.0, grid[0])
    tilt = np.linspace(0.0, tilt_max_deg, grid[1])
    torsions = np.asarray(torsions_deg, dtype=np.float64)
    k, tt, aa = np.meshgrid(torsions, tilt, azimuth, indexing="ij")
    psi = np.stack([aa, tt, k], axis=-1)
    return InverseConditionMaps(azimuth, tilt, torsions, _inverse_condition(design, psi, branch))


def sweep_start(lo: float, hi: float, full_turn: bool) -> float:
    """Where a torsion sweep starts (deg): at lo for a full turn, else half a turn before
    the middle of [lo, hi], which puts the prescribed range in the middle of the plot."""
    return lo if full_turn else 0.5 * (lo + hi) - 180.0


def torsion_sweeps(
    design: sp.SpmDesign, branch: int, azimuth_tilt_deg: Sequence[tuple[float, float]],
    start_deg: float = 0.0,
) -> TorsionSweeps:  # fmt: skip
    """1/kappa along psi3 over one turn from start_deg (every 1°) at each (psi1, psi2)."""
    psi3 = np.linspace(start_deg, start_deg + 360.0, SWEEP_POINTS)
    pairs = np.asarray(azimuth_tilt_deg, dtype=np.float64).reshape(-1, 2)
    psi = np.empty((len(pairs), SWEEP_POINTS, 3))
    psi[..., 0] = pairs[:, :1]
    psi[..., 1] = pairs[:, 1:]
    psi[..., 2] = psi3
    return TorsionSweeps(psi3, pairs, _inverse_condition(design, psi, branch))
