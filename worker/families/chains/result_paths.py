"""The numeric result paths of the chain processes: units, symbols, meanings
(:mod:`worker.result_paths`; lengths in the job's ``length_unit``)."""

from __future__ import annotations

from worker.result_paths import ResultPathInfo as R

__all__ = ["CHAIN_PARALLELISM_RESULT_PATHS", "FOURBAR_GRASHOF_RESULT_PATHS"]

_Q = "$Q$"

CHAIN_PARALLELISM_RESULT_PATHS = (
    R("chains[].links", "-", "", "Links of the chain."),
    R("chains[].joints", "-", "", "Joints of the chain."),
    R("chains[].independent_loops", "-", "", "Independent loops."),
    R("chains[].mobility", "-", "$M$", "Degrees of freedom (Grübler-Kutzbach)."),
    R("chains[].dimensions[].length", "length", "$l_i$", "A dimension: a binary link, or a "
      "side of a polygonal link."),
    R("chains[].dimensions[].normalized", "-", r"$l_i/\sum l$", "The dimension over the sum "
      "of them all."),
    R("chains[].total_length", "length", r"$\sum l$", "The sum of the dimensions."),
    R("chains[].P", "length^n", "$P$", "Product of the dimensions (eq 1), in length_unit "
      "to the power of their number."),
    R("chains[].P_normalized", "-", r"$P_{\mathrm{norm}}$", "P of the dimensions over their "
      "sum (eq 1; larger: more uniform rigidity)."),
    R("chains[].loops[].index", "-", "", "The loop's index (the peripheral loop last)."),
    R("chains[].loops[].lengths[]", "length", "$l_i$", "Its sides' lengths, in order round "
      "the loop."),
    R("chains[].loops[].products[]", "length^2", r"$l_i l_{i+1}$", "Products of adjacent "
      "sides (product k joins sides k and k+1)."),
    R("chains[].loops[].deviations[]", "length^2", r"$\varepsilon_i$",
      "eps_i = l_(i-1) l_i - l_i l_(i+1), one per side."),
    R("chains[].loops[].Q", "length^4", "$Q$", "The loop's sum of eps_i squared."),
    R("chains[].Q", "length^4", _Q, "Q: the sum of eps squared over every side of every loop "
      "(eq 3; smaller: more parallel)."),
    R("chains[].Q_normalized", "-", r"$Q_{\mathrm{norm}}$", "Q of the dimensions over their "
      "sum: Q / (sum l)^4."),
    R("chains[].arrangements.count", "-", "", "Distinct cyclic arrangements of a single loop."),
    R("chains[].arrangements.given_rank", "-", "", "The given arrangement's rank by Q."),
    R("chains[].arrangements.ranked[].rank", "-", "", "The arrangement's rank by Q (1 most "
      "parallel)."),
    R("chains[].arrangements.ranked[].lengths[]", "length", "$l_i$", "Its lengths in order."),
    R("chains[].arrangements.ranked[].Q", "length^4", _Q, "Its Q (eq 3)."),
    R("chains[].rank.by_P", "-", "", "The chain's place ranked by P_normalized (1 first)."),
    R("chains[].rank.by_Q", "-", "", "The chain's place ranked by Q (1 first)."),
    R("ranking.by_P.order[].rank", "-", "", "Rank by P_normalized (ties share a rank)."),
    R("ranking.by_P.order[].value", "-", r"$P_{\mathrm{norm}}$", "The chain's P_normalized."),
    R("ranking.by_Q.order[].rank", "-", "", "Rank by Q (ties share a rank)."),
    R("ranking.by_Q.order[].value", "mixed", _Q, "The chain's value of the measure ranked: "
      "Q (length_unit^4), or Q_normalized (a pure number) when the chains' total lengths "
      "differ; 'measure' says which."),
)  # fmt: skip

FOURBAR_GRASHOF_RESULT_PATHS = (
    R("lengths[]", "length", "$L_i$", "The four lengths, in order round the loop."),
    R("ground", "-", "", "Index of the fixed link."),
    R("criterion.shortest", "-", "", "Index of the shortest link, s."),
    R("criterion.longest", "-", "", "Index of the longest link, l."),
    R("criterion.s_plus_l", "length", "$s + l$", "Shortest plus longest length."),
    R("criterion.p_plus_q", "length", "$p + q$", "The other two lengths' sum."),
    R("criterion.margin", "length", "$p + q - (s + l)$", "Grashof's margin: positive for a "
      "Grashof chain, 0 at a change point, negative otherwise."),
    R("links[].index", "-", "", "The link's index."),
    R("links[].length", "length", "$L_i$", "Its length."),
    R("links[].turns_fully_relative_to[]", "-", "", "Indices of the links it turns fully "
      "relative to."),
    R("full_turns[][]", "-", "", "Pairs [i, j] of links that turn fully relative to each "
      "other."),
)  # fmt: skip
