"""Grashof type, Barker's classes and fully turning pairs, against an independent simulator."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from worker.common.grashof import end_effector_fully_rotatable
from worker.families.chains.kinematics.fourbar import (
    BARKER_CLASSES,
    ROLES,
    classify_four_bar,
    four_bar_poses,
    full_turn_pairs,
)
from worker.families.chains.kinematics.fourbar_simulation import drive_closes, simulated_full_turns


def placed(values: dict[str, float], at: dict[str, int]) -> list[float]:
    lengths = [0.0] * 4
    for key, index in at.items():
        lengths[index] = values[key]
    return lengths


GRASHOF = {"s": 2.0, "p": 5.0, "q": 6.0, "l": 7.0}  # 9 < 11
NON_GRASHOF = {"s": 2.0, "p": 4.0, "q": 5.0, "l": 9.0}  # 11 > 9
CHANGE_POINT = {"s": 2.0, "p": 4.0, "q": 6.0, "l": 8.0}  # 10 = 10


@pytest.mark.parametrize("position", range(4))
@pytest.mark.parametrize("ground", range(4))
def test_barker_class_follows_the_shortest_or_longest_link(position: int, ground: int) -> None:
    others = [k for k in range(4) if k != position]
    for values, extreme, family, grashof in (
        (GRASHOF, "s", "I", "grashof"),
        (NON_GRASHOF, "l", "II", "non-grashof"),
        (CHANGE_POINT, "s", "III", "change-point"),
    ):
        rest = [key for key in ("s", "p", "q", "l") if key != extreme]
        lengths = placed(values, {extreme: position, **dict(zip(rest, others, strict=True))})
        result = classify_four_bar(lengths, ground)
        offset = (position - ground) % 4 + 1
        assert result.grashof == grashof
        assert result.barker == BARKER_CLASSES[f"{family}-{offset}"]


@pytest.mark.parametrize(
    ("lengths", "ground", "number", "code", "classification"),
    [
        ((30, 17, 18, 25), 0, "II-1", "RRR1", "triple-rocker"),  # the paper's Fig 3
        ((18, 10, 17, 15), 0, "I-2", "GCRR", "crank-rocker"),  # Fig 2e
        ((18, 10, 17, 15), 1, "I-1", "GCCC", "double-crank"),
        ((18, 10, 17, 15), 3, "I-3", "GRCR", "double-rocker"),
        ((18, 10, 17, 15), 2, "I-4", "GRRC", "crank-rocker"),
        ((15, 14, 8, 12), 3, "I-4", "GRRC", "crank-rocker"),  # Patel & Sobh Ex 1, d = 12
        ((15, 14, 8, 7), 3, "III-1", "SCCC", "change-point"),  # d = 7: the disk's edge
        ((15, 14, 8, 5), 3, "I-1", "GCCC", "double-crank"),
        ((15, 8, 14, 12), 3, "I-3", "GRCR", "double-rocker"),  # Case 2: l2 shortest
        ((15, 14, 8, 8.5), 3, "II-2", "RRR2", "triple-rocker"),  # in the gap (7, 9)
        ((20, 10, 20, 10), 0, "III-5", "S2X", "change-point"),  # Fig 2b
        ((20, 20, 10, 10), 2, "III-5", "S2X", "change-point"),  # Fig 2c
        ((15, 15, 15, 15), 1, "III-6", "S3X", "change-point"),  # Fig 2a
        ((0.1, 0.7, 0.3, 0.5), 0, "III-1", "SCCC", "change-point"),  # within rounding
    ],
)
def test_classifications(lengths, ground, number, code, classification) -> None:
    result = classify_four_bar(lengths, ground)
    assert (result.barker.number, result.barker.code) == (number, code)
    assert result.classification == classification


def test_roles_go_round_the_loop_from_the_ground() -> None:
    assert classify_four_bar((1, 2, 3, 4), 2).roles == ("coupler", "output", "ground", "input")
    assert ROLES == ("ground", "input", "coupler", "output")


@pytest.mark.parametrize("ground", range(4))
@pytest.mark.parametrize("values", [GRASHOF, NON_GRASHOF, CHANGE_POINT])
def test_barker_letters_are_the_motions_relative_to_the_ground(values, ground) -> None:
    for order in itertools.permutations(("s", "p", "q", "l")):
        lengths = [values[key] for key in order]
        result = classify_four_bar(lengths, ground)
        letters = "".join(
            "C" if result.motion((ground + k) % 4) == "crank" else "R" for k in (1, 2, 3)
        )
        code = result.barker.code
        assert letters == ("RRR" if code.startswith("RRR") else code[1:])


@pytest.mark.parametrize("values", [GRASHOF, CHANGE_POINT])
def test_the_shortest_link_turns_fully_relative_to_every_other(values) -> None:
    for order in itertools.permutations(("s", "p", "q", "l")):
        turns = full_turn_pairs([values[key] for key in order])
        s = order.index("s")
        expected = {frozenset((s, k)) for k in range(4) if k != s}
        found = {frozenset((i, j)) for i in range(4) for j in range(4) if turns[i, j]}
        assert found == expected


def test_non_grashof_chains_have_no_full_turns() -> None:
    assert not full_turn_pairs([30, 17, 18, 25]).any()


def test_equal_links_turn_fully_at_a_change_point() -> None:
    assert full_turn_pairs([15, 15, 15, 15]).sum() == 12
    parallelogram = full_turn_pairs([20, 10, 20, 10])
    assert parallelogram[0, 1] and parallelogram[1, 3] and not parallelogram[0, 2]


def test_full_turn_pairs_are_batched_and_symmetric() -> None:
    batch = np.array([[[30, 17, 18, 25], [18, 10, 17, 15]], [[1, 1, 1, 1], [5, 2, 2.5, 1]]])
    turns = full_turn_pairs(batch)
    assert turns.shape == (2, 2, 4, 4)
    assert (turns == np.swapaxes(turns, -1, -2)).all()
    assert not turns[..., range(4), range(4)].any()
    assert (turns[1, 0] == full_turn_pairs(batch[1, 0])).all()


@pytest.mark.parametrize(
    ("call", "parameter", "function"),
    [
        (lambda: classify_four_bar([1, 2, 3], 0), "lengths", "classify_four_bar"),
        (lambda: classify_four_bar([1, 2, 3, 0], 0), "lengths", "classify_four_bar"),
        (lambda: classify_four_bar([1, 2, 3, 4], 4), "ground", "classify_four_bar"),
        (lambda: full_turn_pairs([1, 2, 3]), "lengths", "full_turn_pairs"),
        (lambda: four_bar_poses([1, 2, 3, math.inf], 0, [0.0]), "lengths", "four_bar_poses"),
        (lambda: four_bar_poses([1, 2, 3, 4], -1, [0.0]), "ground", "four_bar_poses"),
    ],
)
def test_bad_parameters_name_the_parameter(call, parameter, function) -> None:
    with pytest.raises(ValueError, match=rf"The '{parameter}' parameter of {function} must be"):
        call()


# -- the independent simulator -----------------------------------------------------------

lengths_st = st.tuples(*[st.floats(0.5, 10.0)] * 4)


def away_from_change_points(lengths: tuple[float, ...], margin: float = 1e-3) -> bool:
    """Every split into two pairs has unequal sums (s + l = p + q is one of them)."""
    total = sum(lengths)
    a, b, c, d = lengths
    return all(abs(x) > margin * total for x in (a + b - c - d, a + c - b - d, a + d - b - c))


#: Away from change points, the motions of input, coupler and output relative to the
#: ground (C: turns fully, R: rocks) name the classification on their own.
CLASSIFICATION_OF_MOTIONS = {
    "CCC": "double-crank",
    "CRR": "crank-rocker",
    "RRC": "crank-rocker",
    "RCR": "double-rocker",
    "RRR": "triple-rocker",
}


@settings(max_examples=60, deadline=None)
@given(lengths_st, st.integers(0, 3))
def test_classification_agrees_with_the_simulator(lengths, ground) -> None:
    assume(away_from_change_points(lengths))
    result = classify_four_bar(lengths, ground)
    simulated = np.array(simulated_full_turns(lengths, steps=360))
    assert (simulated == result.full_turns).all()
    if result.grashof == "grashof":
        s = int(result.check.shortest)
        assert simulated[s].sum() == 3 and simulated.sum() == 6
    else:
        assert not simulated.any()
    # Barker's letters and the classification, read off the simulated motions alone
    motions = "".join("C" if simulated[ground, (ground + k) % 4] else "R" for k in (1, 2, 3))
    code = result.barker.code
    assert motions == ("RRR" if code.startswith("RRR") else code[1:])
    assert result.classification == CLASSIFICATION_OF_MOTIONS[motions]


@pytest.mark.parametrize(
    "lengths", [(15, 15, 15, 15), (20, 10, 20, 10), (10, 10, 20, 20), (15, 14, 8, 7)]
)
def test_simulator_agrees_at_exact_change_points_with_whole_lengths(lengths) -> None:
    assert (np.array(simulated_full_turns(lengths, steps=360)) == full_turn_pairs(lengths)).all()


def test_simulator_drives_a_crank_and_stops_a_rocker() -> None:
    assert drive_closes([18, 10, 17, 15], 0, 1)  # the crank of Fig 2e
    assert not drive_closes([18, 10, 17, 15], 0, 3)  # its rocker


@settings(max_examples=100, deadline=None)
@given(st.tuples(*[st.floats(0.2, 5.0)] * 3), st.floats(0.05, 1.0))
def test_end_effector_pair_matches_the_virtual_four_bar(links, fraction) -> None:
    distance = fraction * sum(links)
    assume(away_from_change_points((*links, distance)))
    turns = full_turn_pairs([*links, distance])
    assert bool(turns[2, 3]) == end_effector_fully_rotatable(links, distance)


# -- poses ------------------------------------------------------------------------------


@pytest.mark.parametrize("ground", range(4))
def test_poses_close_the_loop(ground: int) -> None:
    lengths = (18.0, 10.0, 17.0, 15.0)
    poses = four_bar_poses(lengths, ground, np.linspace(0, 2 * np.pi, 73))
    assert poses.shape == (2, 73, 4, 2)
    closed = np.isfinite(poses[..., 0, 0])
    for k in range(4):
        sides = np.linalg.norm(poses[..., (k + 1) % 4, :] - poses[..., k, :], axis=-1)
        assert np.allclose(sides[closed], lengths[k])
    assert np.allclose(poses[closed][:, (ground + 1) % 4], 0.0)
    assert np.allclose(poses[closed][:, ground], (lengths[ground], 0.0))
    crank = classify_four_bar(lengths, ground).motion((ground + 1) % 4) == "crank"
    assert closed.all() == crank


def test_poses_are_nan_where_the_loop_cannot_close() -> None:
    poses = four_bar_poses((30, 17, 18, 25), 0, [0.0, np.pi])
    assert np.isfinite(poses[:, 0]).all() and np.isnan(poses[:, 1]).all()
