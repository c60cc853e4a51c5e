"""Planar kinematic chains as plain data, and the parallelism measures P and Q.

docs/methods/chains.md states the method, cites the paper
cleanly and is followed where the two differ.

A :class:`Chain` is links and loops.  A link is binary (one length) or polygonal (one
length per side: a ternary link is a triangle with three sides, a quaternary link a
quadrilateral, ...).  A loop is the cyclic list of link sides met going round it:
``"2"`` for binary link 2, ``"1.a"`` for side a of link 1.  Consecutive entries are
joined by a revolute joint, and so are the last and the first.  A chain lists every
independent inner loop and, last, the peripheral loop; a single-loop chain lists its
one loop once (there the inner and the peripheral loop coincide).

Measures (lengths in any one unit; batched over leading axes):

* P = product of every distinct dimension (eq 1), each binary link and each side of a
  polygonal link counting once; normalised P uses l_i / sum(l), which is scale-free.
  Larger P: more uniform rigidity.
* in each loop the deviation of side i is eps_i = l_{i-1} l_i - l_i l_{i+1}, the
  difference of the two adjacent-side products containing it (cyclic); Q = sum of
  eps^2 over every side of every loop (eq 3).  Smaller Q: more parallel; Q scales as s^4.
* mobility by Grübler-Kutzbach for revolute joints: M = 3 (n - 1) - 2 j.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "Chain",
    "ChainProblem",
    "ChainStructure",
    "RankedArrangements",
    "adjacent_products",
    "chain_problems",
    "chain_structure",
    "distinct_cyclic_arrangements",
    "grubler_mobility",
    "length_product",
    "loop_deviations",
    "loop_q",
    "normalized_length_product",
    "ranked_arrangements",
    "single_loop_chain",
    "split_side",
    "tie_ranks",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
#: A link: a binary link's length, or a polygonal link's side lengths by side name.
LinkLengths = float | Mapping[str, float]
#: Relative tolerance under which two values of P or Q count as tied.
TIE_RTOL = 1e-12


@dataclass(frozen=True)
class Chain:
    """A chain description (see the module docstring); ``links`` keeps its given order."""

    name: str
    links: Mapping[str, LinkLengths]
    loops: tuple[tuple[str, ...], ...]


@dataclass(frozen=True)
class ChainProblem:
    """Why a chain description is invalid.

    ``where`` is the path inside the chain: ``("loops", 2)``, ``("links", "1")``,
    ``("links", "1", "sides", "c")``, ``("loops",)`` or ``()`` for the whole chain.
    """

    where: tuple[str | int, ...]
    message: str


@dataclass(frozen=True)
class ChainStructure:
    """What a valid chain is made of.

    ``dimensions``: every distinct side (binary link ``"2"``, polygon side ``"1.a"``)
    with its length, links in the given order; ``loop_lengths[k]`` (m_k,) are the side
    lengths of loop k in its order; ``joints`` the linked pairs, in first-met order.
    """

    links: tuple[str, ...]
    joints: tuple[tuple[str, str], ...]
    loops: tuple[tuple[str, ...], ...]
    loop_lengths: tuple[FloatArray, ...]
    dimensions: tuple[tuple[str, float], ...]
    independent_loops: int
    mobility: int


def single_loop_chain(name: str, lengths: Sequence[float]) -> Chain:
    """A single loop of binary links named "1", "2", ... in the given order."""
    names = tuple(str(i + 1) for i in range(len(lengths)))
    return Chain(name, dict(zip(names, (float(v) for v in lengths), strict=True)), (names,))


def split_side(side: str) -> tuple[str, str | None]:
    """``"1.a"`` -> ``("1", "a")``; ``"2"`` -> ``("2", None)``."""
    link, dot, name = side.partition(".")
    return link, (name if dot else None)


# -- measures ------------------------------------------------------------------------


def length_product(lengths: ArrayLike) -> FloatArray:
    """P = l_1 l_2 ... l_n (eq 1); ``lengths`` (..., n) -> (...)."""
    # Sorted first, so that the same lengths in any order give bit-identical products.
    arr = np.sort(np.asarray(lengths, dtype=np.float64), axis=-1)
    return np.asarray(np.prod(arr, axis=-1), dtype=np.float64)


def normalized_length_product(lengths: ArrayLike) -> FloatArray:
    """P of l_i / sum(l) (the paper's normalisation); (..., n) -> (...), scale-free."""
    arr = np.sort(np.asarray(lengths, dtype=np.float64), axis=-1)
    return np.asarray(np.prod(arr / arr.sum(axis=-1, keepdims=True), axis=-1), dtype=np.float64)


def adjacent_products(loop: ArrayLike) -> FloatArray:
    """Products l_i l_{i+1} of adjacent sides round a loop (cyclic); (..., m) -> (..., m)."""
    arr = np.asarray(loop, dtype=np.float64)
    return arr * np.roll(arr, -1, axis=-1)


def loop_deviations(loop: ArrayLike) -> FloatArray:
    """eps_i = l_{i-1} l_i - l_i l_{i+1} for every side of a loop; (..., m) -> (..., m)."""
    products = adjacent_products(loop)
    return np.roll(products, 1, axis=-1) - products


def loop_q(loop: ArrayLike) -> FloatArray:
    """Sum of eps_i^2 over one loop's sides (its share of eq 3); (..., m) -> (...)."""
    return np.asarray(np.sum(loop_deviations(loop) ** 2, axis=-1), dtype=np.float64)


def grubler_mobility(links: int, joints: int) -> int:
    """Degrees of freedom of a planar chain with revolute joints: 3 (n - 1) - 2 j."""
    return 3 * (links - 1) - 2 * joints


def tie_ranks(values: ArrayLike, *, descending: bool) -> tuple[IntArray, IntArray]:
    """``(order, ranks)``: indices best first and 1-based competition ranks (1, 2, 2, 4).

    Values within :data:`TIE_RTOL` of the previous one share its rank; the sort is
    stable, so tied entries keep their given order.  ``values`` (k,).
    """
    arr = np.asarray(values, dtype=np.float64)
    order = np.argsort(-arr if descending else arr, kind="stable")
    ranks = np.empty(arr.size, dtype=np.int64)
    for position, index in enumerate(order):
        previous = arr[order[position - 1]] if position else math.nan
        tied = position and math.isclose(arr[index], previous, rel_tol=TIE_RTOL, abs_tol=0.0)
        ranks[index] = ranks[order[position - 1]] if tied else position + 1
    return order.astype(np.int64), ranks


# -- cyclic arrangements of a single loop --------------------------------------------


@dataclass(frozen=True)
class RankedArrangements:
    """Distinct cyclic arrangements, most parallel first.

    ``orders`` (k, n): indices into the given lengths, each starting with index 0;
    ``lengths`` (k, n); ``q`` (k,); ``ranks`` (k,) competition ranks by Q.
    """

    orders: IntArray
    lengths: FloatArray
    q: FloatArray
    ranks: IntArray


def distinct_cyclic_arrangements(lengths: ArrayLike) -> IntArray:
    """Every distinct way to arrange ``lengths`` (n,) round one loop, as index orders (k, n).

    Rotations and reflections of a loop are the same chain, and so are orders that
    differ only by swapping equal lengths: n distinct lengths give (n - 1)!/2
    arrangements (n >= 3).  Each starts with index 0; the given order comes first.
    Enumerates (n - 1)! orders: meant for short loops.
    """
    arr = np.asarray(lengths, dtype=np.float64)
    n = arr.size
    seen: set[tuple[float, ...]] = set()
    kept: list[tuple[int, ...]] = []
    for rest in itertools.permutations(range(1, n)):
        order = (0, *rest)
        key = _cyclic_key(arr[list(order)].tolist())
        if key not in seen:
            seen.add(key)
            kept.append(order)
    return np.asarray(kept, dtype=np.int64).reshape(len(kept), n)


def _cyclic_key(values: list[float]) -> tuple[float, ...]:
    """The smallest of a cycle's rotations and reflections: equal for equivalent loops."""
    n = len(values)
    forms = (tuple(seq[i:] + seq[:i]) for seq in (values, values[::-1]) for i in range(n))
    return min(forms)


def ranked_arrangements(lengths: ArrayLike) -> RankedArrangements:
    """Every distinct cyclic arrangement of ``lengths`` (n,), ranked by Q (smallest first)."""
    arr = np.asarray(lengths, dtype=np.float64)
    orders = distinct_cyclic_arrangements(arr)
    arranged = arr[orders]
    q = loop_q(arranged)
    order, ranks = tie_ranks(q, descending=False)
    return RankedArrangements(orders[order], arranged[order], q[order], ranks[order])


# -- structure and validation --------------------------------------------------------


def _link_of(side: str) -> str:
    return split_side(side)[0]


def _side_length(chain: Chain, side: str) -> float:
    link, name = split_side(side)
    value = chain.links[link]
    if isinstance(value, Mapping):
        return float(value[name or ""])
    return float(value)


def _joints(loops: Iterable[Sequence[str]]) -> dict[frozenset[str], list[int]]:
    """Each joint (a pair of links consecutive in a loop) -> the loops it borders."""
    joints: dict[frozenset[str], list[int]] = {}
    for index, loop in enumerate(loops):
        links = [_link_of(side) for side in loop]
        for a, b in zip(links, links[1:] + links[:1], strict=True):
            joints.setdefault(frozenset((a, b)), []).append(index)
    return joints


def chain_structure(chain: Chain) -> ChainStructure:
    """Links, joints, loop lengths, dimensions and mobility of a VALID chain.

    Check :func:`chain_problems` first; this trusts the description.
    """
    joints = _joints(chain.loops)
    n, j = len(chain.links), len(joints)
    dimensions: list[tuple[str, float]] = []
    for link, value in chain.links.items():
        if isinstance(value, Mapping):
            dimensions += [(f"{link}.{side}", float(v)) for side, v in value.items()]
        else:
            dimensions.append((link, float(value)))
    ordered_joints = []
    for pair in joints:
        a, b = sorted(pair, key=list(chain.links).index)
        ordered_joints.append((a, b))
    return ChainStructure(
        links=tuple(chain.links),
        joints=tuple(ordered_joints),
        loops=chain.loops,
        loop_lengths=tuple(
            np.array([_side_length(chain, s) for s in loop], dtype=np.float64)
            for loop in chain.loops
        ),
        dimensions=tuple(dimensions),
        independent_loops=j - n + 1,
        mobility=grubler_mobility(n, j),
    )


def chain_problems(chain: Chain) -> list[ChainProblem]:
    """Everything wrong with a chain description, stage by stage; [] if it is valid.

    Stages (a later stage runs only when the earlier ones pass, so one mistake is
    reported once): names (every loop side names a defined link or side, loops of at
    least 3 links, no link twice in a loop); use (every binary link and every side in
    a loop, a side in one loop, a binary link in at most two); structure (connected,
    the number of loops Euler's formula asks for, every joint bordering two loops,
    binary links with two joints, polygon sides meeting at its corners); geometry
    (every polygonal link and every loop can close: each side shorter than the sum of
    the others).
    """
    for stage in (_name_problems, _use_problems, _structure_problems, _geometry_problems):
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
            link = _link_of(side)
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
    joints = _joints(chain.loops)
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
                ends[name] = (_link_of(loop[position - 1]), _link_of(after))
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
        problem = _closure_problem(loop, [_side_length(chain, side) for side in loop])
        if problem is not None:
            problems.append(ChainProblem(("loops", index), f"the loop cannot close: {problem}"))
    return problems
