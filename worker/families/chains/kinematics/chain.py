"""A planar kinematic chain as plain data (links, loops, sides) and its structure
(links, joints, loops, mobility); see :mod:`worker.families.chains.kinematics`."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from worker.families.chains.kinematics.measures import grubler_mobility

__all__ = [
    "Chain",
    "ChainProblem",
    "ChainStructure",
    "LinkLengths",
    "chain_structure",
    "joints_of",
    "link_of",
    "side_length",
    "single_loop_chain",
    "split_side",
]

FloatArray = NDArray[np.float64]
#: A link: a binary link's length, or a polygonal link's side lengths by side name.
LinkLengths = float | Mapping[str, float]


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


# -- structure and validation --------------------------------------------------------


def link_of(side: str) -> str:
    return split_side(side)[0]


def side_length(chain: Chain, side: str) -> float:
    link, name = split_side(side)
    value = chain.links[link]
    if isinstance(value, Mapping):
        return float(value[name or ""])
    return float(value)


def joints_of(loops: Iterable[Sequence[str]]) -> dict[frozenset[str], list[int]]:
    """Each joint (a pair of links consecutive in a loop) -> the loops it borders."""
    joints: dict[frozenset[str], list[int]] = {}
    for index, loop in enumerate(loops):
        links = [link_of(side) for side in loop]
        for a, b in zip(links, links[1:] + links[:1], strict=True):
            joints.setdefault(frozenset((a, b)), []).append(index)
    return joints


def chain_structure(chain: Chain) -> ChainStructure:
    """Links, joints, loop lengths, dimensions and mobility of a VALID chain.

    Check :func:`chain_problems` first; this trusts the description.
    """
    joints = joints_of(chain.loops)
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
            np.array([side_length(chain, s) for s in loop], dtype=np.float64)
            for loop in chain.loops
        ),
        dimensions=tuple(dimensions),
        independent_loops=j - n + 1,
        mobility=grubler_mobility(n, j),
    )
