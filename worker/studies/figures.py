"""A study's figures: each objective over a grid of two (or one) varied inputs, and the
objective space with the non-dominated designs highlighted.

Input and result paths are shown as code (mathtext ``\\mathtt``), with their units
(:mod:`.files`); infeasible designs are grey (maps) or left out (scatter).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib import colormaps
from matplotlib.figure import Figure
from numpy.typing import NDArray

from worker.common.figures import explained_constant

__all__ = ["code", "objective_maps_figure", "pareto_figure"]

_FRONT = "#e8373f"
_CLOUD = "#8c8c8c"
_INFEASIBLE = "#d9d9d9"


def code(path: str) -> str:
    """A path as mathtext code: ``task_points[].d_z|min`` without any subscript."""
    escaped = "".join("\\" + c if c in "_{}#%&" else c for c in path)
    return r"$\mathtt{" + escaped + "}$"


def objective_maps_figure(
    axes_values: Sequence[NDArray[np.float64]],
    axes_labels: Sequence[str],
    maps: Sequence[NDArray[np.float64]],
    map_labels: Sequence[str],
    title: str,
) -> Figure:
    """Heat maps (two varied inputs: ``maps`` (n0, n1) each) or curves (one: (n0,)) of
    each objective; NaN (infeasible) drawn grey."""
    count = len(maps)
    fig = Figure(figsize=(4.9 * count + 0.6, 4.6), layout="constrained")
    for k, (values, label) in enumerate(zip(maps, map_labels, strict=True)):
        ax = fig.add_subplot(1, count, k + 1)
        if len(axes_values) == 1:
            ax.plot(axes_values[0], values, color="#2c5d8a", marker="o", ms=3, lw=1.5)
            ax.set_xlabel(axes_labels[0], fontsize=10)
            ax.set_ylabel(label, fontsize=10)
            ax.grid(alpha=0.3)
            continue
        x, y = axes_values[1], axes_values[0]
        cmap = colormaps["viridis"].with_extremes(bad=_INFEASIBLE)
        mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(values), shading="nearest", cmap=cmap,
                             rasterized=True)  # fmt: skip
        finite = values[np.isfinite(values)]
        if finite.size and np.ptp(finite) == 0:
            explained_constant(ax, "the same value at every feasible design")
        ax.set_xlabel(axes_labels[1], fontsize=10)
        ax.set_ylabel(axes_labels[0], fontsize=10)
        bar = fig.colorbar(mesh, ax=ax, shrink=0.9)
        bar.set_label(label, fontsize=10)
    fig.suptitle(title, fontsize=12, fontweight="bold")
    return fig


def pareto_figure(
    objectives: NDArray[np.float64],
    front: NDArray[np.intp],
    labels: Sequence[str],
    goals: Sequence[str],
    title: str,
) -> Figure:
    """The first two objectives of every feasible design (n, k), the non-dominated
    ``front`` rows joined in order of the first objective."""
    fig = Figure(figsize=(6.6, 5.4), layout="constrained")
    ax = fig.add_subplot()
    finite = np.isfinite(objectives[:, :2]).all(axis=1)
    ax.plot(objectives[finite, 0], objectives[finite, 1], ls="none", marker=".", ms=4,
            color=_CLOUD, alpha=0.6, label=f"feasible designs ({int(finite.sum()):,})")  # fmt: skip
    points = objectives[front][:, :2]
    order = np.argsort(points[:, 0], kind="stable")
    ax.plot(points[order, 0], points[order, 1], marker="o", ms=5, color=_FRONT, lw=1.2,
            label=f"non-dominated ({len(front):,})")  # fmt: skip
    words = {"max": "larger is better", "min": "smaller is better"}
    ax.set_title(f"x: {words[goals[0]]}; y: {words[goals[1]]}", fontsize=9.5, color="0.3")
    ax.set_xlabel(labels[0], fontsize=10)
    ax.set_ylabel(labels[1], fontsize=10)
    ax.grid(alpha=0.3)
    fig.legend(loc="outside lower center", ncols=2, fontsize=9.5, frameon=False)
    fig.suptitle(title, fontsize=12, fontweight="bold")
    return fig
