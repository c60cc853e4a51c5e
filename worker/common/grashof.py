"""Grashof's criterion for four-bar chains and the virtual four-bar of a 3R arm.

Patel & Sobh (2012) §3, eqs (6)-(7): a four-bar chain with shortest link s, longest l
and the other two p, q has a fully rotatable link iff ``s + l <= p + q`` (Grashof); in a
Grashof chain the shortest link turns fully relative to every other link. §4 closes a
three-link arm (l1, l2, l3) with the virtual ground link d = |p| (base to end-effector);
docs/methods/planar-serial.md states when that makes the end-effector link turn fully.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from worker.common.parameter_errors import bad_parameter

__all__ = ["FourBarCheck", "end_effector_fully_rotatable", "four_bar_check"]


@dataclass(frozen=True)
class FourBarCheck:
    """Grashof's test (eq 6) on one four-bar chain.

    ``shortest``/``longest`` name the first link of minimal/maximal length;
    ``s_plus_l`` and ``p_plus_q`` are the two sides of eq (6).
    """

    lengths: tuple[float, float, float, float]
    names: tuple[str, str, str, str]
    shortest: str
    longest: str
    s_plus_l: float
    p_plus_q: float
    is_grashof: bool


def four_bar_check(
    lengths: Sequence[float], names: Sequence[str] = ("a", "b", "c", "d")
) -> FourBarCheck:
    """Grashof's criterion ``s + l <= p + q`` (eq 6; non-Grashof is eq 7).

    lengths: four finite non-negative link lengths (a zero-length virtual link is the
    arm's base point itself); names: four distinct labels in the same order.
    """
    function = "four_bar_check"
    try:
        values = tuple(float(v) for v in lengths)
    except (TypeError, ValueError):
        values = ()
    if len(values) != 4 or not all(math.isfinite(v) and v >= 0 for v in values):
        raise bad_parameter("lengths", function, "four finite non-negative lengths", lengths)
    labels = tuple(str(name) for name in names)
    if len(labels) != 4 or len(set(labels)) != 4:
        raise bad_parameter("names", function, "four distinct labels", names)
    shortest = min(range(4), key=values.__getitem__)
    longest = max(range(4), key=values.__getitem__)
    if shortest == longest:  # all equal: any two distinct links serve as s and l
        longest = (shortest + 1) % 4
    s_plus_l = values[shortest] + values[longest]
    p_plus_q = math.fsum(values) - s_plus_l
    return FourBarCheck(
        lengths=(values[0], values[1], values[2], values[3]),
        names=(labels[0], labels[1], labels[2], labels[3]),
        shortest=labels[shortest],
        longest=labels[longest],
        s_plus_l=s_plus_l,
        p_plus_q=p_plus_q,
        is_grashof=s_plus_l <= p_plus_q,
    )


def end_effector_fully_rotatable(links: ArrayLike, distance: float) -> bool:
    """Whether the end-effector link turns fully at distance d from the base.

    Builds the virtual four-bar (l1, l2, l3, d) of §4 and applies docs/methods/planar-serial.md: l3
    turns fully relative to the ground d iff the chain is Grashof (eq 6) and its shortest
    link is l3 or d (ties included; a shortest l1 makes l1 the crank, a shortest l2 a
    double rocker). This equals ``exact_orientation_dexterity(links, p) == 1`` for |p| = d.
    """
    function = "end_effector_fully_rotatable"
    try:
        arr = np.asarray(links, dtype=np.float64)
    except (TypeError, ValueError):
        arr = np.empty(0)
    if arr.shape != (3,) or not np.all(np.isfinite(arr)) or not np.all(arr > 0):
        raise bad_parameter("links", function, "three finite positive lengths (l1, l2, l3)", links)
    if not (isinstance(distance, numbers.Real) and math.isfinite(distance) and distance >= 0):
        raise bad_parameter("distance", function, "a finite non-negative distance", distance)
    l1, l2, l3 = (float(v) for v in arr)
    check = four_bar_check((l1, l2, l3, float(distance)), ("l1", "l2", "l3", "d"))
    return check.is_grashof and min(l3, float(distance)) <= min(l1, l2)
