"""Four-bar chains: Grashof type, Barker's classes, and which links turn fully.

Grashof's criterion (Patel & Sobh eqs 6-7, via :func:`worker.common.grashof.
four_bar_check`) splits four-bar chains by s + l against p + q (shortest, longest, the
other two): Grashof (<), non-Grashof (>) and change point (=).  Barker (1985) refines
that by which link is the ground, the input, the coupler and the output:

====== ====== ============================== =====================================
class  code   name                           when
====== ====== ============================== =====================================
I-1    GCCC   Grashof double-crank           s + l < p + q, s is the ground
I-2    GCRR   Grashof crank-rocker           s is the input
I-3    GRCR   Grashof double-rocker          s is the coupler
I-4    GRRC   Grashof rocker-crank           s is the output
II-k   RRRk   non-Grashof triple-rocker      s + l > p + q, l is link k (as in I-k)
III-1  SCCC   change-point double-crank      s + l = p + q, s is the ground
III-2  SCRR   change-point crank-rocker      s is the input
III-3  SRCR   change-point double-rocker     s is the coupler
III-4  SRRC   change-point rocker-crank      s is the output
III-5  S2X    double change point            two pairs of equal links
III-6  S3X    triple change point            all four links equal
====== ====== ============================== =====================================

The letters C/R say whether the input, the coupler and the output turn fully (crank)
relative to the ground or rock.  The links are given in order round the loop; with
ground g, the input is link g+1, the coupler g+2 and the output g+3 (mod 4).

Which links turn fully relative to which follows from loop closure: take the pair
{i, x} and the other two links {y, z}; their relative angle can take every value, so a
full turn, iff L_i + L_x <= L_y + L_z and |L_i - L_x| >= |L_y - L_z| (for an adjacent or
an opposite pair alike: the relative angle sweeps the distance that {y, z} must span
between its extremes L_i + L_x and |L_i - L_x|).  In a Grashof chain these are exactly
the three pairs containing s; in a non-Grashof chain none; at a change point the pairs
containing s (through the flat configuration, where the chain may change branch), and
more when links are equal.  Equalities hold within :data:`CHANGE_POINT_RTOL` of the sum
of the lengths, so decimal inputs such as (0.1, 0.7, 0.3, 0.5) are change points.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from worker.common.grashof import FourBarCheck, four_bar_check
from worker.common.parameter_errors import bad_parameter

__all__ = [
    "BARKER_CLASSES",
    "CHANGE_POINT_RTOL",
    "ROLES",
    "BarkerClass",
    "FourBarClassification",
    "FourBarType",
    "GrashofType",
    "classify_four_bar",
    "four_bar_poses",
    "full_turn_pairs",
]

#: Sums of lengths equal within this fraction of the total count as equal.
CHANGE_POINT_RTOL = 1e-9
ROLES = ("ground", "input", "coupler", "output")

GrashofType = Literal["grashof", "non-grashof", "change-point"]
FourBarType = Literal[
    "crank-rocker", "double-crank", "double-rocker", "triple-rocker", "change-point"
]
BoolArray = NDArray[np.bool_]
FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class BarkerClass:
    """One of Barker's 14 classes: ``number`` ("I-2"), ``code`` ("GCRR"), ``name``."""

    number: str
    code: str
    name: str
    classification: FourBarType


def _barker_table() -> dict[str, BarkerClass]:
    rows = [
        ("I-1", "GCCC", "Grashof double-crank", "double-crank"),
        ("I-2", "GCRR", "Grashof crank-rocker", "crank-rocker"),
        ("I-3", "GRCR", "Grashof double-rocker", "double-rocker"),
        ("I-4", "GRRC", "Grashof rocker-crank", "crank-rocker"),
        ("II-1", "RRR1", "non-Grashof triple-rocker, longest link grounded", "triple-rocker"),
        ("II-2", "RRR2", "non-Grashof triple-rocker, longest link the input", "triple-rocker"),
        ("II-3", "RRR3", "non-Grashof triple-rocker, longest link the coupler", "triple-rocker"),
        ("II-4", "RRR4", "non-Grashof triple-rocker, longest link the output", "triple-rocker"),
        ("III-1", "SCCC", "change-point double-crank", "change-point"),
        ("III-2", "SCRR", "change-point crank-rocker", "change-point"),
        ("III-3", "SRCR", "change-point double-rocker", "change-point"),
        ("III-4", "SRRC", "change-point rocker-crank", "change-point"),
        ("III-5", "S2X", "double change point: two pairs of equal links", "change-point"),
        ("III-6", "S3X", "triple change point: four equal links", "change-point"),
    ]
    return {
        number: BarkerClass(number, code, name, kind)  # type: ignore[arg-type]
        for number, code, name, kind in rows
    }


#: Barker's classes by number ("I-1" ... "III-6").
BARKER_CLASSES = _barker_table()


@dataclass(frozen=True)
class FourBarClassification:
    """A four-bar chain with a chosen ground, classified.

    ``full_turns`` (4, 4): ``[i, j]`` is True iff link j turns fully relative to link i
    (symmetric, False on the diagonal); ``roles[i]`` is link i's role.
    """

    lengths: tuple[float, float, float, float]
    ground: int
    roles: tuple[str, str, str, str]
    check: FourBarCheck
    grashof: GrashofType
    barker: BarkerClass
    full_turns: BoolArray

    @property
    def classification(self) -> FourBarType:
        return self.barker.classification

    def motion(self, link: int) -> Literal["crank", "rocker", "ground"]:
        """How ``link`` moves relative to the ground: 'crank' turns fully, 'rocker' not."""
        if link == self.ground:
            return "ground"
        return "crank" if bool(self.full_turns[self.ground, link]) else "rocker"


def full_turn_pairs(lengths: ArrayLike, rtol: float = CHANGE_POINT_RTOL) -> BoolArray:
    """Which links of four-bar chains turn fully relative to which.

    ``lengths`` (..., 4) in order round the loop -> (..., 4, 4) booleans, ``[..., i, j]``
    True iff L_i + L_j <= L_y + L_z and |L_i - L_j| >= |L_y - L_z| for the other two
    links y, z (equalities within ``rtol`` times the sum of the lengths).
    """
    arr = np.asarray(lengths, dtype=np.float64)
    if arr.shape[-1:] != (4,) or not np.all(np.isfinite(arr)) or not np.all(arr > 0):
        raise bad_parameter(
            "lengths", "full_turn_pairs", "finite positive lengths of shape (..., 4)", lengths
        )
    tol = rtol * arr.sum(axis=-1)
    result = np.zeros((*arr.shape[:-1], 4, 4), dtype=bool)
    for i in range(4):
        for j in range(i + 1, 4):
            y, z = (k for k in range(4) if k not in (i, j))
            li, lj, ly, lz = arr[..., i], arr[..., j], arr[..., y], arr[..., z]
            full = (li + lj <= ly + lz + tol) & (np.abs(li - lj) >= np.abs(ly - lz) - tol)
            result[..., i, j] = result[..., j, i] = full
    return result


def _close(a: float, b: float, tol: float) -> bool:
    return abs(a - b) <= tol


def classify_four_bar(lengths: Sequence[float], ground: int) -> FourBarClassification:
    """Grashof type, Barker class and full-turn pairs of one four-bar chain.

    lengths: four finite positive lengths in order round the loop; ground: the index
    (0-3) of the fixed link.
    """
    function = "classify_four_bar"
    try:
        values = tuple(float(v) for v in lengths)
    except (TypeError, ValueError):
        values = ()
    if len(values) != 4 or not all(math.isfinite(v) and v > 0 for v in values):
        raise bad_parameter("lengths", function, "four finite positive lengths", lengths)
    if not (isinstance(ground, int) and 0 <= ground <= 3):
        raise bad_parameter("ground", function, "a link index 0, 1, 2 or 3", ground)
    names = ("0", "1", "2", "3")
    check = four_bar_check(values, names)
    tol = CHANGE_POINT_RTOL * math.fsum(values)
    if _close(check.s_plus_l, check.p_plus_q, tol):
        grashof: GrashofType = "change-point"
        barker = _change_point_class(values, ground, int(check.shortest), tol)
    elif check.s_plus_l < check.p_plus_q:
        grashof = "grashof"
        barker = BARKER_CLASSES[f"I-{(int(check.shortest) - ground) % 4 + 1}"]
    else:
        grashof = "non-grashof"
        barker = BARKER_CLASSES[f"II-{(int(check.longest) - ground) % 4 + 1}"]
    roles = tuple(ROLES[(i - ground) % 4] for i in range(4))
    return FourBarClassification(
        lengths=(values[0], values[1], values[2], values[3]),
        ground=ground,
        roles=(roles[0], roles[1], roles[2], roles[3]),
        check=check,
        grashof=grashof,
        barker=barker,
        full_turns=full_turn_pairs(values),
    )


def _change_point_class(
    values: tuple[float, ...], ground: int, shortest: int, tol: float
) -> BarkerClass:
    ordered = sorted(values)
    if _close(ordered[0], ordered[3], tol):
        return BARKER_CLASSES["III-6"]
    if _close(ordered[0], ordered[1], tol) and _close(ordered[2], ordered[3], tol):
        return BARKER_CLASSES["III-5"]
    return BARKER_CLASSES[f"III-{(shortest - ground) % 4 + 1}"]


def four_bar_poses(lengths: Sequence[float], ground: int, input_angles: ArrayLike) -> FloatArray:
    """Joint positions as the input turns, on both assembly branches.

    Link k runs from joint J_k to J_{k+1} (mod 4).  The ground runs from the input pivot
    J_{g+1} = (0, 0) to the output pivot J_g = (L_g, 0); the input link makes the angle
    theta with the ground, counter-clockwise.  ``input_angles`` (k,) radians ->
    (2, k, 4, 2): branch (+1, -1: the output joint J_{g+3} left or right of the line
    from J_{g+2} to J_g), sample, joint J_0..J_3, (x, y); NaN where the loop cannot
    close at that input angle.
    """
    values = np.asarray(lengths, dtype=np.float64)
    if values.shape != (4,) or not np.all(np.isfinite(values)) or not np.all(values > 0):
        raise bad_parameter("lengths", "four_bar_poses", "four finite positive lengths", lengths)
    if not (isinstance(ground, int) and 0 <= ground <= 3):
        raise bad_parameter("ground", "four_bar_poses", "a link index 0, 1, 2 or 3", ground)
    theta = np.asarray(input_angles, dtype=np.float64).reshape(-1)
    g, i, c, o = ground, (ground + 1) % 4, (ground + 2) % 4, (ground + 3) % 4
    pivot_out = np.array([values[g], 0.0])
    tip = values[i] * np.stack([np.cos(theta), np.sin(theta)], axis=-1)  # J_{g+2}, (k, 2)
    diagonal = pivot_out - tip
    d = np.hypot(diagonal[:, 0], diagonal[:, 1])
    # The output joint J_{g+3} is L_c from the input tip and L_o from the output pivot.
    with np.errstate(invalid="ignore", divide="ignore"):
        a = (values[c] ** 2 - values[o] ** 2 + d**2) / (2.0 * d)
        h = np.sqrt(values[c] ** 2 - a**2)
        unit = diagonal / d[:, None]
    normal = np.stack([-unit[:, 1], unit[:, 0]], axis=-1)
    poses = np.full((2, theta.size, 4, 2), np.nan)
    for branch, sign in enumerate((1.0, -1.0)):
        joint = tip + a[:, None] * unit + sign * h[:, None] * normal
        poses[branch, :, i] = 0.0
        poses[branch, :, g] = pivot_out
        poses[branch, :, c] = tip
        poses[branch, :, o] = joint
        poses[branch, ~np.isfinite(joint).all(axis=-1)] = np.nan
    return poses
