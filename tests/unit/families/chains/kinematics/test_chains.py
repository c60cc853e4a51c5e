"""P, Q, mobility and chain validation (docs/methods/chains.md): the paper's figures and
properties."""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Mapping
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from worker.families.chains import kinematics as c
from worker.families.chains.kinematics import validation

TERNARY_1 = {"a": 6.0, "b": 7.0, "c": 9.0}
TERNARY_4 = {"a": 6.0, "b": 8.0, "c": 9.0}
FIG_4A = c.Chain(
    "Fig 4a",
    {"1": TERNARY_1, "2": 11.0, "3": 10.0, "4": TERNARY_4, "5": 7.0, "6": 5.0, "7": 10.0},
    (
        ("1.a", "2", "3", "4.a"),
        ("1.b", "4.b", "5", "6", "7"),
        ("1.c", "2", "3", "4.c", "5", "6", "7"),
    ),
)
FIG_4B = c.Chain(
    "Fig 4b",
    {"1": TERNARY_1, "2": 11.0, "3": 10.0, "4": TERNARY_4, "5": 5.0, "6": 7.0, "7": 10.0},
    (
        ("1.a", "2", "3", "4.a", "5"),
        ("1.b", "5", "4.b", "6", "7"),
        ("1.c", "2", "3", "4.c", "6", "7"),
    ),
)


# -- the paper's numbers (docs/methods/chains.md, errata applied) -----------------------------


@pytest.mark.parametrize(
    ("lengths", "p"),
    [((15, 15, 15, 15), 50625.0), ((20, 10, 20, 10), 40000.0), ((20, 20, 10, 10), 40000.0),
     ((18, 15, 10, 17), 45900.0), ((18, 10, 17, 15), 45900.0)],
)  # fmt: skip
def test_fig_2_products(lengths: tuple[float, ...], p: float) -> None:
    assert c.length_product(lengths) == p


def test_fig_2d_deviations_and_q() -> None:
    # docs/methods/chains.md: 36, 120, 20, 136 (the paper's 126 is a typo); signs by eps_i's formula
    assert c.adjacent_products([18, 15, 10, 17]).tolist() == [270, 150, 170, 306]
    assert c.loop_deviations([18, 15, 10, 17]).tolist() == [36, 120, -20, -136]
    assert c.loop_q([18, 15, 10, 17]) == 36**2 + 120**2 + 20**2 + 136**2 == 34592


def test_fig_2e_deviations_and_q() -> None:
    # docs/methods/chains.md: 90, 10, 85, 15 (the paper's 75 is an "opposite product")
    assert c.loop_deviations([18, 10, 17, 15]).tolist() == [90, 10, -85, -15]
    assert c.loop_q([18, 10, 17, 15]) == 15650
    assert c.loop_q([18, 10, 17, 15]) < c.loop_q([18, 15, 10, 17])  # 2e more parallel


def test_parallel_quadrangles_have_zero_q() -> None:
    assert c.loop_q([15, 15, 15, 15]) == 0 == c.loop_q([20, 10, 20, 10])
    assert c.loop_q([20, 20, 10, 10]) == 100000  # 2b more parallel than 2c


def test_normalised_p_of_fig_2d_and_fig_3() -> None:
    p_2d = c.normalized_length_product([18, 15, 10, 17])
    p_3 = c.normalized_length_product([30, 17, 18, 25])
    assert p_2d == pytest.approx(15 * 10 * 17 * 18 / 60**4) == pytest.approx(0.0035417, abs=5e-8)
    assert p_3 == pytest.approx(0.0034979, abs=5e-8)  # not the paper's 0.0349
    assert p_2d > p_3


def test_fig_4a_loop_products_and_total_deviation() -> None:
    assert c.chain_problems(FIG_4A) == []
    s = c.chain_structure(FIG_4A)
    products = [c.adjacent_products(loop).tolist() for loop in s.loop_lengths]
    assert products == [
        [66, 110, 60, 36],
        [56, 56, 35, 50, 70],
        [99, 110, 90, 63, 35, 50, 90],
    ]
    assert c.loop_deviations(s.loop_lengths[0])[0] == -30  # |66 - 36| = 30, as in the paper
    shares = [float(c.loop_q(loop)) for loop in s.loop_lengths]
    assert shares == [5912, 1262, 3940]
    assert sum(shares) == 11114  # the paper prints 11214


def test_fig_4b_total_deviation() -> None:
    s = c.chain_structure(FIG_4B)
    products = [c.adjacent_products(loop).tolist() for loop in s.loop_lengths]
    assert products == [
        [66, 110, 60, 30, 30],
        [35, 40, 56, 70, 70],
        [99, 110, 90, 63, 70, 90],  # the paper prints "7 and 1 = 70"
    ]
    assert sum(float(c.loop_q(loop)) for loop in s.loop_lengths) == 10114  # printed 9538
    printed = [9, 11, 10, 9, 7, 10]  # loop 3 with 7 x 1 = 70 is not realisable; its Q:
    products_printed = np.array([99, 110, 90, 63, 70, 70], dtype=float)
    eps = np.roll(products_printed, 1) - products_printed
    assert 6632 + 1702 + float(np.sum(eps**2)) == 10474
    assert c.adjacent_products(printed).tolist() != products_printed.tolist()


def test_fig_4_structure_and_mobility() -> None:
    for chain in (FIG_4A, FIG_4B):
        s = c.chain_structure(chain)
        assert (len(s.links), len(s.joints), s.independent_loops, s.mobility) == (7, 8, 2, 2)
        assert len(s.dimensions) == 11
        assert sum(length for _, length in s.dimensions) == 88
    assert c.chain_structure(FIG_4A).joints[:4] == (("1", "2"), ("2", "3"), ("3", "4"), ("1", "4"))
    # the same dimensions: P ties exactly (products are taken over sorted lengths)
    dims_a = [v for _, v in c.chain_structure(FIG_4A).dimensions]
    dims_b = [v for _, v in c.chain_structure(FIG_4B).dimensions]
    assert c.normalized_length_product(dims_a) == c.normalized_length_product(dims_b)


@pytest.mark.parametrize(("links", "joints", "mobility"), [(4, 4, 1), (7, 8, 2), (6, 7, 1),
                                                           (3, 3, 0), (5, 5, 2)])  # fmt: skip
def test_grubler_mobility(links: int, joints: int, mobility: int) -> None:
    assert c.grubler_mobility(links, joints) == mobility


def test_single_loop_chain_names_links_in_order() -> None:
    chain = c.single_loop_chain("q", [18, 15, 10, 17])
    assert chain.links == {"1": 18.0, "2": 15.0, "3": 10.0, "4": 17.0}
    assert chain.loops == (("1", "2", "3", "4"),)
    assert c.chain_structure(chain).mobility == 1


# -- arrangements ----------------------------------------------------------------------


def test_fig_2d_arrangements_ranked_by_q() -> None:
    ranked = c.ranked_arrangements([18, 15, 10, 17])
    assert ranked.lengths.tolist() == [[18, 15, 17, 10], [18, 10, 15, 17], [18, 15, 10, 17]]
    assert ranked.q.tolist() == [15650, 30402, 34592]  # the first is Fig 2e, reflected
    assert ranked.ranks.tolist() == [1, 2, 3]


@pytest.mark.parametrize("n", [3, 4, 5, 6, 7, 8])
def test_distinct_lengths_give_half_factorial_arrangements(n: int) -> None:
    orders = c.distinct_cyclic_arrangements(np.arange(1.0, n + 1))
    assert orders.shape == (math.factorial(n - 1) // 2, n)
    assert (orders[:, 0] == 0).all()
    assert orders[0].tolist() == list(range(n))  # the given order first


@pytest.mark.parametrize(
    ("lengths", "count"), [([1, 1, 1, 1], 1), ([2, 1, 2, 1], 2), ([1, 1, 2, 3], 2),
                           ([1, 1, 1, 2, 2, 2], 3)],
)  # fmt: skip
def test_equal_lengths_are_not_counted_twice(lengths: list[float], count: int) -> None:
    assert len(c.distinct_cyclic_arrangements(lengths)) == count


def test_tie_ranks_share_a_rank_and_keep_order() -> None:
    order, ranks = c.tie_ranks([3.0, 1.0, 3.0, 0.5], descending=True)
    assert order.tolist() == [0, 2, 1, 3]
    assert ranks.tolist() == [1, 3, 1, 4]


# -- properties ------------------------------------------------------------------------

lengths_st = st.lists(st.floats(0.1, 100.0), min_size=3, max_size=8)
scale_st = st.floats(0.01, 100.0)


@settings(max_examples=100, deadline=None)
@given(lengths_st, scale_st)
def test_q_scales_as_the_fourth_power(lengths: list[float], s: float) -> None:
    loop = np.array(lengths)
    assert c.loop_q(s * loop) == pytest.approx(s**4 * c.loop_q(loop), rel=1e-9, abs=1e-9)


@settings(max_examples=100, deadline=None)
@given(lengths_st, scale_st)
def test_normalised_p_is_scale_free_and_p_scales_as_s_to_the_n(lengths: list[float], s: float):
    loop = np.array(lengths)
    assert c.normalized_length_product(s * loop) == pytest.approx(
        c.normalized_length_product(loop), rel=1e-9
    )
    assert c.length_product(s * loop) == pytest.approx(s ** len(loop) * c.length_product(loop),
                                                       rel=1e-9)  # fmt: skip


@settings(max_examples=100, deadline=None)
@given(lengths_st, st.integers(0, 7), st.booleans())
def test_q_is_the_same_for_rotations_and_reflections(lengths: list[float], k: int, flip: bool):
    loop = np.array(lengths)
    moved = np.roll(loop, k)
    if flip:
        moved = moved[::-1]
    assert c.loop_q(moved) == pytest.approx(c.loop_q(loop), rel=1e-12, abs=1e-9)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0.1, 100.0), min_size=4, max_size=6))
def test_normalised_p_is_largest_for_equal_lengths(lengths: list[float]) -> None:
    n = len(lengths)
    assert c.normalized_length_product(lengths) <= (1.0 / n) ** n * (1 + 1e-12)


def slow_q(loops: list[list[float]]) -> float:
    """eq 3 written out: per loop, eps_i = l_(i-1) l_i - l_i l_(i+1) (cyclic), squared."""
    total = 0.0
    for loop in loops:
        m = len(loop)
        for i in range(m):
            eps = loop[i - 1] * loop[i] - loop[i] * loop[(i + 1) % m]
            total += eps * eps
    return total


@settings(max_examples=100, deadline=None)
@given(lengths_st)
def test_q_matches_a_slow_implementation(lengths: list[float]) -> None:
    assert c.loop_q(lengths) == pytest.approx(slow_q([lengths]), rel=1e-12, abs=1e-9)
    total = math.fsum(lengths)
    slow_p = math.prod(v / total for v in lengths)
    assert c.normalized_length_product(lengths) == pytest.approx(slow_p, rel=1e-12)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.integers(1, 6), min_size=3, max_size=6))
def test_arrangements_cover_every_permutation(lengths: list[int]) -> None:
    # brute force over all n! orders: the same set of Q values, the same best Q
    every_q = {slow_q([list(map(float, order))]) for order in itertools.permutations(lengths)}
    ranked = c.ranked_arrangements(lengths)
    assert set(ranked.q.tolist()) == every_q
    assert ranked.q[0] == min(every_q)
    assert (np.diff(ranked.q) >= 0).all()


def scaled(chain: c.Chain, s: float) -> c.Chain:
    """Every binary link and every polygon side multiplied by s."""
    links: dict[str, c.LinkLengths] = {
        name: ({k: s * v for k, v in value.items()} if isinstance(value, Mapping) else s * value)
        for name, value in chain.links.items()
    }
    return c.Chain(chain.name, links, chain.loops)


@settings(max_examples=50, deadline=None)
@given(st.sampled_from([FIG_4A, FIG_4B]), scale_st)
def test_multi_loop_chains_scale_with_each_side_one_dimension(chain: c.Chain, s: float) -> None:
    base, big = c.chain_structure(chain), c.chain_structure(scaled(chain, s))
    q = sum(float(c.loop_q(loop)) for loop in base.loop_lengths)
    q_s = sum(float(c.loop_q(loop)) for loop in big.loop_lengths)
    assert q_s == pytest.approx(s**4 * q, rel=1e-9)
    dims = [v for _, v in base.dimensions]
    dims_s = [v for _, v in big.dimensions]
    assert c.normalized_length_product(dims_s) == pytest.approx(
        c.normalized_length_product(dims), rel=1e-9
    )
    # 11 dimensions (5 binary links, 3 + 3 polygon sides), so P grows as s^11
    assert c.length_product(dims_s) == pytest.approx(s**11 * c.length_product(dims), rel=1e-9)


def test_fig_4_normalised_p_counts_every_polygon_side() -> None:
    dims = [v for _, v in c.chain_structure(FIG_4A).dimensions]
    assert sorted(dims) == sorted([6, 7, 9, 11, 10, 6, 8, 9, 7, 5, 10])
    assert c.length_product(dims) == 6286896000
    assert c.normalized_length_product(dims) == pytest.approx(6286896000 / 88**11, rel=1e-12)
    assert c.normalized_length_product(dims) == pytest.approx(2.5652e-12, abs=5e-17)


def test_batched_shapes() -> None:
    loops = np.arange(1.0, 25.0).reshape(2, 3, 4)
    assert c.loop_q(loops).shape == (2, 3)
    assert c.loop_deviations(loops).shape == (2, 3, 4)
    assert c.normalized_length_product(loops).shape == (2, 3)
    assert c.loop_q(loops)[1, 2] == c.loop_q(loops[1, 2])


# -- validation ------------------------------------------------------------------------

LINKS_4A: dict[str, Any] = dict(FIG_4A.links)
LOOPS_4A = [list(loop) for loop in FIG_4A.loops]


def problems(links: dict[str, Any] | None = None, loops: list[list[str]] | None = None):
    chain = c.Chain("x", links or LINKS_4A, tuple(tuple(lp) for lp in (loops or LOOPS_4A)))
    return [(p.where, p.message) for p in c.chain_problems(chain)]


def with_loop(index: int, loop: list[str]) -> list[list[str]]:
    loops = [list(lp) for lp in LOOPS_4A]
    loops[index] = loop
    return loops


INVALID = [
    (with_loop(1, ["1.b", "4.b", "5", "6", "9"]), ("loops", 1), r"link '9' is not defined"),
    (with_loop(2, ["1", "2", "3", "4.c", "5", "6", "7"]), ("loops", 2),
     r"link '1' is polygonal \(sides 'a', 'b' and 'c'\): name one of its sides, e.g. '1.a'"),
    (with_loop(2, ["1.c", "2", "3", "4.d", "5", "6", "7"]), ("loops", 2),
     r"link '4' has no side 'd' \(its sides: 'a', 'b' and 'c'\)"),
    (with_loop(0, ["1.a", "2.x", "3", "4.a"]), ("loops", 0),
     r"link '2' is a binary link: write '2', not '2.x'"),
    (with_loop(2, ["1.c", "2", "3", "4.c", "5", "6", "7", "1.c"]), ("loops", 2),
     r"passes link '1' twice"),
    (with_loop(0, ["1.a", "2"]), ("loops", 0), r"has 2 side\(s\); a loop needs at least 3"),
    # an open loop: loop 1 skips link 7, so its last side never meets its first again
    (with_loop(1, ["1.b", "4.b", "5", "6"]), ("loops", 1),
     r"does not close with the other loops: its joint '1'-'6' borders no other loop"),
    (with_loop(2, ["1.a", "2", "3", "4.c", "5", "6", "7"]), ("links", "1", "sides", "a"),
     r"side 'a' of link '1' is in loops 0 and 2"),
    (LOOPS_4A[:2], ("links", "1", "sides", "c"), r"side 'c' of link '1' is in no loop"),
]  # fmt: skip


@pytest.mark.parametrize(("loops", "where", "message"), INVALID)
def test_invalid_loops_are_named(loops: list[list[str]], where: tuple[Any, ...], message: str):
    found = problems(loops=loops)
    assert found, "expected a problem"
    assert found[0][0] == where
    assert any(re.search(message, m) for _, m in found), found


def test_unused_link_and_unclosable_shapes() -> None:
    assert problems({**LINKS_4A, "8": 3.0}) == [(("links", "8"), "link '8' is in no loop")]
    ((where, message),) = problems({**LINKS_4A, "2": 40.0})
    assert where == ("loops", 0)
    assert message == ("the loop cannot close: side '2' (40) is not shorter than the sum of the "
                       "others (22)")  # fmt: skip
    ((where, message),) = problems({**LINKS_4A, "1": {"a": 6.0, "b": 7.0, "c": 20.0}})
    assert where == ("links", "1")
    assert "cannot be a triangle: side 'c' (20) is not shorter than the sum of the others (13)" in (
        message
    )


def test_loop_count_follows_euler() -> None:
    square = {"1": 1.0, "2": 1.0, "3": 1.0, "4": 1.0}
    found = problems(square, [["1", "2", "3", "4"], ["1", "2", "3", "4"]])
    assert found == [(("loops",), "4 links and 4 joints make a single loop: list it once (it is "
                                  "its own peripheral loop), not 2 loops")]  # fmt: skip


def test_disconnected_loops() -> None:
    six = {str(i): 1.0 for i in range(1, 7)}
    found = problems(six, [["1", "2", "3"], ["4", "5", "6"]])
    assert found == [(("loops",), "the loops do not join the links into one chain: '4', '5' and "
                                  "'6' are not connected to link '1'")]  # fmt: skip


def test_polygon_sides_must_meet_at_corners() -> None:
    # A safeguard behind the joint and Euler checks: a quaternary link whose four sides
    # pair up as two 2-cycles (a, b between A and B; c, d between C and D) is no polygon.
    links = {"Q": {"a": 1.0, "b": 1.0, "c": 1.0, "d": 1.0}, "A": 1.0, "B": 1.0, "C": 1.0,
             "D": 1.0}  # fmt: skip
    loops = (("Q.a", "B", "A"), ("Q.b", "A", "B"), ("Q.c", "D", "C"), ("Q.d", "C", "D"))
    chain = c.Chain("split", links, loops)
    message = validation._corner_problem(chain, "Q", links["Q"], ["A", "B", "C", "D"])
    assert message is not None and message.startswith("the sides of link 'Q' do not meet")
    assert validation._corner_problem(FIG_4A, "1", TERNARY_1, ["2", "4", "7"]) is None
    binary = validation._corner_problem(FIG_4A, "2", 11.0, ["1", "3", "4"])
    assert binary is not None and "a binary link has 2 joints" in binary
    # through the public entry the same description fails Euler's count first
    assert [p.where for p in c.chain_problems(chain)] == [("loops",)]


def test_valid_single_loop_has_no_problems() -> None:
    assert c.chain_problems(c.single_loop_chain("q", [30, 17, 18, 25])) == []
    (where, message), = [(p.where, p.message) for p in
                         c.chain_problems(c.single_loop_chain("q", [30, 1, 1, 1]))]  # fmt: skip
    assert where == ("loops", 0) and "cannot close" in message
