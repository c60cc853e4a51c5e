"""The ``chain-parallelism`` job: P, normalised P and Q of chains, and their rankings.

For every chain, in the order given: its mobility (Grübler-Kutzbach), its dimensions,
P and normalised P (eq 1), each loop's adjacent-side products and deviations and Q
(eq 3, docs/methods/chains.md); for a single loop, every distinct cyclic arrangement of its
lengths ranked by Q.  Then the chains ranked by normalised P (uniform rigidity) and by
Q (parallelism) with the paper's reading of each.  The paper's misprints are noted
when a chain is recognisably one of its figures (:mod:`worker.families.chains.errata`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from worker.common.figures import figure_artifacts, plain_text
from worker.contract import Artifact, JobContext, JobOutcome
from worker.families.chains import kinematics as chains
from worker.families.chains.errata import parallelism_errata_notes
from worker.families.chains.kinematics.measures import SUMS_RTOL
from worker.families.chains.plots import bars as bar_plots
from worker.families.chains.plots import graphs as graph_plots
from worker.families.chains.specs import ChainParallelismSpec, LoopChain, to_chain

__all__ = ["SUMS_RTOL", "chain_entry", "rankings", "run_chain_parallelism"]


_P_READING = (
    "Larger P: link lengths nearer to equal, so more uniformly rigid links (eq 1, of the "
    "lengths normalised by their sum, which makes chains of different size comparable). "
    "P is necessary but not sufficient for parallelism: it ignores which links are "
    "adjacent, so the same dimensions in another arrangement give the same P."
)
_Q_READING = (
    "Smaller Q: more parallel (eq 3); Q = 0 when, in every loop, the products of adjacent "
    "sides are all equal (a dimensionally parallel chain, e.g. a parallelogram). More "
    "parallel chains are more rigid; less parallel ones suit larger workspaces."
)


def run_chain_parallelism(spec: ChainParallelismSpec, ctx: JobContext) -> JobOutcome:
    """Run the job: validated inputs in, result document + artifacts + notes out."""
    ctx.report_progress(0.0, "measures")
    structures = [chains.chain_structure(to_chain(chain)) for chain in spec.chains]
    entries = [
        chain_entry(chain.name, "lengths" if isinstance(chain, LoopChain) else "links", s)
        for chain, s in zip(spec.chains, structures, strict=True)
    ]
    ranking = rankings(entries)
    for entry, by_p, by_q in zip(entries, *_ranks(entries, ranking), strict=True):
        entry["rank"] = {"by_P": by_p, "by_Q": by_q}
    result: dict[str, Any] = {
        "chains": entries,
        "ranking": ranking,
        "method": {
            "P": "product of every distinct dimension (each binary link and each side of a "
            "polygonal link once), eq 1; P_normalized uses l / sum(l)",
            "deviation": "eps_i = l_{i-1} l_i - l_i l_{i+1}: the difference of the two "
            "adjacent-side products containing side i, cyclic round each loop",
            "Q": "sum of eps_i^2 over every side of every loop, inner and peripheral (eq 3); "
            "Q_normalized is Q of the normalised lengths, Q / sum(l)^4",
            "mobility": "Grübler-Kutzbach for revolute joints: 3 (links - 1) - 2 joints",
        },
        "length_unit": spec.length_unit,
    }
    errata, confirmations = parallelism_errata_notes(entries)
    notes = _general_notes(entries, ranking) + confirmations
    ctx.report_progress(50.0, "plots")
    artifacts = _artifacts(spec, entries, structures, ranking) if spec.plots else ()
    ctx.report_progress(100.0, "done")
    return JobOutcome(result=result, artifacts=artifacts, notes=tuple(notes), errata=tuple(errata))


def _floats(values: Any) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=float).ravel()]


def chain_entry(name: str, form: str, structure: chains.ChainStructure) -> dict[str, Any]:
    """One chain's result: structure, dimensions, P, loops with products and deviations, Q."""
    lengths = np.array([length for _, length in structure.dimensions])
    total = math.fsum(lengths.tolist())
    loops: list[dict[str, Any]] = []
    for index, (sides, loop) in enumerate(
        zip(structure.loops, structure.loop_lengths, strict=True)
    ):
        loops.append(
            {
                "index": index,
                "peripheral": index == len(structure.loops) - 1,
                "sides": list(sides),
                "lengths": _floats(loop),
                "products": _floats(chains.adjacent_products(loop)),
                "deviations": _floats(chains.loop_deviations(loop)),
                "Q": float(chains.loop_q(loop)),
            }
        )
    q = math.fsum(loop["Q"] for loop in loops)
    return {
        "name": name,
        "form": form,
        "links": len(structure.links),
        "joints": len(structure.joints),
        "independent_loops": structure.independent_loops,
        "mobility": structure.mobility,
        "dimensions": [
            {"side": side, "length": length, "normalized": length / total}
            for side, length in structure.dimensions
        ],
        "total_length": total,
        "P": float(chains.length_product(lengths)),
        "P_normalized": float(chains.normalized_length_product(lengths)),
        "loops": loops,
        "Q": q,
        "Q_normalized": q / total**4,
        "arrangements": _arrangements(structure) if len(structure.loops) == 1 else None,
    }


def _arrangements(structure: chains.ChainStructure) -> dict[str, Any]:
    sides = structure.loops[0]
    ranked = chains.ranked_arrangements(structure.loop_lengths[0])
    identity = np.arange(len(sides))
    entries = [
        {
            "rank": int(rank),
            "sides": [sides[i] for i in order],
            "lengths": _floats(lengths),
            "Q": float(q),
            "given": bool(np.array_equal(order, identity)),
        }
        for order, lengths, q, rank in zip(
            ranked.orders, ranked.lengths, ranked.q, ranked.ranks, strict=True
        )
    ]
    given = next(e for e in entries if e["given"])
    return {
        "count": len(entries),
        "given_rank": given["rank"],
        "most_parallel": entries[0]["sides"],
        "ranked": entries,
    }


def _ranked(entries: list[dict[str, Any]], key: str, descending: bool) -> list[dict[str, Any]]:
    values = [entry[key] for entry in entries]
    order, ranks = chains.tie_ranks(values, descending=descending)
    return [{"rank": int(ranks[i]), "name": entries[i]["name"], "value": values[i]} for i in order]


def _standing(order: list[dict[str, Any]], best: str, worst: str) -> str:
    """'Most X: A; least X: B and C (tied).' from a ranked list."""
    first = [e["name"] for e in order if e["rank"] == order[0]["rank"]]
    last = [e["name"] for e in order if e["rank"] == order[-1]["rank"]]
    if len(first) == len(order):
        return "All the chains tie." if len(order) > 1 else f"{best.capitalize()}: {first[0]}."
    return f"{best.capitalize()}: {_names(first)}; {worst}: {_names(last)}."


def _names(names: list[str]) -> str:
    return ", ".join(names) + (" (tied)" if len(names) > 1 else "")


def _ranks(entries: list[dict[str, Any]], ranking: dict[str, Any]) -> tuple[list[int], ...]:
    """Each chain's rank by P and by Q, in the order given (ties share a rank)."""
    out = []
    for key, descending in (("by_P", True), ("by_Q", False)):
        values = [entry[ranking[key]["measure"]] for entry in entries]
        _, ranks = chains.tie_ranks(values, descending=descending)
        out.append([int(r) for r in ranks])
    return tuple(out)


def rankings(entries: list[dict[str, Any]]) -> dict[str, Any]:
    """The chains ranked by normalised P (largest first) and by Q (smallest first).

    Q scales as the fourth power of size, so chains whose total lengths differ are
    ranked by Q_normalized instead (the same order when the totals are equal).
    """
    totals = [entry["total_length"] for entry in entries]
    same_size = all(math.isclose(t, totals[0], rel_tol=SUMS_RTOL) for t in totals)
    q_key = "Q" if same_size else "Q_normalized"
    by_p = _ranked(entries, "P_normalized", descending=True)
    by_q = _ranked(entries, q_key, descending=False)
    q_reading = _Q_READING
    if not same_size:
        q_reading += (
            " The chains' total lengths differ, so they are ranked by Q of the normalised "
            "lengths (Q / sum(l)^4): Q itself grows as the fourth power of size."
        )
    return {
        "by_P": {
            "measure": "P_normalized",
            "order": by_p,
            "reading": f"{_P_READING} {_standing(by_p, 'most uniformly rigid', 'least')}",
        },
        "by_Q": {
            "measure": q_key,
            "order": by_q,
            "reading": f"{q_reading} {_standing(by_q, 'most parallel', 'least')}",
        },
    }


def _general_notes(entries: list[dict[str, Any]], ranking: dict[str, Any]) -> list[str]:
    notes = []
    for entry in entries:
        if entry["mobility"] <= 0:
            notes.append(
                f"{entry['name']}: mobility {entry['mobility']} by Grübler-Kutzbach "
                f"({entry['links']} links, {entry['joints']} joints): a structure, not a "
                "mechanism."
            )
        arrangements = entry["arrangements"]
        if arrangements is not None and arrangements["given_rank"] > 1:
            best = arrangements["ranked"][0]
            notes.append(
                f"{entry['name']}: the given arrangement ranks {arrangements['given_rank']} of "
                f"{arrangements['count']} by Q ({entry['Q']:.6g}); the most parallel is "
                f"({', '.join(f'{v:g}' for v in best['lengths'])}) with Q = {best['Q']:.6g}."
            )
    if ranking["by_Q"]["measure"] == "Q_normalized":
        notes.append(
            "The chains differ in total length, so ranking.by_Q uses Q_normalized; the paper "
            "compares Q only between arrangements of the same dimensions."
        )
    return notes


def _printed(value: float) -> str:
    """``value`` to 5 significant digits (Q of the paper's Fig. 2d: 34592), a power of
    ten in mathtext (``1.5$\\times 10^{6}$``)."""
    mantissa, _, exponent = f"{value:.5g}".partition("e")
    return mantissa if not exponent else rf"{mantissa}$\times 10^{{{int(exponent)}}}$"


def _artifacts(
    spec: ChainParallelismSpec,
    entries: list[dict[str, Any]],
    structures: list[chains.ChainStructure],
    ranking: dict[str, Any],
) -> tuple[Artifact, ...]:
    panels = [
        graph_plots.ChainGraph(
            name=entry["name"],
            links=structure.links,
            polygonal=frozenset(
                side.partition(".")[0] for side, _ in structure.dimensions if "." in side
            ),
            joints=structure.joints,
            loops=structure.loops,
            loop_lengths=tuple(tuple(_floats(loop)) for loop in structure.loop_lengths),
            caption=f"{entry['links']} links, {entry['joints']} joints, mobility "
            f"{entry['mobility']} · $P_{{\\mathrm{{norm}}}}$ = {entry['P_normalized']:.4g} · "
            f"$Q$ = {_printed(entry['Q'])} {plain_text(spec.length_unit)}$^4$",
        )
        for entry, structure in zip(entries, structures, strict=True)
    ]
    graphs = graph_plots.chain_graphs_figure(
        panels, title="Kinematic chains: link graphs and loops", length_unit=spec.length_unit
    )
    q_key = ranking["by_Q"]["measure"]
    bars = bar_plots.parallelism_bars_figure(
        [entry["name"] for entry in entries],
        p_normalized=[entry["P_normalized"] for entry in entries],
        q=[entry[q_key] for entry in entries],
        q_normalized=q_key == "Q_normalized",
        title="Uniform rigidity (P) and parallelism (Q)",
        length_unit=spec.length_unit,
    )
    return (
        *figure_artifacts(graphs, "chain_graphs", "Link graphs of the chains, loops marked"),
        *figure_artifacts(bars, "parallelism_comparison", "P and Q of the chains compared"),
    )
