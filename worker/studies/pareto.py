"""The non-dominated set of a study's designs over two or more objectives.

Design a dominates design b when a is at least as good on every objective and better
on one; designs with equal objective values do not dominate each other (both stay).
Rows with a missing value (NaN: an infeasible design) never enter.  The designs are
taken in lexicographic order of their (minimised) objectives, where no later design can
dominate an earlier one, so the front only grows; each block of designs is checked
against the front so far and then within itself, vectorised.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["non_dominated"]

#: Designs checked together against the front (memory: block x front x objectives).
BLOCK = 512


def _dominated_by(front: NDArray[np.float64], rows: NDArray[np.float64]) -> NDArray[np.bool_]:
    """(m,) whether each of ``rows`` (m, k) is dominated by some row of ``front`` (f, k)."""
    if front.shape[0] == 0:
        return np.zeros(rows.shape[0], dtype=bool)
    no_worse = np.all(front[None, :, :] <= rows[:, None, :], axis=2)
    better = np.any(front[None, :, :] < rows[:, None, :], axis=2)
    return np.asarray(np.any(no_worse & better, axis=1), dtype=bool)


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
    minimised = table[candidates] * signs
    order = np.lexsort(minimised.T[::-1])
    sorted_rows, sorted_ids = minimised[order], candidates[order]
    front_rows = np.empty((0, table.shape[1]))
    kept: list[NDArray[np.intp]] = []
    for start in range(0, len(sorted_rows), BLOCK):
        rows, ids = sorted_rows[start : start + BLOCK], sorted_ids[start : start + BLOCK]
        survive = ~_dominated_by(front_rows, rows)
        rows, ids = rows[survive], ids[survive]
        within = _dominated_by(rows, rows)  # a row never dominates itself
        rows, ids = rows[~within], ids[~within]
        front_rows = np.concatenate([front_rows, rows])
        kept.append(ids)
    return np.sort(np.concatenate(kept)) if kept else np.zeros(0, dtype=np.intp)
