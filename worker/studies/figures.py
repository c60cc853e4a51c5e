"""A study's figures: each objective over a grid of two (or one) varied inputs, small
multiples over three, and the objective space with the non-dominated designs
highlighted.

Input and result paths are shown as code (mathtext ``\\mathtt``), with their units
(:mod:`.files`) and, for an objective, the symbol its process declares; infeasible
designs are grey (maps) or left out (scatter).  The paper's designs the study contains
(:mod:`.paper_points`) are marked on each, under the non-dominated designs.

Axes follow the order of the varied inputs: the first on x, the second on y (as the
papers' figures put alpha1 on x and alpha2 on y); with three, the one with the fewest
values makes the panels and the other two keep that order.
"""

from __future__ import annotations

import math
import unicodedata
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib import colormaps
from matplotlib.figure import Figure
from numpy.typing import NDArray

from worker.common.figures import explained_constant

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = [
    "Marker",
    "code",
    "objective_label",
    "objective_maps_figure",
    "objective_slices_figure",
    "pareto_figure",
    "slice_indices",
]

_FRONT = "#e8373f"
_CLOUD = "#8c8c8c"
_PAPER = "#1f1f1f"
#: Drawing order in the objective space: the cloud, the paper's designs, the front on top.
_CLOUD_Z, _PAPER_Z, _FRONT_Z = 2.0, 3.0, 4.0
_INFEASIBLE = "#d9d9d9"
_MARKER_SHAPES = ("*", "D", "P", "X", "s", "^")
#: Most slices of the third varied input shown (evenly spread, both ends kept).
MAX_SLICES = 6
#: Point clouds larger than this are drawn as an image inside the SVG (a million
#: vector markers would make a file of hundreds of megabytes).
RASTER_POINTS = 5_000


@dataclass(frozen=True)
class Marker:
    """A paper's design on the plots: its label, its value of each varied input (in the
    figure's axis order) and, where the study evaluated it, its objectives."""

    label: str
    at: tuple[float, ...]
    objectives: tuple[float, ...] | None = None


def symbols(label: str) -> str:
    """A label with its Greek letters as mathtext symbols ("δ = 1.7" -> "$\\delta$ = 1.7")."""
    out = []
    for c in label:
        name = unicodedata.name(c, "")
        if name.startswith(("GREEK SMALL LETTER ", "GREEK CAPITAL LETTER ")):
            word = name.rsplit(" ", 1)[-1].lower()
            out.append(f"$\\{word.capitalize() if 'CAPITAL' in name else word}$")
        else:
            out.append(c)
    return "".join(out)


def _mark(ax: Axes, markers: Sequence[Marker], x_axis: int, y_axis: int | None) -> None:
    """Draw the markers on a heat map (x and y axes) or a curve (x only)."""
    for k, marker in enumerate(markers):
        shape = _MARKER_SHAPES[k % len(_MARKER_SHAPES)]
        label = symbols(marker.label)
        if y_axis is None:
            ax.axvline(marker.at[x_axis], ls="--", lw=1.2, color="#b8321f", label=label)
            continue
        ax.plot(marker.at[x_axis], marker.at[y_axis], ls="none", marker=shape, ms=11,
                mfc="white", mec="black", mew=1.2, label=label, zorder=5)  # fmt: skip


def code(path: str) -> str:
    """A path as mathtext code: ``task_points[].d_z|min`` without any subscript."""
    # Mathtext spaces a "." as punctuation: a negative thin space takes it back.
    escaped = "".join("\\" + c if c in "_{}#%&" else ".\\!" if c == "." else c for c in path)
    return r"$\mathtt{" + escaped + "}$"


def objective_label(path: str, symbol: str, unit: str) -> str:
    """An objective's axis label: its path as code, then its symbol (with the reduction
    the path asks for, ``min $d_z$``) and unit: ``[cm$^2$]``, ``[-]``."""
    shown = unit.replace("$", r"\$")
    for power in ("2", "3", "4", "n"):
        shown = shown.replace(f"^{power}", f"$^{power}$")
    reduction = path.partition("|")[2]
    if not symbol:
        return f"{code(path)} [{shown}]"
    return f"{code(path)}\n{reduction} {symbol} [{shown}]".replace("\n ", "\n")


def objective_maps_figure(
    axes_values: Sequence[NDArray[np.float64]],
    axes_labels: Sequence[str],
    maps: Sequence[NDArray[np.float64]],
    map_labels: Sequence[str],
    title: str,
    markers: Sequence[Marker] = (),
) -> Figure:
    """Heat maps (two varied inputs: ``maps`` (n0, n1) each, the first input on x) or
    curves (one: (n0,)) of each objective; NaN (infeasible) drawn grey; ``markers`` on
    each panel."""
    count = len(maps)
    fig = Figure(figsize=(4.9 * count + 0.6, 4.6 + 0.35 * bool(markers)), layout="constrained")
    for k, (values, label) in enumerate(zip(maps, map_labels, strict=True)):
        ax = fig.add_subplot(1, count, k + 1)
        if len(axes_values) == 1:
            ax.plot(axes_values[0], values, color="#2c5d8a", marker="o", ms=3, lw=1.5)
            _mark(ax, markers, 0, None)
            ax.set_xlabel(axes_labels[0], fontsize=10)
            ax.set_ylabel(label, fontsize=10)
            ax.grid(alpha=0.3)
            continue
        mesh = _heat_map(ax, axes_values[0], axes_values[1], values.T)
        _mark(ax, markers, 0, 1)
        ax.set_xlabel(axes_labels[0], fontsize=10)
        ax.set_ylabel(axes_labels[1], fontsize=10)
        bar = fig.colorbar(mesh, ax=ax, shrink=0.9)
        bar.set_label(label, fontsize=10)
    _legend(fig, markers)
    fig.suptitle(title, fontsize=12, fontweight="bold")
    return fig


def _heat_map(
    ax: Axes,
    x: NDArray[np.float64],
    y: NDArray[np.float64],
    values: NDArray[np.float64],
    limits: tuple[float, float] | None = None,
) -> Any:
    cmap = colormaps["viridis"].with_extremes(bad=_INFEASIBLE)
    vmin, vmax = limits if limits is not None else (None, None)
    mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(values), shading="nearest", cmap=cmap,
                         vmin=vmin, vmax=vmax, rasterized=True)  # fmt: skip
    finite = values[np.isfinite(values)]
    if finite.size and np.ptp(finite) == 0:
        explained_constant(ax, "the same value at every feasible design")
    return mesh


def _legend(fig: Figure, markers: Sequence[Marker]) -> None:
    """One legend entry per marker drawn (every panel draws its own)."""
    entries: dict[str, Any] = {}
    for ax in fig.axes:
        for handle, label in zip(*ax.get_legend_handles_labels(), strict=True):
            entries.setdefault(label, handle)
    if entries:
        fig.legend(list(entries.values()), list(entries), loc="outside lower center",
                   ncols=min(3, len(entries)), fontsize=9, frameon=False,
                   title="the paper's designs", title_fontsize=9)  # fmt: skip


def slice_indices(n: int, most: int = MAX_SLICES) -> list[int]:
    """At most ``most`` indices of ``n`` values, evenly spread, both ends kept."""
    if n <= most:
        return list(range(n))
    return sorted({round(i * (n - 1) / (most - 1)) for i in range(most)})


def objective_slices_figure(
    axes_values: Sequence[NDArray[np.float64]],
    axes_labels: Sequence[str],
    maps: Sequence[NDArray[np.float64]],
    map_labels: Sequence[str],
    title: str,
    markers: Sequence[Marker] = (),
) -> Figure:
    """Three varied inputs: small multiples, one row per objective (``maps`` (n0, n1,
    n2) each), one heat map per value of the input with the fewest values (at most
    :data:`MAX_SLICES`), one colour scale per row; a marker on the panel of its value."""
    sliced = min(range(3), key=lambda axis: (len(axes_values[axis]), -axis))
    x_axis, y_axis = (axis for axis in range(3) if axis != sliced)
    picks = slice_indices(len(axes_values[sliced]))
    rows, cols = len(maps), len(picks)
    fig = Figure(figsize=(3.3 * cols + 1.4, 3.1 * rows + 0.9 + 0.35 * bool(markers)),
                 layout="constrained")  # fmt: skip
    grid = fig.subplots(rows, cols, squeeze=False, sharex=True, sharey=True)
    for r, (values, label) in enumerate(zip(maps, map_labels, strict=True)):
        finite = values[np.isfinite(values)]
        limits = (float(finite.min()), float(finite.max())) if finite.size else None
        meshes = []
        for c, pick in enumerate(picks):
            ax = grid[r][c]
            panel = np.moveaxis(values, (y_axis, x_axis, sliced), (0, 1, 2))[:, :, pick]
            meshes.append(_heat_map(ax, axes_values[x_axis], axes_values[y_axis], panel, limits))
            at = float(axes_values[sliced][pick])
            here = [m for m in markers if math.isclose(m.at[sliced], at, rel_tol=1e-9,
                                                       abs_tol=1e-9)]  # fmt: skip
            _mark(ax, here, x_axis, y_axis)
            ax.set_title(f"{axes_labels[sliced]} = {at:.4g}", fontsize=9)
            if r == rows - 1:
                ax.set_xlabel(axes_labels[x_axis], fontsize=9.5)
            if c == 0:
                ax.set_ylabel(axes_labels[y_axis], fontsize=9.5)
        bar = fig.colorbar(meshes[-1], ax=list(grid[r]), shrink=0.9)
        bar.set_label(label, fontsize=9.5)
    _legend(fig, markers)
    shown = "" if len(picks) == len(axes_values[sliced]) else (
        f" ({len(picks)} of its {len(axes_values[sliced])} values)")  # fmt: skip
    fig.suptitle(f"{title}: one panel per value of {axes_labels[sliced]}{shown}", fontsize=11.5,
                 fontweight="bold")  # fmt: skip
    return fig


def pareto_figure(
    objectives: NDArray[np.float64],
    front: NDArray[np.intp],
    labels: Sequence[str],
    goals: Sequence[str],
    title: str,
    markers: Sequence[Marker] = (),
) -> Figure:
    """The first two objectives of every feasible design (n, k), the non-dominated
    ``front`` rows joined in order of the first objective, and the paper's designs the
    study evaluated."""
    fig = Figure(figsize=(6.6, 5.4), layout="constrained")
    ax = fig.add_subplot()
    finite = np.isfinite(objectives[:, :2]).all(axis=1)
    ax.plot(objectives[finite, 0], objectives[finite, 1], ls="none", marker=".", ms=4,
            color=_CLOUD, alpha=0.6, label=f"feasible designs ({int(finite.sum()):,})",
            zorder=_CLOUD_Z, rasterized=bool(finite.sum() > RASTER_POINTS))  # fmt: skip
    for k, marker in enumerate(markers):
        if marker.objectives is not None and all(map(math.isfinite, marker.objectives[:2])):
            # Hollow and under the front, each smaller than the last: twins share their
            # objectives, and a paper design on the front leaves its red dot in sight.
            ax.plot(*marker.objectives[:2], ls="none", marker=_MARKER_SHAPES[k % 6],
                    ms=max(15 - 4 * k, 6), mfc="none", mec=_PAPER, mew=1.3, zorder=_PAPER_Z,
                    label=f"the paper's design: {symbols(marker.label)}")  # fmt: skip
    points = objectives[front][:, :2]
    order = np.argsort(points[:, 0], kind="stable")
    ax.plot(points[order, 0], points[order, 1], marker="o", ms=5, color=_FRONT, lw=1.2,
            mec="white", mew=0.6, label=f"non-dominated ({len(front):,})",
            zorder=_FRONT_Z, rasterized=len(front) > RASTER_POINTS)  # fmt: skip
    words = {"max": "larger is better", "min": "smaller is better"}
    ax.set_title(f"x: {words[goals[0]]}; y: {words[goals[1]]}", fontsize=9.5, color="0.3")
    ax.set_xlabel(labels[0], fontsize=10)
    ax.set_ylabel(labels[1], fontsize=10)
    ax.grid(alpha=0.3)
    # The legend keeps the study's designs together (cloud, front), the paper's after them.
    handles, names = ax.get_legend_handles_labels()
    listed = [0, len(names) - 1, *range(1, len(names) - 1)]
    fig.legend([handles[i] for i in listed], [names[i] for i in listed],
               loc="outside lower center", ncols=2, fontsize=9, frameon=False)  # fmt: skip
    fig.suptitle(title, fontsize=12, fontweight="bold")
    return fig
