"""The convergence curves of ``planar3r-design``: the best design, generation by generation.

One panel: the quantity the objective drives (the smallest d_z, or the total length) of
the best design after each generation of the kept start of the global search, the other
starts' curves faintly behind it (where they end shows whether they agree), the
polished optimum after the last, and the paper's rule as a horizontal reference.  Conventions as in
:mod:`worker.families.planar_serial.plots.figures`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator
from numpy.typing import ArrayLike

from worker.common.figures import bad_figure_argument, plain_text

__all__ = ["convergence_figure"]

_CURVE = "#2c5d8a"
_OTHER = "#9db3c8"
_RULE = "#e8373f"
_OPTIMUM = "#1a1a1a"


def convergence_figure(
    values: ArrayLike,
    *,
    optimum: float,
    paper_rule: float | None,
    quantity: str,
    title: str,
    met: Sequence[bool] | None = None,
    paper_rule_note: str = "",
    other_starts: ArrayLike | None = None,
) -> Figure:
    """The best ``quantity`` (mathtext allowed, with its unit) per generation (g,).

    ``optimum``: the value after polishing, marked after the last generation;
    ``paper_rule``: the rule's value, a dashed line (None: not drawn); ``met`` (g,):
    whether each generation's best meets the target (``min_length``): hollow markers
    where it does not; ``paper_rule_note`` is appended to the rule's legend entry;
    ``other_starts`` (s, g): the other starts' curves, drawn faintly behind.
    """
    where = "convergence_figure"
    curve = np.asarray(values, dtype=float)
    if curve.ndim != 1 or curve.size < 1 or not np.isfinite(curve).all():
        raise bad_figure_argument("values", where, "a finite array of shape (g,), g >= 1",
                                  f"shape {curve.shape}")  # fmt: skip
    if met is not None and len(met) != curve.size:
        raise bad_figure_argument("met", where, f"{curve.size} flags", f"{len(met)} flags")
    others = np.empty((0, curve.size)) if other_starts is None else np.asarray(other_starts, float)
    if others.ndim != 2 or others.shape[1] != curve.size or not np.isfinite(others).all():
        raise bad_figure_argument("other_starts", where, f"a finite array (s, {curve.size})",
                                  f"shape {others.shape}")  # fmt: skip
    generations = np.arange(1, curve.size + 1)
    fig = Figure(figsize=(7.0, 4.4), layout="constrained")
    ax = fig.add_subplot()
    for index, other in enumerate(others):
        ax.plot(generations, other, color=_OTHER, lw=1.0,
                label=f"other starts ({len(others)})" if index == 0 else None)  # fmt: skip
    ax.plot(generations, curve, color=_CURVE, lw=1.8, label="best design after each generation")
    if met is not None and not all(met):
        missed = ~np.asarray(met, dtype=bool)
        ax.plot(generations[missed], curve[missed], ls="none", marker="o", ms=4, mfc="white",
                mec=_CURVE, label="target not yet met")  # fmt: skip
    ax.plot([curve.size + 1.0], [optimum], ls="none", marker="*", ms=11, color=_OPTIMUM,
            label=f"optimum after polishing: {optimum:.4f}")  # fmt: skip
    if paper_rule is not None:
        ax.axhline(paper_rule, color=_RULE, ls=(0, (5, 3)), lw=1.4,
                   label=f"the paper's rule (eqs 10–11): {paper_rule:.4f}"
                   f"{', ' + paper_rule_note if paper_rule_note else ''}")  # fmt: skip
    ax.set_xlabel("generation of differential evolution [-]", fontsize=11)
    ax.set_ylabel(quantity, fontsize=11)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlim(0.5, curve.size + 2.0)
    ax.grid(alpha=0.3)
    ax.tick_params(labelsize=10)
    fig.legend(loc="outside lower center", ncols=2, fontsize=9.5, frameon=False)
    fig.suptitle(plain_text(title), fontsize=13, fontweight="bold")
    return fig
