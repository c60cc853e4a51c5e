"""The paper's worked examples as inputs ready to POST (docs/methods/chains.md).

Fig 2 (quadrangles with a sum of 60 cm), Fig 3 (30, 17, 18, 25) and Fig 4 (two
seven-link chains) of the parallelism paper (cited in docs/methods/chains.md).  The text
extraction has no figures, so the orderings are inferred from its numbers
(docs/methods/chains.md, "The paper's errata"): Fig 2d is (18, 15, 10, 17) and
Fig 2e (18, 10, 17, 15); Fig 4's side lengths are fixed by its product tables.  Fig 2b
and 2c are inferred: both have P = 20² x 10², and "2b is more parallel than 2c", so 2b
is the parallelogram (20, 10, 20, 10) and 2c the kite (20, 20, 10, 10).

The four-bar examples are the paper's quadrangles with a fixed link and Patel & Sobh's
virtual four-bar (l1, l2, l3, d) of Example 1 (docs/methods/planar-serial.md), grounded at d.
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Any

from worker.processes import ProcessExample

__all__ = [
    "CHAIN_PARALLELISM_EXAMPLES",
    "FIG_2",
    "FIG_3",
    "FIG_4A",
    "FIG_4B",
    "FOURBAR_GRASHOF_EXAMPLES",
]

#: Fig 2a-2e: quadrangles with link lengths summing to 60 cm, in order round the loop.
FIG_2: dict[str, tuple[float, ...]] = {
    "Fig 2a": (15.0, 15.0, 15.0, 15.0),
    "Fig 2b": (20.0, 10.0, 20.0, 10.0),
    "Fig 2c": (20.0, 20.0, 10.0, 10.0),
    "Fig 2d": (18.0, 15.0, 10.0, 17.0),
    "Fig 2e": (18.0, 10.0, 17.0, 15.0),
}
#: Fig 3: a = 30, b = 17, c = 18, d = 25 (sum 90 cm).
FIG_3 = (30.0, 17.0, 18.0, 25.0)

_TERNARY_1 = {"sides": {"a": 6.0, "b": 7.0, "c": 9.0}}
_TERNARY_4 = {"sides": {"a": 6.0, "b": 8.0, "c": 9.0}}
#: Fig 4a: ternary links 1 and 4 joined directly; loop 1 = 1-2-3-4, loop 2 = 1-4-5-6-7.
FIG_4A: dict[str, Any] = {
    "name": "Fig 4a",
    "links": {
        "1": _TERNARY_1,
        "2": 11.0,
        "3": 10.0,
        "4": _TERNARY_4,
        "5": 7.0,
        "6": 5.0,
        "7": 10.0,
    },
    "loops": [
        ["1.a", "2", "3", "4.a"],
        ["1.b", "4.b", "5", "6", "7"],
        ["1.c", "2", "3", "4.c", "5", "6", "7"],
    ],
}
#: Fig 4b: the same links, 5 and 6 swapped in length, link 5 between the ternaries.
FIG_4B: dict[str, Any] = {
    "name": "Fig 4b",
    "links": {
        "1": _TERNARY_1,
        "2": 11.0,
        "3": 10.0,
        "4": _TERNARY_4,
        "5": 5.0,
        "6": 7.0,
        "7": 10.0,
    },
    "loops": [
        ["1.a", "2", "3", "4.a", "5"],
        ["1.b", "5", "4.b", "6", "7"],
        ["1.c", "2", "3", "4.c", "6", "7"],
    ],
}


def _loop(name: str, lengths: tuple[float, ...]) -> dict[str, Any]:
    return {"name": name, "lengths": list(lengths)}


CHAIN_PARALLELISM_EXAMPLES = (
    ProcessExample(
        title="Fig 2: five quadrangles with a sum of 60 cm",
        inputs=MappingProxyType(
            {
                "chains": [_loop(name, lengths) for name, lengths in FIG_2.items()],
                "length_unit": "cm",
            }
        ),
        description="P = 50625 (2a), 40000 (2b, 2c), 45900 (2d, 2e): 2a is the most uniformly "
        "rigid. Q = 0 (2a, 2b), 100000 (2c), 34592 (2d), 15650 (2e): 2e is more parallel "
        "than 2d and 2b than 2c. Each quadrangle's three cyclic arrangements are ranked by Q.",
    ),
    ProcessExample(
        title="Fig 2d against Fig 3: normalised P",
        inputs=MappingProxyType(
            {
                "chains": [_loop("Fig 2d", FIG_2["Fig 2d"]), _loop("Fig 3", FIG_3)],
                "length_unit": "cm",
            }
        ),
        description="Sums 60 and 90 cm: normalised P = 0.0035417 (2d) > 0.0034979 (Fig 3; "
        "the paper prints 0.0349), so 2d's links are more uniformly rigid.",
    ),
    ProcessExample(
        title="Fig 4a against Fig 4b: seven-link chains with two ternary links",
        inputs=MappingProxyType({"chains": [FIG_4A, FIG_4B], "length_unit": "cm"}),
        description="Loops 1, 2 and the peripheral loop 3. Q = 5912 + 1262 + 3940 = 11114 "
        "(4a; the paper prints 11214) and 6632 + 1702 + 1780 = 10114 (4b; the paper prints "
        "9538): 4b is more parallel. Same links, so P ties. Mobility 2 by Grübler-Kutzbach "
        "(the paper says single-DOF).",
    ),
)

FOURBAR_GRASHOF_EXAMPLES = (
    ProcessExample(
        title="Fig 3 with link a grounded: a non-Grashof triple rocker",
        inputs=MappingProxyType({"lengths": list(FIG_3), "ground": 0, "length_unit": "cm"}),
        description="s + l = 17 + 30 = 47 > p + q = 43: no link turns fully (Barker II-1, "
        "RRR1: the longest link is the ground).",
    ),
    ProcessExample(
        title="Fig 2e with the 18 cm link grounded: a crank-rocker",
        inputs=MappingProxyType(
            {"lengths": list(FIG_2["Fig 2e"]), "ground": 0, "length_unit": "cm"}
        ),
        description="s + l = 10 + 18 = 28 < 32: Grashof; the shortest link (10) is the input "
        "and turns fully relative to every other link (Barker I-2, GCRR).",
    ),
    ProcessExample(
        title="Patel & Sobh Example 1 at d = 12: the end-effector turns fully",
        inputs=MappingProxyType({"lengths": [15.0, 14.0, 8.0, 12.0], "ground": 3}),
        description="The virtual four-bar (l1, l2, l3, d) of the design (15, 14, 8) grounded "
        "at d: Grashof with l3 shortest, so l3 turns fully relative to d (Barker I-4, GRRC) "
        "and d_z = 1 at d = 12.",
    ),
    ProcessExample(
        title="Patel & Sobh Example 1 at d = 7: a change point",
        inputs=MappingProxyType({"lengths": [15.0, 14.0, 8.0, 7.0], "ground": 3}),
        description="s + l = 7 + 15 = 22 = 14 + 8: the edge of the central fully dexterous "
        "disk d <= 7 (Barker III-1, SCCC).",
    ),
    ProcessExample(
        title="Fig 2b, the parallelogram (20, 10, 20, 10)",
        inputs=MappingProxyType(
            {"lengths": [20.0, 10.0, 20.0, 10.0], "ground": 0, "length_unit": "cm"}
        ),
        description="Two pairs of equal links: a double change point (Barker III-5, S2X).",
    ),
)
