"""Pressure angles (eq 15) and the conditioning limit they set (eqs 16-17 then 7) for
2-DOF planar parallel robots (Huang et al. 2004 §III-C-2; docs/methods/planar-parallel.md).

Re-exported by :mod:`worker.families.planar_parallel.kinematics`; conventions as there. The
paper's pressure angle beta_i is the acute angle between proximal and distal link,
|A_ii| = sin(beta_i) (eq 8): pi/2 is the best transmission, 0 a singularity.
"""

from __future__ import annotations

import math
from typing import Any, overload

import numpy as np
from scipy.optimize import minimize_scalar

from worker.common.parameter_errors import bad_parameter
from worker.families.planar_parallel.kinematics.model import (
    SIGNS,
    Architecture,
    BoolArray,
    FloatArray,
    finite_real,
    inverse_condition_kernel,
)

__all__ = [
    "condition_limit_from_pressure_angle",
    "max_condition_limit",
    "min_pressure_angle_in_rectangle",
    "pressure_angles_at",
    "proximal_pressure_angle",
]

HALF_SQRT2 = math.sqrt(0.5)
PAPER_MODE = (1, -1)


def proximal_pressure_angle(l1: Any, l2: Any, r2: Any) -> Any:
    """Eq (15): beta = acos(|l1^2 + l2^2 - |p_i|^2| / (2 l1 l2)), rad, from r2 = |p_i|^2.

    (The paper's form with l1 = 1, l2 = delta.) Depends on the distance to the pivot only,
    rises from 0 at |p_i| = |l1 - l2| to pi/2 at |p_i|^2 = l1^2 + l2^2, then falls to 0
    at |p_i| = l1 + l2.
    """
    cosine = np.abs(l1 * l1 + l2 * l2 - r2) / (2.0 * l1 * l2)
    return np.arccos(np.clip(cosine, 0.0, 1.0))


def min_pressure_angle_in_rectangle(
    arch: Architecture, l2: Any, e: Any, w: Any, bottom: Any, top: Any
) -> Any:
    """Exact min over the rectangle |x| <= w, bottom <= y <= top of min(beta_1, beta_2), rad.

    Proximal arm: beta_i depends only on |p_i| and is unimodal in it (eq 15), so its
    minimum is at the point nearest to or farthest from pivot i. Linear drive:
    beta_i = acos(|y| / l2), least at the largest |y|. Telescopic leg: pi/2 (A = E2).
    ``l2``, ``e``, w, bottom, top broadcast (batched rectangles).
    """
    if arch.actuation == "telescopic-leg":
        return np.full(np.shape(w), np.pi / 2.0)
    if arch.actuation == "linear-drive":
        y_far = np.maximum(np.abs(bottom), np.abs(top))
        return np.arccos(np.clip(y_far / l2, 0.0, 1.0))
    y_near = np.clip(0.0, bottom, top)
    y_far = np.where(np.abs(bottom) > np.abs(top), bottom, top)
    angles = []
    for sign in SIGNS:
        pivot = sign * e
        near = (np.clip(pivot, -w, w) - pivot) ** 2 + y_near**2
        far = (np.abs(pivot) + w) ** 2 + y_far**2
        angles += [proximal_pressure_angle(arch.l1, l2, near),
                   proximal_pressure_angle(arch.l1, l2, far)]  # fmt: skip
    return np.min(angles, axis=0)


def pressure_angles_at(arch: Architecture, x: Any, y: Any, reachable: BoolArray) -> FloatArray:
    """(beta_1, beta_2) (..., 2) at x, y (broadcast to reachable's shape), NaN outside."""
    if arch.actuation == "proximal-arm":
        angles = [proximal_pressure_angle(arch.l1, arch.l2, (x - s * arch.e) ** 2 + y * y)
                  for s in (1.0, -1.0)]  # fmt: skip
    elif arch.actuation == "linear-drive":
        angles = [np.arccos(np.clip(np.abs(y) / arch.l2, 0.0, 1.0))] * 2
    else:
        angles = [np.full(reachable.shape, np.pi / 2.0)] * 2
    result = np.stack([np.broadcast_to(b, reachable.shape) for b in angles], axis=-1)
    result[~reachable] = np.nan
    return np.asarray(result, dtype=np.float64)


@overload
def condition_limit_from_pressure_angle(allowable_deg: float, delta: float) -> float: ...
@overload
def condition_limit_from_pressure_angle(allowable_deg: float, delta: FloatArray) -> FloatArray: ...
def condition_limit_from_pressure_angle(
    allowable_deg: float, delta: float | FloatArray
) -> float | FloatArray:
    """1/kappa0 for an allowable pressure angle [beta] (deg) and delta, eqs (17) and (7).

    For the eq-(12) design (l1 = 1, l2 = delta >= 1) in the paper's mode: 1/kappa at
    (x0, y0) = (e, -sqrt(1 + delta^2 - 2 delta cos[beta])), where beta_1 = [beta] on the
    rectangle's top edge (eq 16). A float for a float delta, else an array of its shape.
    """
    function = "condition_limit_from_pressure_angle"
    if not (finite_real(allowable_deg) and 0.0 < allowable_deg < 90.0):
        raise bad_parameter("allowable_deg", function, "an angle in (0, 90) degrees",
                            allowable_deg)  # fmt: skip
    d = np.asarray(delta, dtype=np.float64)
    if not (np.all(np.isfinite(d)) and np.all(d >= 1.0)):
        raise bad_parameter("delta", function, "finite ratios l2 / l1 >= 1", delta)
    e = HALF_SQRT2 * (d - 1.0)
    y0 = -np.sqrt(1.0 + d * d - 2.0 * d * math.cos(math.radians(allowable_deg)))
    template = Architecture("proximal-arm", 1.0, 1.0, 0.0)
    value = inverse_condition_kernel(template, PAPER_MODE, e, y0, l2=d, e=e)
    if isinstance(delta, int | float):
        return float(value)
    return np.asarray(value, dtype=np.float64)


def max_condition_limit(
    allowable_deg: float, delta_range: tuple[float, float] = (1.0, 2.5)
) -> tuple[float, float]:
    """(max over delta of 1/kappa0, the delta at the max), eq (17) then eq (7) (Fig. 7).

    1501 samples over ``delta_range`` then a bounded Brent refinement (xatol 1e-12).
    30 deg -> 0.52555 at 1.7445; 35 deg -> 0.57672 at 1.9185 (docs/methods/planar-parallel.md).
    Only deltas where eq (17)'s point is in reach of both chains count (delta < delta_+,
    2.618 to 3.732 by [beta]); (nan, nan) if it is out of reach all over ``delta_range``.
    """
    function = "max_condition_limit"
    try:
        lo, hi = (float(v) for v in delta_range)
    except (TypeError, ValueError):
        raise bad_parameter("delta_range", function, "(lo, hi) with 1 <= lo < hi",
                            delta_range) from None  # fmt: skip
    if not (math.isfinite(hi) and 1.0 <= lo < hi):
        raise bad_parameter("delta_range", function, "(lo, hi) with 1 <= lo < hi", delta_range)
    deltas = np.linspace(lo, hi, 1501)
    values = np.nan_to_num(condition_limit_from_pressure_angle(allowable_deg, deltas), nan=-1.0)
    best = int(np.argmax(values))  # NaN (out of reach) must not win the argmax
    if not values[best] > 0.0:
        return math.nan, math.nan
    bounds = (deltas[max(best - 1, 0)], deltas[min(best + 1, deltas.size - 1)])
    result = minimize_scalar(
        lambda d: -np.nan_to_num(condition_limit_from_pressure_angle(allowable_deg, float(d)),
                                 nan=-1.0),
        bounds=bounds, method="bounded", options={"xatol": 1e-12},
    )  # fmt: skip
    best_delta = float(result.x)
    refined = condition_limit_from_pressure_angle(allowable_deg, best_delta)
    if not refined >= values[best]:  # the refinement left the reach: keep the sample
        return float(values[best]), float(deltas[best])
    return refined, best_delta
