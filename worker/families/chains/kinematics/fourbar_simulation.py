"""A slow four-bar motion simulator, independent of Grashof's criterion.

For every ordered pair of links (i, j) it fixes link i, drives link j through a full
turn relative to it in small steps and, at every step, solves the loop-closure
equations for the other two links (the intersection of two circles), following the
assembly nearest the previous one.  Link j turns fully relative to link i iff every
step closes.  Plain loops with the math module only and no code shared with
:mod:`.fourbar` or :mod:`worker.common.grashof`: kept for the
property tests, which compare it with the closed-form classification.

Joints J0..J3: link k runs from J_k to J_{k+1} (indices mod 4).  Angles in radians.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

__all__ = ["drive_closes", "simulated_full_turns"]

Point = tuple[float, float]
#: Loop-closure residual (relative to the longest link) a solved assembly must meet.
CLOSURE_TOL = 1e-9


def _circle_intersections(c1: Point, r1: float, c2: Point, r2: float) -> list[Point]:
    """Points at distance r1 from c1 and r2 from c2 (none, one or two)."""
    dx, dy = c2[0] - c1[0], c2[1] - c1[1]
    d = math.hypot(dx, dy)
    if d == 0.0 or d > r1 + r2 or d < abs(r1 - r2):
        return []
    a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d)
    h = math.sqrt(max(r1 * r1 - a * a, 0.0))
    mx, my = c1[0] + a * dx / d, c1[1] + a * dy / d
    return [(mx - h * dy / d, my + h * dx / d), (mx + h * dy / d, my - h * dx / d)]


def _assemble(lengths: Sequence[float], i: int, j: int, angle: float) -> list[list[Point]]:
    """Every assembly [J0, J1, J2, J3] with link i from (0, 0) along +x and link j at
    ``angle`` relative to it (direction J_j -> J_{j+1})."""
    joints: list[Point | None] = [None] * 4
    joints[i] = (0.0, 0.0)
    joints[(i + 1) % 4] = (lengths[i], 0.0)
    direction = (math.cos(angle), math.sin(angle))
    if j == (i + 1) % 4:  # j starts where i ends: place its far end, solve the last joint
        start = joints[(i + 1) % 4]
        assert start is not None
        joints[(i + 2) % 4] = (
            start[0] + lengths[j] * direction[0],
            start[1] + lengths[j] * direction[1],
        )
        free, a, b = (i + 3) % 4, (i + 2) % 4, i
        centre_a, centre_b = joints[a], joints[b]
        assert centre_a is not None and centre_b is not None
        solutions = _circle_intersections(centre_a, lengths[a], centre_b, lengths[free])
        return [_with(joints, free, p) for p in solutions]
    if j == (i + 3) % 4:  # j ends where i starts: place its near end, solve the other
        joints[j] = (-lengths[j] * direction[0], -lengths[j] * direction[1])
        free = (i + 2) % 4
        near, far = joints[(i + 1) % 4], joints[j]
        assert near is not None and far is not None
        solutions = _circle_intersections(near, lengths[(i + 1) % 4], far, lengths[free])
        return [_with(joints, free, p) for p in solutions]
    # j opposite i: J_{j+1} = J_j + L_j e, so J_j lies on a circle about J_i - L_j e too
    start, end = joints[(i + 1) % 4], joints[i]
    assert start is not None and end is not None
    shifted = (end[0] - lengths[j] * direction[0], end[1] - lengths[j] * direction[1])
    solutions = _circle_intersections(start, lengths[(i + 1) % 4], shifted, lengths[(j + 1) % 4])
    assemblies = []
    for p in solutions:
        placed = _with(joints, j, p)
        assemblies.append(
            _with(
                placed,
                (j + 1) % 4,
                (p[0] + lengths[j] * direction[0], p[1] + lengths[j] * direction[1]),
            )
        )
    return assemblies


def _with(joints: Sequence[Point | None], index: int, point: Point) -> list[Point]:
    placed = list(joints)
    placed[index] = point
    return [p if p is not None else (math.nan, math.nan) for p in placed]


def _closes(lengths: Sequence[float], joints: Sequence[Point]) -> bool:
    scale = max(lengths)
    return all(
        abs(math.dist(joints[k], joints[(k + 1) % 4]) - lengths[k]) <= CLOSURE_TOL * scale
        for k in range(4)
    )


def drive_closes(lengths: Sequence[float], i: int, j: int, steps: int = 2048) -> bool:
    """Drive link j one full turn relative to link i in ``steps`` equal steps, following
    the nearest assembly; True iff the loop closes at every step."""
    previous: list[Point] | None = None
    for step in range(steps):
        assemblies = [
            a for a in _assemble(lengths, i, j, 2.0 * math.pi * step / steps) if _closes(lengths, a)
        ]
        if not assemblies:
            return False
        if previous is not None:
            last = previous
            assemblies.sort(
                key=lambda a: sum(math.dist(p, q) for p, q in zip(a, last, strict=True))
            )
        previous = assemblies[0]
    return True


def simulated_full_turns(lengths: Sequence[float], steps: int = 2048) -> list[list[bool]]:
    """4 x 4: ``[i][j]`` True iff link j turns fully relative to link i (by simulation)."""
    values = [float(v) for v in lengths]
    return [[i != j and drive_closes(values, i, j, steps) for j in range(4)] for i in range(4)]
