"""The parallelism measures P and Q of a chain's lengths, and the cyclic arrangements
of a single loop ranked by them (see :mod:`worker.families.chains.kinematics`)."""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "SUMS_RTOL",
    "TIE_RTOL",
    "RankedArrangements",
    "adjacent_products",
    "close_values",
    "distinct_cyclic_arrangements",
    "grubler_mobility",
    "length_product",
    "loop_deviations",
    "loop_q",
    "normalized_length_product",
    "ranked_arrangements",
    "tie_ranks",
    "tie_ranks_rows",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
#: Relative tolerance under which two values of P or Q count as tied.
TIE_RTOL = 1e-12
#: Chains' total lengths within this relative difference count as equal (then Q ranks
#: them as it is; otherwise normalised Q does).
SUMS_RTOL = 1e-9


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


def close_values(a: FloatArray, b: FloatArray, rel_tol: float) -> NDArray[np.bool_]:
    """:func:`math.isclose` (``abs_tol`` 0) elementwise, exactly as CPython decides it."""
    diff = np.abs(b - a)
    with np.errstate(invalid="ignore"):
        near = (diff <= np.abs(rel_tol * b)) | (diff <= np.abs(rel_tol * a))
    finite = np.isfinite(a) & np.isfinite(b)
    return np.asarray((a == b) | (near & finite))


def tie_ranks_rows(values: ArrayLike, *, descending: bool) -> tuple[IntArray, IntArray]:
    """:func:`tie_ranks` of every row of ``values`` (m, k) at once: ``(order, ranks)``,
    each (m, k)."""
    arr = np.asarray(values, dtype=np.float64)
    order = np.argsort(-arr if descending else arr, axis=-1, kind="stable")
    ranked = np.take_along_axis(arr, order, axis=-1)
    tied = np.zeros(arr.shape, dtype=bool)
    tied[:, 1:] = close_values(ranked[:, 1:], ranked[:, :-1], TIE_RTOL)
    positions = np.broadcast_to(np.arange(1, arr.shape[-1] + 1), arr.shape)
    by_position = np.maximum.accumulate(np.where(tied, 0, positions), axis=-1)
    ranks = np.empty_like(order)
    np.put_along_axis(ranks, order, by_position, axis=-1)
    return order.astype(np.int64), ranks.astype(np.int64)


def tie_ranks(values: ArrayLike, *, descending: bool) -> tuple[IntArray, IntArray]:
    """``(order, ranks)``: indices best first and 1-based competition ranks (1, 2, 2, 4).

    Values within :data:`TIE_RTOL` of the previous one share its rank; the sort is
    stable, so tied entries keep their given order.  ``values`` (k,).
    """
    order, ranks = tie_ranks_rows(np.asarray(values, dtype=np.float64)[None], descending=descending)
    return order[0], ranks[0]


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
