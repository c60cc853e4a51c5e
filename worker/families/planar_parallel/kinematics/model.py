"""The model behind :mod:`worker.families.planar_parallel.kinematics`: architecture, input checks
and the batched chain kernel (inverse kinematics, A and B of eq 4, 1/kappa of eq 7).

Huang et al., "Optimal kinematic design of 2-DOF parallel manipulators with well-shaped
workspace bounded by a specified conditioning index" (IEEE T-RA 2004), restated in
docs/methods/planar-parallel.md. Import the public names from
:mod:`worker.families.planar_parallel.kinematics`.

Geometry (Fig. 1), mirror-symmetric about the y axis, chain i = 1 on the +x side
(``sgn(1) = +1``, ``sgn(2) = -1``), end-effector reference point ``r = (x, y)``:

* ``proximal-arm``: revolute actuators at ``(sgn(i) e, 0)`` turn arms of length l1
  (actuated angle th_1i, rad); distal links l2 reach r. Eq (1)-(2).
* ``telescopic-leg``: legs from pivots at ``(sgn(i) e, 0)`` to r, actuated by their
  length q_i = |r - sgn(i) e e1|; A = E2; l1 and l2 are not used (no stroke limits).
* ``linear-drive``: sliders on the common line y = 0 (the x axis), drive direction
  u_i = e1, joint q_i = the slider's x coordinate; links l2 reach r; A = diag(w_i^T u_i);
  e and l1 are not used (no stroke limits).

Working mode ``(m1, m2)``, each +1 or -1: for the proximal arm m_i is the sign in front
of the square root of eq (2); the paper's mode is (+1, -1) (docs/methods/planar-parallel.md).
Equivalently ``th_1i = atan2(p_iy, p_ix) + m_i acos((|p_i|^2 + l1^2 - l2^2) / (2 l1 |p_i|))`` with
``p_i = r - sgn(i) e e1``, which is what the kernel evaluates (trig-free). For the linear
drive m_i = +1 puts slider i on the +x side of r: ``q_i = x + m_i sqrt(l2^2 - y^2)``.
The telescopic leg has one solution and ignores the mode. The pair is mirror-symmetric
(1/kappa(-x, y) = 1/kappa(x, y)) iff m2 = -m1 (always for the telescopic leg).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from typing import Any, Literal, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray

from worker.common.parameter_errors import bad_parameter

__all__ = [
    "SIGNS",
    "Actuation",
    "Architecture",
    "BoolArray",
    "ChainTerms",
    "FloatArray",
    "Robot",
    "WorkingMode",
    "chain_components",
    "chain_terms",
    "checked_limit",
    "checked_mode",
    "checked_points",
    "finite_real",
    "inverse_condition_from_terms",
    "inverse_condition_kernel",
    "inverse_condition_of_components",
    "is_mirror_symmetric",
    "joints_of_components",
]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]
Actuation = Literal["proximal-arm", "telescopic-leg", "linear-drive"]
WorkingMode = tuple[int, int]
ACTUATIONS: tuple[str, ...] = get_args(Actuation)
SIGNS = (1.0, -1.0)  # sgn(i), eq (1)


def finite_real(value: object) -> bool:
    """A finite real number (numpy scalars included, bool excluded)."""
    return (
        isinstance(value, numbers.Real)
        and not isinstance(value, bool)
        and math.isfinite(float(value))
    )


@dataclass(frozen=True)
class Architecture:
    """Dimensions of a mirror-symmetric 2-DOF planar parallel robot (Fig. 1).

    actuation: which of Fig. 1's types; l1: proximal arm length (1 normalises the
    proximal-arm type, docs/methods/planar-parallel.md); l2: distal link length (delta = l2 / l1);
    e: distance from O to each actuated joint, >= 0. Lengths in one unit, any unit.
    l1 and l2 are unused by the telescopic leg, l1 and e by the linear drive (they are
    still checked: finite, lengths positive).
    """

    actuation: Actuation
    l1: float
    l2: float
    e: float

    def __post_init__(self) -> None:
        if self.actuation not in ACTUATIONS:
            raise bad_parameter("actuation", "Architecture", f"one of {ACTUATIONS}", self.actuation)
        for name in ("l1", "l2"):
            value = getattr(self, name)
            if not (finite_real(value) and value > 0):
                raise bad_parameter(name, "Architecture", "a finite positive length", value)
        if not (finite_real(self.e) and self.e >= 0):
            raise bad_parameter("e", "Architecture", "a finite non-negative distance", self.e)


@dataclass(frozen=True)
class Robot:
    """One robot of Fig. 1 in one working mode: its :class:`Architecture` (which checked
    its dimensions) and the working mode, checked here once. A job builds one and passes
    it on; the functions taking a Robot trust it (no checks)."""

    arch: Architecture
    mode: WorkingMode

    def __post_init__(self) -> None:
        if not isinstance(self.arch, Architecture):
            raise bad_parameter("arch", "Robot", "an Architecture", self.arch)
        object.__setattr__(self, "mode", checked_mode(self.mode, "Robot"))


def checked_mode(working_mode: object, function: str) -> WorkingMode:
    """``working_mode`` as a pair of ints, each +1 or -1."""
    signs: list[int] = []
    if isinstance(working_mode, tuple | list) and len(working_mode) == 2:
        signs = [int(m) for m in working_mode if not isinstance(m, bool) and m in (1, -1)]
    if len(signs) != 2:
        raise bad_parameter("working_mode", function, "a pair of signs (+1 or -1)", working_mode)
    return signs[0], signs[1]


def checked_points(points: ArrayLike, function: str, parameter: str = "points") -> FloatArray:
    """``points`` as float64 (..., 2), finite."""
    requirement = "finite (x, y) coordinates of shape (..., 2)"
    try:
        arr = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise bad_parameter(parameter, function, requirement, points) from None
    if arr.ndim < 1 or arr.shape[-1] != 2 or not np.all(np.isfinite(arr)):
        raise bad_parameter(parameter, function, requirement, points)
    return arr


def checked_limit(limit: object, function: str) -> float:
    """A conditioning limit 1/kappa0 in (0, 1]."""
    if not (finite_real(limit) and 0.0 < float(limit) <= 1.0):  # type: ignore[arg-type]
        raise bad_parameter("limit", function, "a conditioning limit 1/kappa0 in (0, 1]", limit)
    return float(limit)  # type: ignore[arg-type]


def is_mirror_symmetric(arch: Architecture, mode: WorkingMode) -> bool:
    """True iff 1/kappa(-x, y) = 1/kappa(x, y) for this working mode."""
    return arch.actuation == "telescopic-leg" or mode[1] == -mode[0]


@dataclass(frozen=True)
class ChainTerms:
    """Per-point quantities of both chains; NaN where unreachable.

    reachable (...) bool; joints (..., 2) (rad for the proximal arm, lengths otherwise);
    a (..., 2) the diagonal of A (eq 4); w (..., 2, 2) rows w_i^T (B of eq 4);
    u (..., 2, 2) rows u_i^T (the proximal arm's direction, e1 for the linear drive,
    w_i for the telescopic leg).
    """

    reachable: BoolArray
    joints: FloatArray
    a: FloatArray
    w: FloatArray
    u: FloatArray


def _scalar_or(arch: Architecture, name: str, override: ArrayLike | None) -> Any:
    return getattr(arch, name) if override is None else override


def _chain(
    actuation: str, lengths: tuple[Any, Any, Any], sign: float, m: float, x: Any, y: Any
) -> tuple[Any, ...]:
    """One chain: (ok, a_ii, w_x, w_y, u_x, u_y, joint); arrays broadcast, junk where not ok."""
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # junk is masked
        return _chain_terms(actuation, lengths, sign, m, x, y)


def _proximal_reach(l1: Any, l2: Any, r2: Any) -> tuple[Any, Any, Any]:
    """(k, h2, ok): k = |p| cos(alpha) and h2 = |p|^2 sin^2(alpha) of eq (2)'s triangle
    (sides |p|, l1, l2), reachable iff h2 >= 0 and |p| > 0. One formula for every path,
    so that all functions agree on reachability to the last bit."""
    k = (r2 + l1 * l1 - l2 * l2) / (2.0 * l1)
    h2 = r2 - k * k
    return k, h2, (h2 >= 0.0) & (r2 > 0.0)


def _chain_terms(
    actuation: str, lengths: tuple[Any, Any, Any], sign: float, m: float, x: Any, y: Any
) -> tuple[Any, ...]:
    l1, l2, e = lengths
    if actuation == "linear-drive":
        h2 = l2 * l2 - y * y
        ok = h2 >= 0.0
        hh = np.sqrt(np.where(ok, h2, 0.0))
        wx = -m * hh / l2
        ones = np.ones_like(wx)
        return ok, wx, wx, y / l2, ones, 0.0 * ones, x + m * hh
    px = x - sign * e
    y2 = y * y
    r2 = px * px + y2
    safe = np.where(r2 > 0.0, r2, 1.0)
    if actuation == "telescopic-leg":
        rho = np.sqrt(safe)
        wx, wy = px / rho, y / rho
        return r2 > 0.0, np.ones_like(rho), wx, wy, wx, wy, np.sqrt(r2)
    k, h2, ok = _proximal_reach(l1, l2, r2)
    hh = m * np.sqrt(np.where(ok, h2, 0.0))
    ux = (k * px - hh * y) / safe
    uy = (k * y + hh * px) / safe
    # w_i^T Q u_i = p^T Q u / l2 = -m |p| sin(alpha) / l2; A_ii = l1 w_i^T Q u_i (eq 3)
    return ok, -l1 * hh / l2, (px - l1 * ux) / l2, (y - l1 * uy) / l2, ux, uy, None


def inverse_condition_from_terms(a1: Any, a2: Any, c: Any, s: Any) -> Any:
    """1/kappa of J = A^-1 B by eq (7), rationalised to avoid cancellation.

    With v_i = A_ii (up to a common factor), c = w1^T w2 and s = w1 x w2 (so that
    c^2 + s^2 = 1), eq (7) is ``sqrt((S - R) / (S + R))``, S = v1^2 + v2^2,
    R = sqrt((v1^2 - v2^2)^2 + (2 v1 v2 c)^2); since S^2 - R^2 = 4 v1^2 v2^2 (1 - c^2) it
    equals ``2 |v1 v2| |s| / (S + R)``, accurate near singularities too (|s| rather than
    sqrt(1 - c^2)). Where A is singular in both rows (S + R = 0) J does not exist; 0.
    """
    v1s, v2s = a1 * a1, a2 * a2
    root = np.sqrt((v1s - v2s) ** 2 + 4.0 * v1s * v2s * c * c)
    denominator = v1s + v2s + root
    safe = np.where(denominator > 0.0, denominator, 1.0)
    value = np.minimum(2.0 * np.abs(a1 * a2 * s) / safe, 1.0)  # rounding can pass 1 by 1 ulp
    return np.where(denominator > 0.0, value, 0.0)


def _proximal_inverse_condition(
    l1: float, l2: Any, e: Any, mode: WorkingMode, x: Any, y: Any
) -> tuple[Any, Any]:
    """(reachable, 1/kappa) of the proximal arm without forming u_i and w_i (hot path).

    With p_i = r - sgn(i) e e1, k_i = |p_i| cos(alpha_i), s_i = m_i |p_i| sin(alpha_i):
    l2 w_i = (1 - l1 k_i / |p_i|^2) p_i - (l1 s_i / |p_i|^2) Q p_i, v_i = -l1 s_i / l2, and
    p1 . p2 = x^2 - e^2 + y^2 and p1 x p2 = -2 e y give w1 . w2 and w1 x w2 in closed form
    (Q preserves dot and cross products, p x Q q = p . q).
    """
    y2 = y * y
    terms = []
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # junk masked by ok
        for sign, m in zip(SIGNS, mode, strict=True):
            px = x - sign * e
            r2 = px * px + y2
            k, h2, ok = _proximal_reach(l1, l2, r2)
            s = m * np.sqrt(np.maximum(h2, 0.0))
            inv = 1.0 / r2
            terms.append((ok, s, (r2 - l1 * k) * inv, -l1 * s * inv, px))
        (ok1, s1, a1, b1, p1x), (ok2, s2, a2, b2, p2x) = terms
        dot, cross = p1x * p2x + y2, -2.0 * e * y  # p1 . p2, p1 x p2
        same, mixed = a1 * a2 + b1 * b2, a1 * b2 - b1 * a2
        scale = 1.0 / (l2 * l2)
        c = (same * dot - mixed * cross) * scale
        sine = (same * cross + mixed * dot) * scale
        return ok1 & ok2, inverse_condition_from_terms(s1, s2, c, sine)


def inverse_condition_kernel(
    arch: Architecture,
    mode: WorkingMode,
    x: Any,
    y: Any,
    l2: ArrayLike | None = None,
    e: ArrayLike | None = None,
    outside: float = np.nan,
) -> FloatArray:
    """1/kappa (eq 7) at x, y (broadcast), ``outside`` (NaN) where unreachable; no checks.

    ``l2`` and ``e`` override the architecture's (arrays broadcast with x, y): the
    batched sweeps evaluate many architectures of one type in one call.
    """
    lengths = (arch.l1, _scalar_or(arch, "l2", l2), _scalar_or(arch, "e", e))
    if arch.actuation == "proximal-arm":
        ok, value = _proximal_inverse_condition(arch.l1, lengths[1], lengths[2], mode, x, y)
    else:
        first, second = chain_components(arch.actuation, lengths, mode, x, y)
        ok, value = first[0] & second[0], inverse_condition_of_components(first, second)
    # The linear drive's 1/kappa does not depend on x: broadcast to the full shape.
    shape = np.broadcast_shapes(
        np.shape(x), np.shape(y), np.shape(lengths[1]), np.shape(lengths[2])
    )
    result = np.asarray(np.where(ok, value, outside), dtype=np.float64)
    return result if result.shape == shape else np.broadcast_to(result, shape).copy()


def chain_components(
    actuation: str, lengths: tuple[Any, Any, Any], mode: WorkingMode, x: Any, y: Any
) -> tuple[tuple[Any, ...], tuple[Any, ...]]:
    """Both chains' (ok, A_ii, w_x, w_y, u_x, u_y, joint or None) at x, y (broadcast)."""
    first = _chain(actuation, lengths, SIGNS[0], mode[0], x, y)
    return first, _chain(actuation, lengths, SIGNS[1], mode[1], x, y)


def inverse_condition_of_components(first: tuple[Any, ...], second: tuple[Any, ...]) -> Any:
    """1/kappa from :func:`chain_components` (junk where not reachable: the junk may
    overflow or be undefined, and is masked by the caller, so it raises no warning)."""
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        c = first[2] * second[2] + first[3] * second[3]
        s = first[2] * second[3] - first[3] * second[2]
        return inverse_condition_from_terms(first[1], second[1], c, s)


def joints_of_components(actuation: str, chains: tuple[tuple[Any, ...], ...]) -> list[Any]:
    """The actuated joint of each chain: th_1i = atan2(u_y, u_x) in (-pi, pi] for the
    proximal arm, else the leg length or slider position."""
    if actuation == "proximal-arm":  # atan2(-0.0, -1) is -pi: keep (-pi, pi]
        return [np.where(q == -np.pi, np.pi, q)
                for q in (np.arctan2(chain[5], chain[4]) for chain in chains)]  # fmt: skip
    return [chain[6] for chain in chains]


def chain_terms(arch: Architecture, mode: WorkingMode, points: FloatArray) -> ChainTerms:
    """Inverse kinematics and the A, B terms of eq (4) at points (..., 2); no checks."""
    x, y = points[..., 0], points[..., 1]
    chains = chain_components(arch.actuation, (arch.l1, arch.l2, arch.e), mode, x, y)
    reachable = np.asarray(chains[0][0] & chains[1][0], dtype=np.bool_)

    def stacked(parts: list[Any]) -> FloatArray:
        full = [np.broadcast_to(np.asarray(part, dtype=np.float64), x.shape) for part in parts]
        result = np.stack(full, axis=-1)
        result[~reachable] = np.nan
        return result

    joints = stacked(joints_of_components(arch.actuation, chains))
    a = stacked([chain[1] for chain in chains])
    w = np.stack(
        [stacked([chain[2] for chain in chains]), stacked([chain[3] for chain in chains])], axis=-1
    )  # (..., chain, xy)
    u = np.stack([stacked([chain[4] for chain in chains]),
                  stacked([chain[5] for chain in chains])], axis=-1)  # fmt: skip
    return ChainTerms(reachable, joints, a, w, u)
