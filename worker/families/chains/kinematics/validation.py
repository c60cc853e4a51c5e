"""What is wrong with a chain, every problem at once, each naming where it is (names,
link uses, structure, geometry); see :mod:`worker.families.chains.kinematics`."""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence

from worker.families.chains.kinematics.chain import (
    Chain,
    ChainProblem,
    LinkLengths,
    joints_of,
    link_of,
    side_length,
    split_side,
)

__all__ = ["chain_problems"]


def chain_problems(chain: Chain, *, geometry: bool = True) -> list[ChainProblem]:
    """Everything wrong with a chain description, stage by stage; [] if it is valid.

    Stages (a later stage runs only when the earlier ones pass, so one mistake is
    reported once): names (every loop side names a defined link or side, loops of at
    least 3 links, no link twice in a loop); use (every binary link and every side in
    a loop, a side in one loop, a binary link in at most two); structure (connected,
    the number of loops Euler's formula asks for, every joint bordering two loops,
    binary links with two joints, polygon sides meeting at its corners); geometry
    (every polygonal link and every loop can close: each side shorter than the sum of
    the others).  ``geometry=False`` leaves the last stage out (a design study's
    kernel checks it per design, from the lengths).
    """
    stages = [_name_problems, _use_problems, _structure_problems]
    for stage in (*stages, _geometry_problems) if geometry else stages:
        problems = stage(chain)
        if problems:
            return problems
    return []


def _listing(items: Iterable[object], quote: bool = False) -> str:
    """``[0, 2, 3]`` -> ``"0, 2 and 3"`` (quoted: ``"'a', 'b' and 'c'"``)."""
    words = [f"'{item}'" if quote else str(item) for item in items]
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " and " + words[-1]


def _side_name_problem(chain: Chain, side: str) -> str | None:
    link, name = split_side(side)
    if link not in chain.links:
        return f"link '{link}' is not defined"
    value = chain.links[link]
    if isinstance(value, Mapping):
        if name is None:
            return (
                f"link '{link}' is polygonal (sides {_listing(value, quote=True)}): name one "
                f"of its sides, e.g. '{link}.{next(iter(value))}'"
            )
        if name not in value:
            return f"link '{link}' has no side '{name}' (its sides: {_listing(value, quote=True)})"
    elif name is not None:
        return f"link '{link}' is a binary link: write '{link}', not '{side}'"
    return None


def _name_problems(chain: Chain) -> list[ChainProblem]:
    problems = []
    for index, loop in enumerate(chain.loops):
        where: tuple[str | int, ...] = ("loops", index)
        if len(loop) < 3:
            problems.append(
                ChainProblem(where, f"has {len(loop)} side(s); a loop needs at least 3 links")
            )
        met: dict[str, str] = {}
        for side in loop:
            problem = _side_name_problem(chain, side)
            link = link_of(side)
            if problem is not None:
                problems.append(ChainProblem(where, problem))
            elif link in met:
                problems.append(
                    ChainProblem(
                        where,
                        (
                            f"passes link '{link}' twice ('{met[link]}' and '{side}'); a loop "
                            "meets each link once and closes from its last side back to its "
                            "first"
                        ),
                    )
                )
            met.setdefault(link, side)
    return problems


def _use_problems(chain: Chain) -> list[ChainProblem]:
    uses: dict[str, list[int]] = {}
    for index, loop in enumerate(chain.loops):
        for side in loop:
            uses.setdefault(side, []).append(index)
    problems = []
    for link, value in chain.links.items():
        if isinstance(value, Mapping):
            for name in value:
                loops = uses.get(f"{link}.{name}", [])
                where: tuple[str | int, ...] = ("links", link, "sides", name)
                if not loops:
                    problems.append(
                        ChainProblem(
                            where,
                            (
                                f"side '{name}' of link '{link}' is in no loop; every side of a "
                                "polygonal link borders one loop"
                            ),
                        )
                    )
                elif len(loops) > 1:
                    problems.append(
                        ChainProblem(
                            where,
                            (
                                f"side '{name}' of link '{link}' is in loops {_listing(loops)}; a "
                                "side of a polygonal link borders exactly one loop"
                            ),
                        )
                    )
        else:
            loops = uses.get(link, [])
            if not loops:
                problems.append(ChainProblem(("links", link), f"link '{link}' is in no loop"))
            elif len(loops) > 2:
                problems.append(
                    ChainProblem(
                        ("links", link),
                        (
                            f"link '{link}' is in loops {_listing(loops)}; a binary link "
                            "borders at most two loops, one on each side"
                        ),
                    )
                )
    return problems


def _link_neighbours(chain: Chain, joints: Iterable[frozenset[str]]) -> dict[str, list[str]]:
    """Each link -> the links it is jointed to, in the chain's link order."""
    found: dict[str, set[str]] = {link: set() for link in chain.links}
    for pair in joints:
        a, b = tuple(pair)
        found[a].add(b)
        found[b].add(a)
    return {link: [other for other in chain.links if other in found[link]] for link in found}


def _unconnected(neighbours: Mapping[str, Sequence[str]]) -> list[str]:
    first = next(iter(neighbours))
    reached, frontier = {first}, [first]
    while frontier:
        for other in neighbours[frontier.pop()]:
            if other not in reached:
                reached.add(other)
                frontier.append(other)
    return [link for link in neighbours if link not in reached]


def _loop_count_message(links: int, joints: int, independent: int, given: int) -> str:
    if independent <= 1:
        return (
            f"{links} links and {joints} joints make a single loop: list it once (it is its "
            f"own peripheral loop), not {given} loops"
        )
    return (
        f"{links} links and {joints} joints make {independent} independent loops: list them "
        f"and, last, the peripheral loop ({independent + 1} loops), not {given}"
    )


def _structure_problems(chain: Chain) -> list[ChainProblem]:
    joints = joints_of(chain.loops)
    neighbours = _link_neighbours(chain, joints)
    missing = _unconnected(neighbours)
    if missing:
        verb = "is" if len(missing) == 1 else "are"
        return [
            ChainProblem(
                ("loops",),
                (
                    "the loops do not join the links into one chain: "
                    f"{_listing(missing, quote=True)} {verb} not connected to link "
                    f"'{next(iter(chain.links))}'"
                ),
            )
        ]
    problems = _border_problems(chain, joints) if len(chain.loops) > 1 else []
    if problems:
        return problems
    n, j = len(chain.links), len(joints)
    independent = j - n + 1
    if len(chain.loops) != (1 if independent <= 1 else independent + 1):
        return [ChainProblem(("loops",), _loop_count_message(n, j, independent, len(chain.loops)))]
    for link, value in chain.links.items():
        problem = _corner_problem(chain, link, value, neighbours[link])
        if problem is not None:
            problems.append(ChainProblem(("links", link), problem))
    return problems


def _border_problems(
    chain: Chain, joints: Mapping[frozenset[str], Sequence[int]]
) -> list[ChainProblem]:
    """In a multi-loop chain every joint borders two loops; name the loops left open."""
    order = list(chain.links)
    unmatched: dict[int, list[str]] = {}
    for pair, loops in joints.items():
        if len(loops) != 2:
            a, b = sorted(pair, key=order.index)
            where = "no other loop" if len(loops) == 1 else f"loops {_listing(loops)}"
            unmatched.setdefault(loops[0], []).append(f"'{a}'-'{b}' borders {where}")
    return [
        ChainProblem(
            ("loops", index),
            (
                f"does not close with the other loops: its joint {'; joint '.join(found)}; every "
                "joint borders exactly two loops (two inner loops, or an inner loop and the "
                "peripheral loop, listed last)"
            ),
        )
        for index, found in sorted(unmatched.items())
    ]


def _corner_problem(
    chain: Chain, link: str, value: LinkLengths, neighbours: Sequence[str]
) -> str | None:
    """A binary link has two joints; a polygon's sides meet at its corners (joints)."""
    corners = len(value) if isinstance(value, Mapping) else 2
    if len(neighbours) != corners:
        kind = f"a link with {corners} sides" if isinstance(value, Mapping) else "a binary link"
        return (
            f"link '{link}' is joined to {len(neighbours)} link(s) "
            f"({_listing(neighbours, quote=True)}); {kind} has {corners} joints"
        )
    if not isinstance(value, Mapping):
        return None
    ends: dict[str, tuple[str, str]] = {}
    for loop in chain.loops:
        for position, side in enumerate(loop):
            owner, name = split_side(side)
            if owner == link and name is not None:
                after = loop[(position + 1) % len(loop)]
                ends[name] = (link_of(loop[position - 1]), link_of(after))
    # Walk round the polygon from one corner: every side must be met on the way.
    corner, remaining = ends[next(iter(value))][0], dict(ends)
    while (step := next((n for n, pair in remaining.items() if corner in pair), None)) is not None:
        a, b = remaining.pop(step)
        corner = b if corner == a else a
    if not remaining:
        return None
    described = ", ".join(f"{n} between '{a}' and '{b}'" for n, (a, b) in ends.items())
    return (
        f"the sides of link '{link}' do not meet at its corners ({described}); each joint "
        "of a polygonal link is a corner shared by two consecutive sides"
    )


def _closure_problem(names: Sequence[str], lengths: Sequence[float]) -> str | None:
    longest = max(range(len(lengths)), key=lengths.__getitem__)
    rest = math.fsum(v for i, v in enumerate(lengths) if i != longest)
    if lengths[longest] >= rest:
        return (
            f"side '{names[longest]}' ({lengths[longest]:g}) is not shorter than the sum of "
            f"the others ({rest:g})"
        )
    return None


def _polygon_name(sides: int) -> str:
    return {3: "triangle", 4: "quadrilateral"}.get(sides, f"polygon of {sides} sides")


def _geometry_problems(chain: Chain) -> list[ChainProblem]:
    problems = []
    for link, value in chain.links.items():
        if isinstance(value, Mapping):
            problem = _closure_problem(list(value), [float(v) for v in value.values()])
            if problem is not None:
                problems.append(
                    ChainProblem(
                        ("links", link),
                        (f"link '{link}' cannot be a {_polygon_name(len(value))}: {problem}"),
                    )
                )
    for index, loop in enumerate(chain.loops):
        problem = _closure_problem(loop, [side_length(chain, side) for side in loop])
        if problem is not None:
            problems.append(ChainProblem(("loops", index), f"the loop cannot close: {problem}"))
    return problems
