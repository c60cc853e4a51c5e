"""The paper's worked examples (Patel & Sobh §5), as inputs ready to POST.

The numbers are the paper's, exactly as printed; what the paper then gets wrong about
them is listed in docs/methods/planar-serial.md and reported in the jobs' ``notes`` and
``paper_errata``.
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Any

from worker.processes import ProcessExample

__all__ = [
    "DESIGN_EXAMPLES",
    "DEXTERITY_MAP_EXAMPLES",
    "EXAMPLE_1_CUBIC",
    "EXAMPLE_1_DESIGN",
    "EXAMPLE_1_L3",
    "EXAMPLE_1_SWAPPED_DESIGN",
    "EXAMPLE_1_TASK_POINTS",
    "EXAMPLE_1_X_RANGE",
    "EXAMPLE_2_DESIGN",
    "EXAMPLE_2_L3",
    "EXAMPLE_2_TASK_POINTS",
    "PAPER_JOINT_LIMITS_DEG",
    "SYNTHESIS_EXAMPLES",
]

#: Example 1, eq (12): y = -0.2292 x^3 + 7.625 x^2 - 78.83 x + 252, from A (x = 14) to E (x = 8).
EXAMPLE_1_CUBIC = (-0.2292, 7.625, -78.83, 252.0)
EXAMPLE_1_X_RANGE = (14.0, 8.0)
EXAMPLE_1_TASK_POINTS = ((14.0, 14.0), (12.0, 8.0), (10.0, -3.0), (9.0, -7.0), (8.0, -8.0))
EXAMPLE_1_LABELS = ("A", "B", "C", "D", "E")
EXAMPLE_1_L3 = 8.0
#: The paper's design for Example 1 (from its rounded distances 10 and 20).
EXAMPLE_1_DESIGN = (15.0, 14.0, 8.0)
#: Example 1, Case 2: the same links with l2 and l3 swapped.
EXAMPLE_1_SWAPPED_DESIGN = (15.0, 8.0, 14.0)
#: Example 2: seven independent task points A..G.
EXAMPLE_2_TASK_POINTS = (
    (16.0, 19.0),
    (18.0, 0.0),
    (-8.0, -25.0),
    (-15.0, 11.0),
    (-10.0, 16.0),
    (20.0, -21.0),
    (-7.0, 27.0),
)
EXAMPLE_2_LABELS = ("A", "B", "C", "D", "E", "F", "G")
EXAMPLE_2_L3 = 15.0
#: The paper's design for Example 2 (eqs 10-11 with d_max = 29, l3 = 15).
EXAMPLE_2_DESIGN = (23.0, 22.0, 15.0)
#: Case 3 of both examples: th1, th2 in [-150, 150], th3 in [-175, 175] degrees.
PAPER_JOINT_LIMITS_DEG = ((-150.0, 150.0), (-150.0, 150.0), (-175.0, 175.0))

_EXAMPLE_1_TRAJECTORY: dict[str, Any] = {
    "polynomial": list(EXAMPLE_1_CUBIC),
    "x_start": EXAMPLE_1_X_RANGE[0],
    "x_end": EXAMPLE_1_X_RANGE[1],
    "samples": 200,
}


def _points(points: tuple[tuple[float, float], ...]) -> list[list[float]]:
    return [list(p) for p in points]


def _limits() -> list[list[float]]:
    return [list(pair) for pair in PAPER_JOINT_LIMITS_DEG]


_EXAMPLE_1_SYNTHESIS: dict[str, Any] = {
    "trajectory": _EXAMPLE_1_TRAJECTORY,
    "task_points": _points(EXAMPLE_1_TASK_POINTS),
    "task_labels": list(EXAMPLE_1_LABELS),
    "l3": EXAMPLE_1_L3,
    "joint_limits_deg": _limits(),
    "grid": {"points_per_axis": 201},
}

SYNTHESIS_EXAMPLES = (
    ProcessExample(
        title="Example 1: cubic trajectory A..E, distances rounded as in the paper",
        inputs=MappingProxyType({**_EXAMPLE_1_SYNTHESIS, "round_distances": True}),
        description="The paper's Example 1 (eq 12, l3 = 8, Cases 1-3). The exact range "
        "10.3923..19.7673 is rounded outward to 10..20, giving the paper's (15, 14, 8).",
    ),
    ProcessExample(
        title="Example 1 without rounding: the exact distance range",
        inputs=MappingProxyType({**_EXAMPLE_1_SYNTHESIS, "round_distances": False}),
        description="Eqs (10)-(11) from the exact d_min = 10.3923 and d_max = 19.7673: "
        "(14.8837, 13.8837, 8).",
    ),
    ProcessExample(
        title="Example 2: seven independent task points",
        inputs=MappingProxyType(
            {
                "task_points": _points(EXAMPLE_2_TASK_POINTS),
                "task_labels": list(EXAMPLE_2_LABELS),
                "l3": EXAMPLE_2_L3,
                "joint_limits_deg": _limits(),
                "grid": {"points_per_axis": 201},
            }
        ),
        description="The paper's Example 2 (l3 = 15): d_min = 18 (B), d_max = 29 (F), "
        "design (23, 22, 15); under the joint limits only F stays fully dexterous.",
    ),
)

_EXAMPLE_1_MAP: dict[str, Any] = {
    "links": list(EXAMPLE_1_DESIGN),
    "task_points": _points(EXAMPLE_1_TASK_POINTS),
    "task_labels": list(EXAMPLE_1_LABELS),
    "trajectory": _EXAMPLE_1_TRAJECTORY,
    "grid": {"points_per_axis": 201},
}

DEXTERITY_MAP_EXAMPLES = (
    ProcessExample(
        title="Example 1, Case 1: the design (15, 14, 8) with fully revolute joints",
        inputs=MappingProxyType(_EXAMPLE_1_MAP),
        description="Exact d_z (Figs 6-8): full dexterity on d <= 7 and 9 <= d <= 21; "
        "all five task points and the whole cubic trajectory have d_z = 1.",
    ),
    ProcessExample(
        title="Example 1, Case 3: the design (15, 14, 8) under joint limits",
        inputs=MappingProxyType({**_EXAMPLE_1_MAP, "joint_limits_deg": _limits()}),
        description="th1, th2 in [-150, 150] and th3 in [-175, 175] degrees (Fig 11), d_z "
        "exact by events (the default method); task points B..E lose full dexterity "
        "(E: d_z = 0.7273).",
    ),
    ProcessExample(
        title="Example 2, Case 1: the design (23, 22, 15) at its seven task points",
        inputs=MappingProxyType(
            {
                "links": list(EXAMPLE_2_DESIGN),
                "task_points": _points(EXAMPLE_2_TASK_POINTS),
                "task_labels": list(EXAMPLE_2_LABELS),
                "grid": {"points_per_axis": 101},
            }
        ),
        description="Exact d_z on a 101 x 101 grid: every task point A..G is fully "
        "dexterous with unlimited joints.  Small enough to answer synchronously "
        "(Prefer: wait=N).",
    ),
    ProcessExample(
        title="Example 1, Case 3 by orientation sampling (the reference method)",
        inputs=MappingProxyType(
            {
                **_EXAMPLE_1_MAP,
                "joint_limits_deg": _limits(),
                "method": "orientation-sampling",
                "orientation_step_deg": 1.0,
            }
        ),
        description="The same map with orientations sampled every 1 degree, as the "
        "paper does: map values come in steps of 1/360 (task points are refined by "
        "bisection); compare with the exact example above.",
    ),
)

_EXAMPLE_1_DESIGN: dict[str, Any] = {
    "trajectory": _EXAMPLE_1_TRAJECTORY,
    "task_points": _points(EXAMPLE_1_TASK_POINTS),
    "task_labels": list(EXAMPLE_1_LABELS),
    "joint_limits_deg": _limits(),
    "total_length_max": 37.0,
    "paper_l3": EXAMPLE_1_L3,
    "round_distances": True,
}
_EXAMPLE_2_DESIGN: dict[str, Any] = {
    "task_points": _points(EXAMPLE_2_TASK_POINTS),
    "task_labels": list(EXAMPLE_2_LABELS),
    "joint_limits_deg": _limits(),
    "total_length_max": 60.0,
    "paper_l3": EXAMPLE_2_L3,
}
#: Example 1 with the tool designed as well, each link at least 1 unit long.
_EXAMPLE_1_ALL_LINKS = [[1.0, 37.0], [1.0, 37.0], [1.0, 37.0]]

DESIGN_EXAMPLES = (
    ProcessExample(
        title="Example 1 under its joint limits, total length at most 37, l3 = 8 held",
        inputs=MappingProxyType(_EXAMPLE_1_DESIGN),
        description="The cubic trajectory and task points A..E with th1, th2 in [-150, 150] "
        "and th3 in [-175, 175] degrees, the tool held at the rule's l3 = 8 for 37 units (the "
        "default): the paper's rule gives (15, 14, 8) and a worst d_z of 0.727 (at E); the "
        "optimum (13.18, 13.18, 8) lifts it to 0.772.",
    ),
    ProcessExample(
        title="Example 1 with the tool designed too (every link at least 1)",
        inputs=MappingProxyType({**_EXAMPLE_1_DESIGN, "link_bounds": _EXAMPLE_1_ALL_LINKS}),
        description="link_bounds make l3 a design variable: the optimum (14.40, 6.44, 1) "
        "keeps every point fully dexterous with the shortest tool allowed, in 21.8 of the "
        "37 units.",
    ),
    ProcessExample(
        title="Example 1 with the base free in a 10 x 10 box (l3 = 8 held)",
        inputs=MappingProxyType({**_EXAMPLE_1_DESIGN, "base_box": [-5, 5, -5, 5]}),
        description="Moving the base as well: with l3 = 8 and total length 37 the task "
        "becomes fully dexterous everywhere.",
    ),
    ProcessExample(
        title="Example 2 under its joint limits, total length at most 60, l3 = 15 held",
        inputs=MappingProxyType(_EXAMPLE_2_DESIGN),
        description="Seven task points A..G, the tool held at the rule's l3 = 15 for 60 "
        "units: the rule's (23, 22, 15) leaves B at d_z = 0.777; the optimum "
        "(20.98, 20.98, 15) raises the worst point to 0.794.",
    ),
    ProcessExample(
        title="Shortest arm keeping Example 1's task points fully dexterous, l3 = 1",
        inputs=MappingProxyType(
            {
                "task_points": _points(EXAMPLE_1_TASK_POINTS),
                "task_labels": list(EXAMPLE_1_LABELS),
                "joint_limits_deg": _limits(),
                "objective": "min_length",
                "dz_target": 1.0,
                "total_length_max": 37.0,
                "l3": 1.0,
                "paper_l3": EXAMPLE_1_L3,
                "round_distances": True,
            }
        ),
        description="objective 'min_length' with a 1-unit tool held: the least "
        "l1 + l2 + l3 that keeps d_z = 1 at A..E under the joint limits, 21.83 units (the "
        "rule's 37 units do not).",
    ),
)
