"""Planar kinematic chains as plain data, and the parallelism measures P and Q.

The front of the chains' kinematics: import names from here.  The work is done in
:mod:`.chain` (the data and its structure), :mod:`.validation` (what is wrong with a
chain) and :mod:`.measures` (P, Q and the ranked arrangements); the four-bar's
Grashof classification and motion are in :mod:`.fourbar` and :mod:`.fourbar_simulation`.

docs/methods/chains.md states the method, cites the paper
cleanly and is followed where the two differ.

A :class:`Chain` is links and loops.  A link is binary (one length) or polygonal (one
length per side: a ternary link is a triangle with three sides, a quaternary link a
quadrilateral, ...).  A loop is the cyclic list of link sides met going round it:
``"2"`` for binary link 2, ``"1.a"`` for side a of link 1.  Consecutive entries are
joined by a revolute joint, and so are the last and the first.  A chain lists every
independent inner loop and, last, the peripheral loop; a single-loop chain lists its
one loop once (there the inner and the peripheral loop coincide).

Measures (lengths in any one unit; batched over leading axes):

* P = product of every distinct dimension (eq 1), each binary link and each side of a
  polygonal link counting once; normalised P uses l_i / sum(l), which is scale-free.
  Larger P: more uniform rigidity.
* in each loop the deviation of side i is eps_i = l_{i-1} l_i - l_i l_{i+1}, the
  difference of the two adjacent-side products containing it (cyclic); Q = sum of
  eps^2 over every side of every loop (eq 3).  Smaller Q: more parallel; Q scales as s^4.
* mobility by Grübler-Kutzbach for revolute joints: M = 3 (n - 1) - 2 j.
"""

from worker.families.chains.kinematics.chain import (
    Chain,
    ChainProblem,
    ChainStructure,
    LinkLengths,
    chain_structure,
    single_loop_chain,
    split_side,
)
from worker.families.chains.kinematics.measures import (
    TIE_RTOL,
    RankedArrangements,
    adjacent_products,
    distinct_cyclic_arrangements,
    grubler_mobility,
    length_product,
    loop_deviations,
    loop_q,
    normalized_length_product,
    ranked_arrangements,
    tie_ranks,
)
from worker.families.chains.kinematics.validation import chain_problems

__all__ = [
    "TIE_RTOL",
    "Chain",
    "ChainProblem",
    "ChainStructure",
    "LinkLengths",
    "RankedArrangements",
    "adjacent_products",
    "chain_problems",
    "chain_structure",
    "distinct_cyclic_arrangements",
    "grubler_mobility",
    "length_product",
    "loop_deviations",
    "loop_q",
    "normalized_length_product",
    "ranked_arrangements",
    "single_loop_chain",
    "split_side",
    "tie_ranks",
]
