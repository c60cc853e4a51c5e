"""Kinematic chains (docs/methods/chains.md): two job kinds.

``chain-parallelism``: P, normalised P and Q of chains with the same number of links
and degrees of freedom, ranked; every cyclic arrangement of a single loop ranked by Q.
``fourbar-grashof``: Grashof type, Barker's class and the fully turning link pairs of a
four-bar chain with a chosen ground.

Importing this package builds the two process definitions and nothing else: the job
modules (matplotlib figures) are imported when a job runs.
"""

from __future__ import annotations

from worker.contract import JobContext, JobOutcome
from worker.families.chains.costs import (
    CHAIN_COST_LIMIT,
    CHAIN_SYNC_COST_LIMIT,
    FOURBAR_COST_LIMIT,
    FOURBAR_SYNC_COST_LIMIT,
    TIME_LIMIT_S,
    chain_parallelism_cost,
    fourbar_grashof_cost,
)
from worker.families.chains.examples import CHAIN_PARALLELISM_EXAMPLES, FOURBAR_GRASHOF_EXAMPLES
from worker.families.chains.fourbar_spec import FourBarGrashofSpec
from worker.families.chains.result_paths import (
    CHAIN_PARALLELISM_RESULT_PATHS,
    FOURBAR_GRASHOF_RESULT_PATHS,
)
from worker.families.chains.specs import (
    MAX_CHAINS,
    MAX_SINGLE_LOOP_LINKS,
    ChainParallelismSpec,
)
from worker.families.chains.study import CHAIN_PARALLELISM_KERNEL, FOURBAR_GRASHOF_KERNEL
from worker.processes import FamilyInfo, ProcessDefinition, figure_files

__all__ = ["CHAIN_PARALLELISM", "FAMILY", "FOURBAR_GRASHOF", "PROCESSES"]


def _run_chain_parallelism(spec: ChainParallelismSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib, scipy) loads when a job runs, not with the registry
    from worker.families.chains.jobs.parallelism import run_chain_parallelism

    return run_chain_parallelism(spec, ctx)


def _run_fourbar_grashof(spec: FourBarGrashofSpec, ctx: JobContext) -> JobOutcome:
    # lazy: the job module (matplotlib, scipy) loads when a job runs, not with the registry
    from worker.families.chains.jobs.fourbar import run_fourbar_grashof

    return run_fourbar_grashof(spec, ctx)


CHAIN_PARALLELISM = ProcessDefinition(
    id="chain-parallelism",
    version="1.1.0",  # chain_graphs: Q with its unit
    result_paths=CHAIN_PARALLELISM_RESULT_PATHS,
    study_kernel=CHAIN_PARALLELISM_KERNEL,
    title="Kinematic chains: uniform rigidity (P) and parallelism (Q)",
    method_doc="chains",
    files=(
        *figure_files("chain_graphs", "Link graphs of the chains, loops marked"),
        *figure_files("parallelism_comparison", "P and Q of the chains compared"),
    ),
    description=(
        "Compares planar kinematic chains with the same number of links and degrees of "
        "freedom (docs/methods/chains.md). For each chain, in the order given: its mobility by "
        "Grübler-Kutzbach, P = the product of its dimensions and P of the lengths "
        "normalised by their sum (eq 1; larger: more uniform rigidity), each loop's "
        "adjacent-side products and deviations eps_i = l_(i-1) l_i - l_i l_(i+1), and "
        "Q = the sum of eps² over every side of every inner and the peripheral loop (eq 3; "
        "smaller: more parallel); for a single loop, every distinct cyclic arrangement of "
        "its lengths ranked by Q. Then the chains ranked by P and by Q with the paper's "
        "reading, its misprints in notes when a chain is one of its figures, and link-graph "
        "and bar-chart plots. A chain is {'name', 'lengths'} (one loop of binary links) or "
        "{'name', 'links', 'loops'} (polygonal links by side; inner loops, peripheral last). "
        f"Cost: links x loops per chain, plus (n-1)!/2 arrangements for a single loop of n "
        f"<= {MAX_SINGLE_LOOP_LINKS} links; at most {CHAIN_COST_LIMIT:,} ({MAX_CHAINS} chains). "
        f"Requests costing up to {CHAIN_SYNC_COST_LIMIT:,} sent with 'Prefer: wait=N' are "
        "answered synchronously (200 with the results) when they finish within N seconds."
    ),
    inputs_model=ChainParallelismSpec,
    run=_run_chain_parallelism,
    examples=CHAIN_PARALLELISM_EXAMPLES,
    outputs={
        "chains": "Per chain, in the order given: name, form ('lengths' or 'links'), links, "
        "joints, independent_loops, mobility, dimensions (side, length, normalized), "
        "total_length, P, P_normalized, loops (index, peripheral, sides, lengths, products "
        "[product k joins sides k and k+1], deviations [one per side], Q), Q, Q_normalized, "
        "and for a single loop its arrangements (count, given_rank, most_parallel, ranked: "
        "rank, sides, lengths, Q, given); null otherwise; rank (by_P, by_Q: its place in "
        "the rankings below, 1 first, ties sharing a rank).",
        "ranking": "by_P (P_normalized, largest first) and by_Q (Q, or Q_normalized when the "
        "chains' total lengths differ; smallest first): measure, order [rank, name, value] "
        "with ties sharing a rank, and the paper's reading.",
        "method": "The formulas used for P, the deviations, Q and the mobility.",
        "length_unit": "The length unit.",
    },
    cost=chain_parallelism_cost,
    cost_limit=CHAIN_COST_LIMIT,
    seconds_per_cost=5e-5,
    cost_unit="links x loops, plus cyclic arrangements of single loops",
    sync_cost_limit=CHAIN_SYNC_COST_LIMIT,
    time_limit_s=TIME_LIMIT_S,
)

FOURBAR_GRASHOF = ProcessDefinition(
    id="fourbar-grashof",
    result_paths=FOURBAR_GRASHOF_RESULT_PATHS,
    study_kernel=FOURBAR_GRASHOF_KERNEL,
    title="Four-bar chain: Grashof type, Barker's class and fully turning links",
    method_doc="chains",
    files=figure_files("fourbar_motion", "Range of motion and fully turning links"),
    description=(
        "Grashof's criterion s + l vs p + q (Patel & Sobh eqs 6-7) on four link lengths in "
        "order round the loop: Grashof, non-Grashof or change point; with the given ground "
        "link (input ground+1, coupler ground+2, output ground+3), the classification "
        "(crank-rocker, double-crank, double-rocker, triple-rocker, change-point) and "
        "Barker's finer class (I-1 GCCC ... III-6 S3X); and which links turn fully relative "
        "to which, from loop closure: links i and j do iff L_i + L_j <= L_y + L_z and "
        "|L_i - L_j| >= |L_y - L_z| for the other two. Cost 1, always within the synchronous "
        "limit: with 'Prefer: wait=N' the response is 200 with the results."
    ),
    inputs_model=FourBarGrashofSpec,
    run=_run_fourbar_grashof,
    examples=FOURBAR_GRASHOF_EXAMPLES,
    outputs={
        "lengths": "The four lengths, in order round the loop.",
        "ground": "The index of the fixed link.",
        "grashof": "'grashof' (s + l < p + q), 'non-grashof' (>) or 'change-point' (=).",
        "classification": "'crank-rocker', 'double-crank', 'double-rocker', "
        "'triple-rocker' or 'change-point'.",
        "barker": "Barker's class: number ('I-2'), code ('GCRR'), name.",
        "criterion": "shortest and longest link (indices), s + l, p + q and their margin.",
        "links": "Per link: index, length, role (ground/input/coupler/output), motion "
        "relative to the ground (crank/rocker), and the links it turns fully relative to.",
        "full_turns": "Every pair [i, j] (i < j) of links that turn fully relative to each other.",
        "length_unit": "The length unit.",
    },
    cost=fourbar_grashof_cost,
    cost_limit=FOURBAR_COST_LIMIT,
    cost_unit="four-bar chains",
    sync_cost_limit=FOURBAR_SYNC_COST_LIMIT,
    time_limit_s=TIME_LIMIT_S,
)

#: Who this family is: the tag its operations are listed under, and its paper.
FAMILY = FamilyInfo(
    name="chains",
    tag="Kinematic chains",
    description=("Parallelism measures P and Q; Grashof classification of four-bars."),
    paper="the parallelism paper",
)

#: This family's processes, in the order GET /v1/processes lists them.
PROCESSES = (
    CHAIN_PARALLELISM,
    FOURBAR_GRASHOF,
)
