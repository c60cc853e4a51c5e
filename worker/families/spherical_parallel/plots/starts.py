"""The outcome of every start of an spm optimisation, as a bar chart.

Conventions as in :mod:`worker.families.spherical_parallel.plots.conditioning`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from worker.common.figures import bad_figure_argument, categorical, dimensionless, plain_text

if TYPE_CHECKING:
    from matplotlib.artist import Artist

__all__ = ["StartBar", "optimisation_starts_figure"]


@dataclass(frozen=True)
class StartBar:
    """One optimisation start: its final eq 28 value (NaN: infeasible), whether scipy
    reported convergence, and a short label of where it ended."""

    score: float
    converged: bool
    label: str


def _best_label(starts: Sequence[StartBar], best: int | None, reported: str) -> str:
    """The legend entry of the best start, naming the reported design when it is a twin."""
    if best is None or not reported or plain_text(reported) == plain_text(starts[best].label):
        return "optimum"
    return (
        f"optimum: start {best} ends at {plain_text(starts[best].label)}, reported as its "
        f"twin {plain_text(reported)} (the same score)"
    )


def optimisation_starts_figure(
    starts: Sequence[StartBar],
    *,
    best_index: int | None,
    title: str,
    references: Sequence[tuple[str, float]] = (),
    reported: str = "",
) -> Figure:
    """The final mean(1/kappa^2) of every start, the best one highlighted; horizontal lines
    for reference values (e.g. the paper's printed value).  ``reported``: the design the
    result reports, when it is not the best start's own (a twin scoring the same)."""
    where = "optimisation_starts_figure"
    if not starts:
        raise bad_figure_argument("starts", where, "at least one StartBar", "none")
    fig = Figure(figsize=(max(7.0, 0.55 * len(starts) + 3.0), 5.6), layout="constrained")
    ax = fig.add_subplot()
    x = np.arange(len(starts))
    scores = np.array([s.score for s in starts], dtype=float)
    colors = ["#1f5fa8" if s.converged else "#e9a23b" for s in starts]
    heights = np.where(np.isfinite(scores), scores, 0.0)
    bars = ax.bar(x, heights, color=colors, edgecolor="black", linewidth=0.6, zorder=3)
    if best_index is not None:
        bars[best_index].set_edgecolor("#d1495b")
        bars[best_index].set_linewidth(2.4)
    top = max(1e-3, float(np.nanmax(scores)) if np.isfinite(scores).any() else 1e-3)
    for k, start in enumerate(starts):
        text = plain_text(start.label) if np.isfinite(scores[k]) else "infeasible"
        ax.text(k, heights[k] + 0.015 * top, text, rotation=90, ha="center", va="bottom",
                fontsize=7.5, color="0.2", zorder=4)  # fmt: skip
    styles = ((0, (5, 3)), (0, (1, 2)), "-.")
    for k, (label, value) in enumerate(references):
        ax.axhline(value, color="#d1495b", lw=1.1, ls=styles[k % 3], zorder=2,
                   label=plain_text(label))  # fmt: skip
    ax.set_ylim(0.0, 1.45 * top)
    ax.set_xticks(x, [str(k) for k in x], fontsize=9)
    ax.set_xlabel("start", fontsize=11)
    ax.set_ylabel(r"mean$(1/\kappa^2)$ at the end of the start (eq 28)", fontsize=10.5)
    categorical(ax.xaxis)
    dimensionless(ax.yaxis)
    ax.grid(axis="y", alpha=0.3, zorder=0)
    fig.suptitle(title, fontsize=12.5, fontweight="bold")
    best = _best_label(starts, best_index, reported)
    handles: list[Artist] = [
        Patch(fc="#1f5fa8", ec="black", lw=0.6, label="converged"),
        Patch(fc="#e9a23b", ec="black", lw=0.6, label="stopped by the evaluation budget"),
        Patch(fc="white", ec="#d1495b", lw=2.4, label=best),
    ]
    handles += ax.get_legend_handles_labels()[0]
    fig.legend(
        handles=handles,
        loc="outside lower center",
        ncols=1 if len(best) > 40 else 2,  # a long entry gets a line of its own
        fontsize=9,
        frameon=False,
    )
    return fig
