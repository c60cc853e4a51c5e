"""The study kernels of ``chain-parallelism`` and ``fourbar-grashof``
(:mod:`worker.study_kernels`): many sets of lengths at once, the chains' structure and
the four-bar's ground fixed.

``chain-parallelism`` varies any length (``chains[i].lengths[j]``, a binary link's
``chains[i].links.<name>``, a side's ``chains[i].links.<name>.sides.<side>``) and
covers each chain's P, Q, their normalised forms, each loop's Q, the total length, its
ranks by P and by Q and its structure (links, joints, loops, mobility); the cyclic
arrangements of a single loop and the rankings' lists are the job's alone.
``fourbar-grashof`` varies ``lengths[j]`` and covers ``criterion.*`` and the echoed
lengths, ground and link indices.  Refusals, exactly as the processes make them: the
first length out of its range (in the order of the inputs), then, chain by chain, the
spread of its lengths, then its polygons and loops that cannot close (for a four-bar:
the spread, then the loop).  The numbers are the jobs' to the bit
(:mod:`~worker.families.chains.kinematics.study_kernel`).
"""

from __future__ import annotations

from worker.families.chains.study_chains import ChainsPlan
from worker.families.chains.study_fourbar import FourBarPlan
from worker.study_kernels import KernelPlan, KernelRequest, StudyKernel

__all__ = ["CHAIN_PARALLELISM_KERNEL", "FOURBAR_GRASHOF_KERNEL"]

_PER_CHAIN = ("links", "joints", "independent_loops", "mobility", "total_length", "P",
              "P_normalized", "Q", "Q_normalized", "rank.by_P", "rank.by_Q")  # fmt: skip
CHAIN_COVERS = (*(f"chains[].{name}" for name in _PER_CHAIN), "chains[].loops[].Q")
FOURBAR_COVERS = (
    "lengths[]", "ground", "links[].index", "links[].length", "criterion.shortest",
    "criterion.longest", "criterion.s_plus_l", "criterion.p_plus_q", "criterion.margin",
)  # fmt: skip
#: Seconds per unit of chain-parallelism's cost (a link x loop) for one design, batched
#: (Fig 2's five quadrangles, 20 units: about 11 µs a design on the 2-core test machine).
CHAIN_SECONDS_PER_COST = 5e-7
#: Seconds per unit of a batched four-bar's price (``FOURBAR_KERNEL_COST``).
FOURBAR_SECONDS_PER_COST = 4e-3


def _prepare_chains(request: KernelRequest) -> KernelPlan:
    return ChainsPlan.of(request)


def _prepare_fourbar(request: KernelRequest) -> KernelPlan:
    return FourBarPlan.of(request)


CHAIN_PARALLELISM_KERNEL = StudyKernel(
    covers=CHAIN_COVERS,
    varies={
        "chains[].lengths[]": 1.0,
        "chains[].links.*": 1.0,
        "chains[].links.*.sides.*": 1.0,
    },
    prepare=_prepare_chains,
    seconds_per_cost=CHAIN_SECONDS_PER_COST,
    description="Every chain's P, Q, normalised forms, loop Q and ranks over many sets of "
    "lengths at once; any length varied.",
)

FOURBAR_GRASHOF_KERNEL = StudyKernel(
    covers=FOURBAR_COVERS,
    varies={"lengths[]": 1.0},
    prepare=_prepare_fourbar,
    seconds_per_cost=FOURBAR_SECONDS_PER_COST,
    description="Grashof's criterion of many four-bars at once; the lengths varied.",
)
