"""SPM design space (eqs 14-19) on the continuous workspace (docs/methods/spherical-parallel.md)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from worker.families.spherical_parallel.kinematics import (
    EDGE_TOLERANCE,
    SpmDesign,
    Workspace,
    design_margins,
    design_space,
    design_widths,
    is_feasible,
    link_angles,
)
from worker.families.spherical_parallel.kinematics.axis_reach import platform_axis

DEG = math.radians
CONE_120 = Workspace(DEG(60.0))
CONE_90_TORSION_30 = Workspace(DEG(45.0), (DEG(-15.0), DEG(15.0)), False)
FAST = settings(max_examples=40, deadline=None)


def test_beta_75_in_the_120_degree_cone() -> None:
    space = design_space(CONE_120, 0.0, np.radians([75.0]))
    assert space.f_min[0] == pytest.approx(math.cos(DEG(135)), abs=1e-5)
    assert space.f_max[0] == pytest.approx(math.cos(DEG(15)), abs=1e-5)
    assert (space.f_min[0], space.f_max[0]) == pytest.approx((-0.707, 0.966), abs=5e-4)
    assert np.degrees([space.d1[0], space.d2[0]]) == pytest.approx([45.0, 15.0], abs=1e-9)
    assert not space.degenerate[0] and not space.empty[0]
    corners = np.degrees(space.corners()[0])
    expected = np.array([[60, 105], [105, 60], [120, 75], [75, 120]])
    assert corners == pytest.approx(expected, abs=1e-9)
    for a1, a2 in [(70, 100), (60, 105), (100, 90)]:
        assert is_feasible(SpmDesign.from_degrees(a1, a2, 75), CONE_120)
    for a1, a2 in [(50, 100), (60, 110), (100, 100)]:  # |a1 - a2| > 45 or |a1 + a2 - 180| > 15
        assert not is_feasible(SpmDesign.from_degrees(a1, a2, 75), CONE_120)


def test_beta_60_degenerates_to_the_line_a1_plus_a2_180() -> None:
    space = design_space(CONE_120, 0.0, np.radians([55.0, 60.0, 90.0]))
    assert space.f_max[:2] == pytest.approx([1.0, 1.0], abs=1e-12)
    assert space.degenerate.tolist() == [True, True, False]
    assert not space.empty.any()
    assert np.degrees(space.d1[1]) == pytest.approx(60.0)
    assert is_feasible(SpmDesign.from_degrees(70, 110, 60), CONE_120)
    assert not is_feasible(SpmDesign.from_degrees(70, 111, 60), CONE_120)


def test_table_optima_sit_on_the_corner_and_need_the_edge_tolerance() -> None:
    for design, ws in [(SpmDesign.from_degrees(60, 90, 90), CONE_120),
                       (SpmDesign.from_degrees(45, 90, 90), Workspace(DEG(45)))]:  # fmt: skip
        margins = design_margins(design, ws)
        assert margins == pytest.approx((0.0, 0.0), abs=1e-12)
        assert is_feasible(design, ws)
    assert min(design_margins(SpmDesign.from_degrees(60, 90, 90), CONE_120)) < 0.0  # rounding
    assert not is_feasible(SpmDesign.from_degrees(60, 90, 90), CONE_120, tolerance=0.0)
    assert EDGE_TOLERANCE == 1e-9


def test_sample_only_optimum_is_infeasible_on_the_continuous_cone() -> None:
    margins = design_margins(SpmDesign.from_degrees(50, 120, 48), CONE_120)
    assert min(margins) < -DEG(10)


def test_identical_platforms_with_limited_torsion() -> None:
    d1, d2 = design_widths(CONE_90_TORSION_30, DEG(33.3), DEG(33.3))
    assert math.degrees(d1) == pytest.approx(180 - 33.3 - 33.3 - 45, abs=1e-9)
    assert math.degrees(d2) == pytest.approx(21.09398, abs=1e-4)
    assert is_feasible(SpmDesign.from_degrees(54.9, 115.4, 33.3, 33.3), CONE_90_TORSION_30)
    space = design_space(CONE_90_TORSION_30, DEG(33.3), np.radians([33.3, 48.1]))
    assert space.d1[0] == pytest.approx(d1) and space.d2[0] == pytest.approx(d2)


def test_link_angles_walk_the_rectangle() -> None:
    d1, d2 = DEG(45), DEG(15)
    assert np.degrees(link_angles(-1.0, -1.0, d1, d2)) == pytest.approx([60, 105])
    assert np.degrees(link_angles(0.0, 0.0, d1, d2)) == pytest.approx([90, 90])


@FAST
@given(st.floats(0.05, 1.5), st.floats(0.05, 3.1), st.floats(0.0, 3.1), st.floats(-3.0, 3.0))
def test_numeric_widths_match_the_full_turn_closed_form(
    tilt: float, beta: float, gamma: float, origin: float
) -> None:
    full = Workspace(tilt, (origin, origin + 2 * math.pi))
    almost = Workspace(tilt, (origin, origin + 2 * math.pi - 2e-9), False)
    assert design_widths(almost, beta, gamma) == pytest.approx(
        design_widths(full, beta, gamma), abs=1e-9
    )


@FAST
@given(st.floats(0.05, 1.5), st.floats(0.05, 3.1), st.floats(0.0, 3.1), st.floats(0.0, 5.0))
def test_numeric_widths_are_attained_and_beat_a_dense_grid(
    tilt: float, beta: float, gamma: float, span: float
) -> None:
    ws = Workspace(tilt, (-0.5 * span, 0.5 * span), False)
    d1, d2 = design_widths(ws, beta, gamma)
    axes = (np.linspace(0, 2 * np.pi, 181), np.linspace(0, tilt, 21),
            np.linspace(-0.5 * span, 0.5 * span, 21))  # fmt: skip
    v = platform_axis(np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1), beta)
    f = np.tensordot([0.0, -math.sin(gamma), math.cos(gamma)], v, axes=1)
    grid = (math.acos(min(1.0, -f.min())), math.acos(min(1.0, f.max())))
    assert d1 <= grid[0] + 1e-9 and d2 <= grid[1] + 1e-9
    assert d1 >= grid[0] - 0.05 and d2 >= grid[1] - 0.05


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: design_space(CONE_120, -0.1, [1.0]), r"The 'gamma' parameter of design_space"),
        (lambda: design_space(CONE_120, 0.0, [0.0]), r"The 'betas' parameter of design_space"),
        (lambda: design_space(CONE_120, 0.0, [[1.0]]), r"of shape \(k,\)"),
        (lambda: design_margins(SpmDesign(1, 1, 1), None), r"'ws' parameter of design_margins"),  # type: ignore[arg-type]
    ],
)  # fmt: skip
def test_bad_arguments(call: object, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        call()  # type: ignore[operator]
