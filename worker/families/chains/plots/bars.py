"""P and Q of the ranked arrangements compared as bars (the chain-parallelism job)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Patch
from matplotlib.ticker import MaxNLocator

from worker.common.figures import categorical, plain_text
from worker.families.chains.plots.graphs import FloatArray, bad_argument

__all__ = ["parallelism_bars_figure"]

_BEST_COLOUR = "#2c5d8a"
_OTHER_COLOUR = "#9db7cf"


def _ranks(values: FloatArray, descending: bool) -> list[int]:
    """1-based competition ranks; values within 1e-12 (relative) tie."""
    signed = -values if descending else values
    return [
        1 + int(np.sum((signed < v) & ~np.isclose(signed, v, rtol=1e-12, atol=0.0))) for v in signed
    ]


def _scale(values: FloatArray) -> tuple[float, str]:
    """A power of ten that brings the largest value into [1, 1000), and its mathtext
    (empty for 1): the axis label carries it, not the axis end."""
    top = float(np.max(np.abs(values))) if values.size else 0.0
    if top == 0.0 or 1e-2 <= top < 1e4:
        return 1.0, ""
    exponent = math.floor(math.log10(top))
    exponent -= exponent % 3
    return 10.0**exponent, f"$10^{{{exponent}}}$"


def _bar_panel(
    ax: Axes,
    names: Sequence[str],
    raw: FloatArray,
    descending: bool,
    label: str,
    quantity: str,
    unit: str,
) -> None:
    ranks = _ranks(raw, descending)
    factor, power = _scale(raw)
    values = raw / factor
    y = np.arange(len(names))
    colours = [_BEST_COLOUR if r == 1 else _OTHER_COLOUR for r in ranks]
    ax.barh(y, values, color=colours, height=0.6, zorder=2)
    span = float(values.max()) if values.size and float(values.max()) > 0 else 1.0
    for yi, (value, rank) in enumerate(zip(values.tolist(), ranks, strict=True)):
        ax.text(
            value + 0.015 * span,
            yi,
            f"{value:.4g}   #{rank}",
            va="center",
            ha="left",
            fontsize=9,
            fontweight="bold" if rank == 1 else "normal",
            color=_BEST_COLOUR if rank == 1 else "0.15",
        )
    ax.set_yticks(y, [plain_text(n) for n in names], fontsize=10)
    ax.invert_yaxis()
    ax.set_xlim(0.0, span * 1.45)
    ax.xaxis.set_major_locator(MaxNLocator(4))
    ax.grid(axis="x", color="0.9", zorder=0)
    ax.set_title(label, fontsize=11)
    scaled = f"{power} {unit}".strip() if unit != "-" or not power else power
    ax.set_xlabel(f"{quantity} [{scaled}]", fontsize=10)


def parallelism_bars_figure(
    names: Sequence[str],
    *,
    p_normalized: Sequence[float],
    q: Sequence[float],
    q_normalized: bool = False,
    title: str,
    length_unit: str = "units",
) -> Figure:
    """Normalised P (larger: more uniform rigidity) beside Q (smaller: more parallel).

    Each bar is labelled with its value and rank (#1 best, ties share a rank); the best
    chain(s) of each measure are drawn dark.  ``q_normalized``: ``q`` holds Q
    of the normalised lengths (chains of different total length), which has no unit;
    otherwise Q is in ``length_unit`` to the fourth power.
    """
    where = "parallelism_bars_figure"
    p_arr = np.asarray(p_normalized, dtype=float)
    q_arr = np.asarray(q, dtype=float)
    if not names or p_arr.shape != (len(names),) or q_arr.shape != (len(names),):
        raise bad_argument(
            "p_normalized",
            where,
            "one value per name in p_normalized and q",
            (len(names), p_arr.shape, q_arr.shape),
        )
    if not (np.all(np.isfinite(p_arr)) and np.all(np.isfinite(q_arr))):
        raise bad_argument("q", where, "finite values", q)
    fig = Figure(figsize=(10.0, 2.0 + 0.55 * len(names)), layout="constrained")
    left, right = fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)
    _bar_panel(
        left, names, p_arr, True, "normalised $P$  (larger: more uniform rigidity)",
        r"$P$ of $l / \sum l$ (eq 1)", "-",
    )  # fmt: skip
    if q_normalized:
        q_title, q_quantity, q_unit = (
            "$Q$ of normalised lengths",
            r"$Q$ of $l / \sum l$ (eq 3)",
            "-",
        )
    else:
        q_title, q_quantity, q_unit = "$Q$", "$Q$ (eq 3)", f"{plain_text(length_unit)}$^4$"
    _bar_panel(
        right, names, q_arr, False, f"{q_title}  (smaller: more parallel)", q_quantity, q_unit
    )
    right.set_yticklabels([])
    left.set_ylabel("chain", fontsize=10)
    categorical(left.yaxis, right.yaxis)
    fig.legend(
        handles=[
            Patch(color=_BEST_COLOUR, label="best of the measure (rank #1; ties share a rank)"),
            Patch(color=_OTHER_COLOUR, label="other chains (value and rank #k on the bar)"),
        ],
        loc="outside lower center", ncols=2, fontsize=9, frameon=False,
    )  # fmt: skip
    fig.suptitle(plain_text(title), fontsize=13, fontweight="bold")
    return fig
