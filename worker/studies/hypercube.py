"""A seeded Latin hypercube whose every block of designs is computed on its own.

Design i of ``count`` takes, on input j, the stratum ``pi_j(i)`` of the ``count``
strata of [0, 1) and a point inside it: ``x_ij = (pi_j(i) + u_ij) / count``.  Each
``pi_j`` is a permutation of 0..count-1 (so every stratum of every input holds exactly
one design, as McKay et al. ask): a keyed Feistel network on the smallest even number
of bits that covers ``count``, walked along its cycles until it lands below
``count``.  ``u_ij`` comes from a counter-based hash (SplitMix64's finaliser) of the
seed, the input and the design.  Nothing depends on designs outside the block, so a
chunk of a study draws only its own designs, in O(block) time and memory.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["latin_hypercube_block"]

U64 = NDArray[np.uint64]
_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_MIX_1 = np.uint64(0xBF58476D1CE4E5B9)
_MIX_2 = np.uint64(0x94D049BB133111EB)
#: Rounds of the Feistel network (four make a pseudo-random permutation; six to spare).
ROUNDS = 6


def _mix(x: U64) -> U64:
    """SplitMix64's finaliser: a bijection of 64-bit words that scrambles every bit."""
    z = x + _GOLDEN
    z = (z ^ (z >> np.uint64(30))) * _MIX_1
    z = (z ^ (z >> np.uint64(27))) * _MIX_2
    return np.asarray(z ^ (z >> np.uint64(31)), dtype=np.uint64)


def _key(seed: int, axis: int, purpose: int) -> int:
    word = _mix(np.array([(seed << 16) ^ (axis << 4) ^ purpose], dtype=np.uint64))
    return int(word[0])


def _permute(index: U64, count: int, key: int) -> U64:
    """``pi(index)``: a keyed permutation of 0..count-1 (Feistel, cycle-walking)."""
    half = max(1, (int(count - 1).bit_length() + 1) // 2)
    mask = np.uint64((1 << half) - 1)
    shift = np.uint64(half)
    out = index.copy()
    todo = np.ones(out.shape, dtype=bool)
    while todo.any():
        x = out[todo]
        left, right = x >> shift, x & mask
        for r in range(ROUNDS):
            round_key = np.uint64((key + r * int(_GOLDEN)) % 2**64)
            left, right = right, left ^ (_mix(right ^ round_key) & mask)
        out[todo] = (left << shift) | right
        todo &= out >= np.uint64(count)
    return out


def latin_hypercube_block(
    count: int, dimensions: int, seed: int, start: int, stop: int
) -> NDArray[np.float64]:
    """Designs ``start`` to ``stop`` (exclusive) of a ``count``-design Latin hypercube
    in [0, 1)^dimensions, seeded: (stop - start, dimensions)."""
    index = np.arange(start, stop, dtype=np.uint64)
    columns = []
    for axis in range(dimensions):
        stratum = _permute(index, count, _key(seed, axis, 1))
        jitter = (_mix(index ^ np.uint64(_key(seed, axis, 2))) >> np.uint64(11)).astype(np.float64)
        columns.append((stratum.astype(np.float64) + jitter * 2.0**-53) / count)
    return np.stack(columns, axis=1).reshape(stop - start, dimensions)
