"""Chain measures and four-bar criteria of many designs at once (design studies).

Every function takes one row per design and gives the numbers the single-design jobs
give, to the bit: sums are exactly rounded as :func:`math.fsum` rounds them (one
design at a time), powers taken as Python takes them, comparisons made as
:func:`math.isclose` makes them; products and sorts are the batched functions of
:mod:`.measures` the jobs call.  Lengths in any one unit.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from worker.families.chains.kinematics.fourbar import CHANGE_POINT_RTOL
from worker.families.chains.kinematics.measures import (
    close_values,
    length_product,
    loop_q,
    normalized_length_product,
    tie_ranks_rows,
)

__all__ = [
    "ChainMeasures",
    "FourBarCriteria",
    "cannot_close",
    "chain_measures",
    "exact_sums",
    "four_bar_cannot_close",
    "four_bar_criteria",
    "ranks_of_chains",
    "spread_too_far",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.intp]
BoolArray = NDArray[np.bool_]


def exact_sums(values: FloatArray) -> FloatArray:
    """Each row's exactly rounded sum, (m, n) -> (m,), as :func:`math.fsum` gives it."""
    rows = np.asarray(values, dtype=np.float64)
    if rows.shape[1] == 1:
        return rows[:, 0].copy()
    return np.fromiter(map(math.fsum, rows.tolist()), dtype=np.float64, count=len(rows))


def _fourth_power(value: float) -> float:
    """x**4 as Python computes it, inf past the largest float (Python raises there)."""
    try:
        return value**4
    except OverflowError:  # a design out of range: refused by the kernel's checks
        return math.inf


def _fourth_powers(values: FloatArray) -> FloatArray:
    """x**4 as Python computes it (libm's pow; numpy's power may round differently)."""
    return np.fromiter(map(_fourth_power, values.tolist()), dtype=np.float64, count=values.size)


def spread_too_far(lengths: FloatArray, max_ratio: float) -> BoolArray:
    """(m,) whether the longest of each row of positive lengths (m, n) is more than
    ``max_ratio`` times the shortest (the check of ``length_ratio_problem``)."""
    with np.errstate(divide="ignore", invalid="ignore"):  # a zero is refused on its own
        return np.asarray(lengths.max(axis=1) / lengths.min(axis=1) > max_ratio)


def cannot_close(sides: FloatArray) -> BoolArray:
    """(m,) whether a loop or polygon of these sides (m, s) cannot close: its longest
    side (the first of the longest) is not shorter than the exact sum of the others."""
    longest = np.argmax(sides, axis=1)
    top = sides[np.arange(len(sides)), longest]
    others = sides.copy()
    others[np.arange(len(sides)), longest] = 0.0
    return np.asarray(top >= exact_sums(others))


class ChainMeasures(NamedTuple):
    """One chain's measures over m designs, each (m,) (loop_q (m, loops)): the sum of
    its dimensions, P and normalised P (eq 1), each loop's Q, Q (eq 3) and normalised Q."""

    total_length: FloatArray
    P: FloatArray
    P_normalized: FloatArray
    loop_q: FloatArray
    Q: FloatArray
    Q_normalized: FloatArray


def chain_measures(dimensions: FloatArray, loops: Sequence[IntArray]) -> ChainMeasures:
    """The measures of one chain from its dimensions (m, n), in the order of
    ``ChainStructure.dimensions``, and each loop's sides as indices into them."""
    total = exact_sums(dimensions)
    per_loop = np.stack([loop_q(dimensions[:, sides]) for sides in loops], axis=1)
    q = exact_sums(per_loop)
    return ChainMeasures(total, length_product(dimensions),
                         normalized_length_product(dimensions), per_loop, q,
                         q / _fourth_powers(total))  # fmt: skip


def ranks_of_chains(
    measures: Sequence[ChainMeasures], sums_rtol: float
) -> tuple[IntArray, IntArray, BoolArray]:
    """Each chain's rank by normalised P (largest first) and by Q (smallest first; by
    normalised Q where the chains' total lengths differ by more than ``sums_rtol``),
    each (m, chains), and whether they are of the same size (m,)."""
    totals = np.stack([c.total_length for c in measures], axis=1)
    same_size = np.asarray(close_values(totals, totals[:, :1], sums_rtol).all(axis=1))
    by_p = np.stack([c.P_normalized for c in measures], axis=1)
    q = np.stack([c.Q for c in measures], axis=1)
    q_normalized = np.stack([c.Q_normalized for c in measures], axis=1)
    by_q = np.where(same_size[:, None], q, q_normalized)
    _, ranks_p = tie_ranks_rows(by_p, descending=True)
    _, ranks_q = tie_ranks_rows(by_q, descending=False)
    return ranks_p, ranks_q, np.asarray(same_size)


class FourBarCriteria(NamedTuple):
    """Grashof's criterion of m four-bars, each (m,): the first shortest and longest
    link's index (s and l), s + l, p + q and the margin p + q - (s + l)."""

    shortest: IntArray
    longest: IntArray
    s_plus_l: FloatArray
    p_plus_q: FloatArray
    margin: FloatArray


def four_bar_criteria(lengths: FloatArray) -> FourBarCriteria:
    """Grashof's criterion (eq 6) of four-bars (m, 4), as
    :func:`worker.common.grashof.four_bar_check` finds it for one."""
    rows = np.arange(len(lengths))
    shortest = np.argmin(lengths, axis=1)
    longest = np.argmax(lengths, axis=1)
    longest = np.where(shortest == longest, (shortest + 1) % 4, longest)
    s_plus_l = lengths[rows, shortest] + lengths[rows, longest]
    p_plus_q = exact_sums(lengths) - s_plus_l
    return FourBarCriteria(shortest, longest, s_plus_l, p_plus_q, p_plus_q - s_plus_l)


def four_bar_cannot_close(lengths: FloatArray) -> tuple[BoolArray, IntArray]:
    """(m,) whether four-bars (m, 4) cannot close (the longest link, the first of them,
    not shorter than the others' exact sum less :data:`CHANGE_POINT_RTOL` of the total)
    and (m,) that link."""
    longest = np.argmax(lengths, axis=1)
    rows = np.arange(len(lengths))
    others = lengths.copy()
    others[rows, longest] = 0.0
    slack = CHANGE_POINT_RTOL * exact_sums(lengths)
    return np.asarray(lengths[rows, longest] >= exact_sums(others) - slack), longest
