"""Grashof's criterion (eqs 6-7) and the virtual four-bar of a 3R arm
(docs/methods/planar-serial.md)."""

from __future__ import annotations

import math

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from worker.common.grashof import FourBarCheck, end_effector_fully_rotatable, four_bar_check
from worker.families.planar_serial.kinematics import exact_orientation_dexterity

EX1_LINKS = (15.0, 14.0, 8.0)


def test_four_bar_check_reports_both_sides_of_eq6() -> None:
    check = four_bar_check([15.0, 14.0, 8.0, 7.0], ("l1", "l2", "l3", "d"))
    assert check == FourBarCheck(
        lengths=(15.0, 14.0, 8.0, 7.0),
        names=("l1", "l2", "l3", "d"),
        shortest="d",
        longest="l1",
        s_plus_l=22.0,
        p_plus_q=22.0,
        is_grashof=True,  # equality still satisfies s + l <= p + q
    )


@pytest.mark.parametrize(
    ("lengths", "is_grashof", "shortest", "longest"),
    [
        ((4.0, 2.0, 3.0, 1.0), True, "d", "a"),
        ((5.0, 2.0, 2.5, 1.0), False, "d", "a"),  # eq (7): 6 > 4.5
        ((2.0, 2.0, 2.0, 2.0), True, "a", "b"),  # all equal: a parallelogram-type chain
    ],
)
def test_four_bar_classification(lengths, is_grashof, shortest, longest) -> None:
    check = four_bar_check(lengths)
    assert (check.is_grashof, check.shortest, check.longest) == (is_grashof, shortest, longest)


@pytest.mark.parametrize(
    ("distance", "rotatable"),
    [(0.0, True), (7.0, True), (7.5, False), (8.0, False), (9.0, True), (15.0, True),
     (21.0, True), (21.5, False), (37.0, False)],
)  # fmt: skip
def test_example1_end_effector_rotatability_follows_the_bands(distance, rotatable) -> None:
    # docs/methods/planar-serial.md: full dexterity on [0, 7] ∪ [9, 21] for (15, 14, 8)
    assert end_effector_fully_rotatable(EX1_LINKS, distance) is rotatable


def test_example1_case2_shortest_link_is_l2_beyond_the_disk() -> None:
    # (15, 8, 14): for 8 < d the shortest link is l2, opposite the ground: a double rocker
    assert end_effector_fully_rotatable((15.0, 8.0, 14.0), 7.0)
    assert not end_effector_fully_rotatable((15.0, 8.0, 14.0), 12.0)
    assert four_bar_check((15.0, 8.0, 14.0, 12.0)).is_grashof


@pytest.mark.parametrize(
    ("call", "parameter", "function"),
    [
        (lambda: four_bar_check([1.0, 2.0, 3.0]), "lengths", "four_bar_check"),
        (lambda: four_bar_check([1.0, 2.0, 3.0, -1.0]), "lengths", "four_bar_check"),
        (lambda: four_bar_check([1.0, 2.0, 3.0, 4.0], ("a", "a", "b", "c")), "names",
         "four_bar_check"),
        (lambda: end_effector_fully_rotatable((1.0, 2.0), 1.0), "links",
         "end_effector_fully_rotatable"),
        (lambda: end_effector_fully_rotatable((1.0, 2.0, 3.0), -1.0), "distance",
         "end_effector_fully_rotatable"),
    ],
)  # fmt: skip
def test_bad_parameters_name_the_parameter(call, parameter, function) -> None:
    with pytest.raises(ValueError, match=rf"The '{parameter}' parameter of {function} must be"):
        call()


lengths = st.floats(0.2, 5.0)


@settings(max_examples=200, deadline=None)
@given(st.tuples(lengths, lengths, lengths), st.floats(0.0, 1.05))
def test_rotatable_iff_exact_dexterity_is_one(links, fraction) -> None:
    distance = fraction * sum(links)
    l1, l2, l3 = links
    # away from exact ties (band edges, and equal shortest links)
    edges = (l3 - abs(l1 - l2), l1 + l2 - l3, l3 + abs(l1 - l2))
    assume(all(abs(distance - edge) > 1e-9 for edge in edges))
    assume(len({round(v, 9) for v in (*links, distance)}) == 4)
    full = exact_orientation_dexterity(links, (distance * math.cos(1.0), distance * math.sin(1.0)))
    assert end_effector_fully_rotatable(links, distance) == (float(full) == 1.0)


@pytest.mark.parametrize(
    ("links", "distance"),
    [
        ((1.0, 2.0, 1.0), 2.0),
        ((1.0, 3.0, 1.0), 3.0),
        ((3.0, 1.0, 3.0), 1.0),
        ((1.0, 3.0, 3.0), 1.0),
    ],
)
def test_ties_for_the_shortest_link_agree_with_the_closed_form(links, distance) -> None:
    assert end_effector_fully_rotatable(links, distance)
    assert exact_orientation_dexterity(links, (distance, 0.0)) == 1.0
