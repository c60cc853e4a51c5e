"""How a design and its conditioning are written into a result document.

Every design an spm job evaluates is reported with the same block
(docs/methods/spherical-parallel.md): C_n = ``rms_inverse_condition`` (eq 25),
``mean_square_inverse_condition`` (eq 28, what the paper prints as "C_n"), ``gci``
(eq 24), ``min_inverse_condition`` over the samples, and the least 1/kappa on the closed
workspace, boundary included. Non-finite values (a design that misses part of the
workspace is never scored) become ``null``.
"""

from __future__ import annotations

import math
from typing import Any

from worker.families.spherical_parallel import kinematics as sp

__all__ = [
    "design_entry",
    "design_space_check",
    "finite",
    "indices_entry",
    "minimum_entry",
]


def finite(value: float) -> float | None:
    """``value`` as a float, or None when it is NaN or infinite (JSON has neither)."""
    value = float(value)
    return value if math.isfinite(value) else None


def design_entry(design: sp.SpmDesign) -> dict[str, float]:
    """alpha1_deg, alpha2_deg, beta_deg, gamma_deg (rounded to 1e-10 deg)."""
    a1, a2, beta, gamma = design.degrees()
    return {
        "alpha1_deg": round(a1, 10),
        "alpha2_deg": round(a2, 10),
        "beta_deg": round(beta, 10),
        "gamma_deg": round(gamma, 10),
    }


def indices_entry(indices: sp.Indices) -> dict[str, Any]:
    """The conditioning of a design over the samples (nulls unless every leg closes
    everywhere: ``all_real``)."""
    real = int(indices.real.sum())
    return {
        "rms_inverse_condition": finite(indices.rms_inverse_condition),
        "mean_square_inverse_condition": finite(indices.mean_square_inverse_condition),
        "gci": finite(indices.gci),
        "min_inverse_condition": finite(indices.min_inverse_condition),
        "max_inverse_condition": finite(indices.max_inverse_condition),
        "min_abs_det_a": finite(indices.min_abs_det_a),
        "all_real": indices.all_real,
        "samples": int(indices.real.size),
        "real_samples": real,
        "branch": indices.branch,
    }


def minimum_entry(minimum: sp.WorkspaceMinimum) -> dict[str, Any]:
    """The least 1/kappa on a boundary-inclusive grid of the closed workspace."""
    return {
        "inverse_condition": finite(minimum.inverse_condition),
        "psi_deg": [round(math.degrees(float(v)), 10) for v in minimum.psi],
        "all_real": minimum.all_real,
        "grid_points": minimum.grid_size,
        "grid": "psi1 over one 120° period every 5°, psi2 = 13 values over [0, T] (ends "
        "included), psi3 every 5° over a full turn or 72 values over [lo, hi]",
    }


def design_space_check(design: sp.SpmDesign, ws: sp.Workspace) -> dict[str, Any]:
    """Where the design sits in the design space of eq 19 (continuous workspace)."""
    d1, d2 = sp.design_widths(ws, design.beta, design.gamma)
    m1, m2 = sp.design_margins(design, ws)
    feasible = min(m1, m2) >= -sp.EDGE_TOLERANCE
    return {
        "f_min": -math.cos(d1),
        "f_max": math.cos(d2),
        "D1_deg": math.degrees(d1),
        "D2_deg": math.degrees(d2),
        "margins_deg": [math.degrees(m1), math.degrees(m2)],
        "feasible": feasible,
        "on_edge": feasible and min(m1, m2) <= math.radians(1e-6),
        "inequalities": "|a1 - a2| <= D1 = acos(-f_min), |a1 + a2 - 180| <= D2 = acos(f_max) "
        "(eqs 16-19); margins are D1 - |a1 - a2| and D2 - |a1 + a2 - 180|",
    }
