"""The non-dominated set of a study's designs over one, two or three objectives.

Design a dominates design b when a is at least as good on every objective and better
on one; designs with equal objective values do not dominate each other (both stay).
Rows with a missing value (NaN: an infeasible design) never enter.  The distinct rows
of (minimised) objectives are sorted lexicographically, so that no row can be
dominated by a later one and a row is dominated exactly when some earlier row is no
worse on the other objectives; the copies of a kept row are all kept.

* one objective: the rows of the least value;
* two: an earlier row is no worse on the second objective exactly when the running
  minimum of the second objective before a row does not exceed it, so one sort and one
  running minimum: O(n log n);
* three: a sweep in that order keeping the staircase of the kept rows' (f2, f3) (f2
  ascending, f3 falling), where a row is dominated exactly when the step at its f2 is
  no higher than its f3: a binary search per row and amortised O(1) updates, O(n log n)
  with a Python loop of one step per distinct row (about a second for 10^6 rows);
* more (never asked for by a study, at most three objectives): blocks of rows checked
  against the front so far and within themselves, vectorised, O(n |front|).
"""

from __future__ import annotations

from bisect import bisect_right

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["non_dominated"]

#: Rows checked together against the front with four or more objectives.
BLOCK = 512


def _dominated_by(front: NDArray[np.float64], rows: NDArray[np.float64]) -> NDArray[np.bool_]:
    """(m,) whether each of ``rows`` (m, k) is dominated by some row of ``front`` (f, k)."""
    if front.shape[0] == 0:
        return np.zeros(rows.shape[0], dtype=bool)
    no_worse = np.all(front[None, :, :] <= rows[:, None, :], axis=2)
    better = np.any(front[None, :, :] < rows[:, None, :], axis=2)
    return np.asarray(np.any(no_worse & better, axis=1), dtype=bool)


def _blocks(rows: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Kept rows of distinct lexicographically sorted ``rows``, block by block."""
    keep = np.zeros(len(rows), dtype=bool)
    front = np.empty((0, rows.shape[1]))
    for start in range(0, len(rows), BLOCK):
        block = rows[start : start + BLOCK]
        survive = ~_dominated_by(front, block)
        alive = np.flatnonzero(survive)
        survive[alive[_dominated_by(block[alive], block[alive])]] = False
        keep[start : start + len(block)] = survive
        front = np.concatenate([front, block[survive]])
    return keep


def _two(rows: NDArray[np.float64]) -> NDArray[np.bool_]:
    second = rows[:, 1]
    before = np.concatenate([[np.inf], np.minimum.accumulate(second)[:-1]])
    return np.asarray(second < before)


def _three(rows: NDArray[np.float64]) -> NDArray[np.bool_]:
    keep = np.zeros(len(rows), dtype=bool)
    steps_f2: list[float] = []  # ascending
    steps_f3: list[float] = []  # strictly falling
    for n, (f2, f3) in enumerate(rows[:, 1:].tolist()):
        j = bisect_right(steps_f2, f2)
        if j and steps_f3[j - 1] <= f3:
            continue
        keep[n] = True
        end = j
        while end < len(steps_f3) and steps_f3[end] >= f3:
            end += 1
        if j and steps_f2[j - 1] == f2:  # the step at the same f2 is higher: replaced
            j -= 1
        steps_f2[j:end] = [f2]
        steps_f3[j:end] = [f3]
    return keep


def non_dominated(values: ArrayLike, maximise: ArrayLike) -> NDArray[np.intp]:
    """Indices (ascending) of the non-dominated rows of ``values`` (n, k).

    ``maximise`` (k,): True where larger is better.  Rows with a NaN are left out.
    """
    table = np.asarray(values, dtype=np.float64)
    if table.ndim != 2:
        raise ValueError(f"values must be (n, k), not of shape {table.shape}")
    signs = np.where(np.asarray(maximise, dtype=bool), -1.0, 1.0)
    if signs.shape != (table.shape[1],):
        raise ValueError(f"maximise needs {table.shape[1]} flags, not {signs.shape}")
    candidates = np.flatnonzero(~np.isnan(table).any(axis=1))
    if candidates.size == 0 or table.shape[1] == 0:
        return candidates.astype(np.intp)
    minimised = table[candidates] * signs + 0.0  # + 0.0: -0.0 sorts as 0.0
    order = np.lexsort(minimised.T[::-1])
    ranked = minimised[order]
    fresh = np.concatenate([[True], np.any(ranked[1:] != ranked[:-1], axis=1)])
    distinct = ranked[fresh]
    k = table.shape[1]
    if k == 1:
        kept = np.arange(len(distinct)) == 0
    elif k == 2:
        kept = _two(distinct)
    elif k == 3:
        kept = _three(distinct)
    else:
        kept = _blocks(distinct)
    group = np.cumsum(fresh) - 1
    return np.sort(candidates[order[kept[group]]]).astype(np.intp)
