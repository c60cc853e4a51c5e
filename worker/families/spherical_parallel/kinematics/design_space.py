"""Design space of SPMs for a prescribed workspace (Bai 2010 eqs 14-19; see
docs/methods/spherical-parallel.md).

With n_i = -u_i and f_i = n_i . v_i over the CONTINUOUS workspace, a leg closes
everywhere iff |a1 - a2| <= D1 = acos(-f_min) and |a1 + a2 - pi| <= D2 = acos(f_max):
a rectangle in the (a1, a2) plane. D2 is the least angle between v_i and n_i over the
workspace and D1 the least angle between v_i and -n_i, so both are computed as angles
(no acos near +-1):

* full-turn torsion (closed form): v_i sweeps the band of polar angles
  [lo, hi] = [max(0, beta - T), min(pi, beta + T)] completely, and n_i sits at polar
  angle gamma, so ``D2 = max(0, lo - gamma, gamma - hi)`` and
  ``D1 = max(0, pi - hi - gamma, lo + gamma - pi)``;
* limited torsion: numerically, by :func:`~.axis_reach.least_angle`
  (on ranges just short of a full turn it meets the closed form to ~1e-14 rad, and to
  ~2e-10 rad where v_i only grazes n_i, a double zero; in 2,100 random and adversarial
  cases it never exceeded a brute-force grid).

Every leg sees the same range (psi1 covers a full turn), so leg 1 is enough. Angles in rad.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from worker.common.arrays import checked_array
from worker.common.parameter_errors import bad_parameter
from worker.families.spherical_parallel.kinematics.axis_reach import least_angle
from worker.families.spherical_parallel.kinematics.model import (
    BoolArray,
    FloatArray,
    SpmDesign,
    Workspace,
    checked_design,
    checked_workspace,
)

__all__ = [
    "EDGE_TOLERANCE",
    "DesignSpace",
    "design_margins",
    "design_space",
    "design_widths",
    "is_feasible",
    "link_angles",
]

#: Slack (rad) on the design-space inequalities: the paper's own optima sit exactly on
#: the corner, where the bounds are met with equality up to rounding.
EDGE_TOLERANCE = 1e-9


def _full_turn_widths(tilt: float, beta: FloatArray, gamma: float) -> tuple[FloatArray, FloatArray]:
    lo = np.maximum(0.0, beta - tilt)
    hi = np.minimum(np.pi, beta + tilt)
    d1 = np.maximum.reduce([np.zeros_like(lo), np.pi - hi - gamma, lo + gamma - np.pi])
    d2 = np.maximum.reduce([np.zeros_like(lo), lo - gamma, gamma - hi])
    return d1, d2


def _checked_angle(value: object, parameter: str, function: str, low_open: bool) -> float:
    angle = float(value) if isinstance(value, numbers.Real) else math.nan
    above = angle > 0.0 if low_open else angle >= 0.0
    if math.isfinite(angle) and above and angle < math.pi:
        return angle
    interval = "(0, pi)" if low_open else "[0, pi)"
    raise bad_parameter(parameter, function, f"a finite angle in {interval} rad", value)


def design_widths(ws: Workspace, beta: float, gamma: float) -> tuple[float, float]:
    """(D1, D2) rad of eqs 19a-b for one (beta, gamma) over the continuous workspace."""
    checked_workspace(ws, "design_widths")
    beta = _checked_angle(beta, "beta", "design_widths", low_open=True)
    gamma = _checked_angle(gamma, "gamma", "design_widths", low_open=False)
    if ws.full_turn:  # _full_turn_widths for one beta, with the math module (hot path)
        lo, hi = max(0.0, beta - ws.tilt_max), min(math.pi, beta + ws.tilt_max)
        d1 = max(0.0, math.pi - hi - gamma, lo + gamma - math.pi)
        return d1, max(0.0, lo - gamma, gamma - hi)
    normal = np.array([0.0, -math.sin(gamma), math.cos(gamma)])  # n_1 in the leg-1 frame
    return least_angle(ws, beta, -normal), least_angle(ws, beta, normal)


def link_angles(s: float, t: float, d1: float, d2: float) -> tuple[float, float]:
    """(a1, a2) with a1 - a2 = s D1 and a1 + a2 - pi = t D2 (s, t in [-1, 1] -> feasible)."""
    return 0.5 * (math.pi + s * d1 + t * d2), 0.5 * (math.pi + t * d2 - s * d1)


@dataclass(frozen=True, eq=False)
class DesignSpace:
    """Sub-design spaces for k values of beta at one gamma (Fig. 5), arrays (k,).

    f_min, f_max: bounds of f_i = n_i . v_i over the workspace (eqs 16-18); d1, d2: the
    half-widths acos(-f_min), acos(f_max) (rad) of the rectangle |a1 - a2| <= d1,
    |a1 + a2 - pi| <= d2 (eq 19). degenerate: no interior (a width <= EDGE_TOLERANCE,
    e.g. the line a1 + a2 = 180° at beta = 60° in a 120° cone); empty: both widths vanish,
    leaving only (90°, 90°), where every leg is stretched or folded somewhere — the
    rectangle itself always contains (90°, 90°).
    """

    betas: FloatArray
    gamma: float
    f_min: FloatArray
    f_max: FloatArray
    d1: FloatArray
    d2: FloatArray
    degenerate: BoolArray
    empty: BoolArray

    def corners(self) -> FloatArray:
        """(k, 4, 2) rad corners (a1, a2) at (s, t) = (-1, -1), (1, -1), (1, 1), (-1, 1)."""
        s = np.array([-1.0, 1.0, 1.0, -1.0])
        t = np.array([-1.0, -1.0, 1.0, 1.0])
        diff = s * self.d1[:, None]
        total = t * self.d2[:, None]
        return np.stack([0.5 * (np.pi + diff + total), 0.5 * (np.pi + total - diff)], axis=-1)


def design_space(ws: Workspace, gamma: float, betas: ArrayLike) -> DesignSpace:
    """Design space (eqs 14-19) over the continuous workspace ``ws`` for each beta (rad).

    gamma: base half-angle in [0, pi) rad; betas: (k,) rad in (0, pi).
    """
    function = "design_space"
    checked_workspace(ws, function)
    gamma = _checked_angle(gamma, "gamma", function, low_open=False)
    b = checked_array(betas, "betas", function, "finite angles in (0, pi) rad of shape (k,)",
                      lambda a: a.ndim == 1 and bool(np.all((a > 0) & (a < np.pi))))  # fmt: skip
    if ws.full_turn:
        d1, d2 = _full_turn_widths(ws.tilt_max, b, float(gamma))
    else:
        pairs = [design_widths(ws, float(beta), float(gamma)) for beta in b]
        d1 = np.array([p[0] for p in pairs]).reshape(b.shape)
        d2 = np.array([p[1] for p in pairs]).reshape(b.shape)
    thin1, thin2 = d1 <= EDGE_TOLERANCE, d2 <= EDGE_TOLERANCE
    return DesignSpace(
        b.copy(), float(gamma), -np.cos(d1), np.cos(d2), d1, d2, thin1 | thin2, thin1 & thin2
    )


def design_margins(design: SpmDesign, ws: Workspace) -> tuple[float, float]:
    """(D1 - |a1 - a2|, D2 - |a1 + a2 - pi|) rad: both >= 0 iff every leg closes
    everywhere in the continuous workspace (eq 19)."""
    checked_design(design, "design_margins")
    checked_workspace(ws, "design_margins")
    d1, d2 = design_widths(ws, design.beta, design.gamma)
    a1, a2 = design.alpha1, design.alpha2
    return d1 - abs(a1 - a2), d2 - abs(a1 + a2 - math.pi)


def is_feasible(design: SpmDesign, ws: Workspace, tolerance: float = EDGE_TOLERANCE) -> bool:
    """Whether ``design`` reaches all of ``ws`` (eq 19, up to ``tolerance`` rad)."""
    return min(design_margins(design, ws)) >= -tolerance
