"""Work limits of the kinematic-chain jobs, checked by the service before a job is queued.

``chain-parallelism`` costs, per chain, links x loops (the products and deviations
computed) plus, for a single loop of n links, its (n - 1)!/2 cyclic arrangements
ranked by Q.  Loops of at most 8 links keep that at most 2520 arrangements a chain.
``fourbar-grashof`` costs 1.
"""

from __future__ import annotations

import math

from worker.families.chains.fourbar_spec import FourBarGrashofSpec
from worker.families.chains.specs import (
    MAX_CHAINS,
    MAX_SINGLE_LOOP_LINKS,
    ChainParallelismSpec,
    LoopChain,
    MultiLoopChain,
)

__all__ = [
    "CHAIN_COST_LIMIT",
    "CHAIN_SYNC_COST_LIMIT",
    "FOURBAR_COST_LIMIT",
    "FOURBAR_SYNC_COST_LIMIT",
    "TIME_LIMIT_S",
    "arrangement_count",
    "chain_parallelism_cost",
    "fourbar_grashof_cost",
]


def arrangement_count(links: int) -> int:
    """Cyclic arrangements of n distinct lengths up to rotation and reflection: (n-1)!/2."""
    return max(1, math.factorial(links - 1) // 2)


#: The largest valid request: 20 single loops of 8 links (8 + 2520 each).
CHAIN_COST_LIMIT = MAX_CHAINS * (MAX_SINGLE_LOOP_LINKS + arrangement_count(MAX_SINGLE_LOOP_LINKS))
#: Answered synchronously up to this cost: two 8-link loops with their arrangements, or
#: any number of multi-loop chains (20 chains of 16 links x 16 loops cost 5120).
CHAIN_SYNC_COST_LIMIT = 6_000
FOURBAR_COST_LIMIT = 1
#: A four-bar is always quick enough to answer synchronously.
FOURBAR_SYNC_COST_LIMIT = 1
#: Wall-clock limit of one attempt, in seconds (plots included; typical runs take ~1 s).
TIME_LIMIT_S = 120.0


def _chain_cost(chain: LoopChain | MultiLoopChain) -> int:
    if isinstance(chain, LoopChain):
        links, loops = len(chain.lengths), 1
    else:
        links, loops = len(chain.links), len(chain.loops)
    return links * loops + (arrangement_count(links) if loops == 1 else 0)


def chain_parallelism_cost(spec: ChainParallelismSpec) -> int:
    """Sum over the chains of links x loops, plus (n - 1)!/2 for a single loop of n links."""
    return sum(_chain_cost(chain) for chain in spec.chains)


def fourbar_grashof_cost(spec: FourBarGrashofSpec) -> int:
    """1: a four-bar is classified in constant time."""
    return 1
