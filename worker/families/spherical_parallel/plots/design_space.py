"""Design-space figures for spherical parallel manipulators (Bai 2010, Figs 5-6).

The sub-design spaces of eq 19 in the alpha1-alpha2 plane (Fig. 5) and the conditioning
index over one of them (Fig. 6). Angles in degrees; conventions as in
:mod:`worker.families.spherical_parallel.plots.conditioning`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from matplotlib import colormaps
from matplotlib.cm import ScalarMappable
from matplotlib.colors import ListedColormap, Normalize
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Polygon
from numpy.typing import ArrayLike

from worker.common.figures import (
    bad_figure_argument,
    contour_labels,
    dimensionless,
    freeze_layout,
    plain_text,
)
from worker.families.spherical_parallel.plots.conditioning import NO_SOLUTION_COLOR, FloatArray

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes

__all__ = [
    "FLAT_RANGE",
    "DesignMarker",
    "SubDesignSpace",
    "design_space_figure",
    "index_distribution_figure",
    "rectangle_corners",
]

_LEGEND_LIMIT = 10  # more sub-design spaces than this: a colour bar over beta instead
#: An index map varying by less than this (relative) is drawn flat, without contours.
FLAT_RANGE = 1e-6
_MARKER_STYLES = {
    "optimum": {"marker": "o", "ms": 9, "mfc": "white", "mec": "black", "mew": 1.6},
    "twin": {"marker": "D", "ms": 7, "mfc": "none", "mec": "#d1495b", "mew": 1.4, "ls": "none"},
    "paper": {"marker": "D", "ms": 7, "mfc": "#d1495b", "mec": "white", "mew": 1.0},
    "grid best": {"marker": "o", "ms": 8, "mfc": "white", "mec": "black", "mew": 1.3},
}


@dataclass(frozen=True)
class SubDesignSpace:
    """One beta's rectangle |a1 - a2| <= d1, |a1 + a2 - 180| <= d2 (deg; eq 19)."""

    beta_deg: float
    gamma_deg: float
    d1_deg: float
    d2_deg: float


@dataclass(frozen=True)
class DesignMarker:
    """A design marked in the alpha1-alpha2 plane."""

    alpha1_deg: float
    alpha2_deg: float
    label: str
    kind: Literal["optimum", "twin", "paper", "grid best"] = "optimum"


def rectangle_corners(d1_deg: float, d2_deg: float) -> FloatArray:
    """(4, 2) corners (a1, a2) at (s, t) = (-1, -1), (1, -1), (1, 1), (-1, 1), where
    a1 - a2 = s d1 and a1 + a2 - 180 = t d2."""
    s = np.array([-1.0, 1.0, 1.0, -1.0])
    t = np.array([-1.0, -1.0, 1.0, 1.0])
    return np.column_stack([90.0 + 0.5 * (s * d1_deg + t * d2_deg),
                            90.0 + 0.5 * (t * d2_deg - s * d1_deg)])  # fmt: skip


def _reference_lines(ax: Axes) -> None:
    line = np.array([0.0, 180.0])
    ax.plot(line, line, color="0.6", lw=0.8, ls=(0, (4, 3)), zorder=1)
    ax.plot(line, 180.0 - line, color="0.6", lw=0.8, ls=(0, (4, 3)), zorder=1)


def _markers(ax: Axes, markers: Sequence[DesignMarker]) -> list[Artist]:
    handles: list[Artist] = []
    seen: set[str] = set()
    for m in markers:
        style = dict(_MARKER_STYLES[m.kind])
        style.pop("ls", None)
        ax.plot([m.alpha1_deg], [m.alpha2_deg], ls="none", zorder=6, **style)  # type: ignore[arg-type]
        if m.label not in seen:
            seen.add(m.label)
            handles.append(Line2D([], [], ls="none", label=plain_text(m.label), **style))  # type: ignore[arg-type]
    return handles


def _space_label(space: SubDesignSpace, kind: str) -> str:
    gamma = "" if space.gamma_deg == 0 else rf", $\gamma$ = {space.gamma_deg:g}°"
    return (
        rf"$\beta$ = {space.beta_deg:g}°{gamma}: $|\alpha_1-\alpha_2| \leq$ "
        rf"{space.d1_deg:.4g}°, $|\alpha_1+\alpha_2-180°| \leq$ "
        rf"{space.d2_deg:.4g}°{kind}"
    )


def _draw_space(ax: Axes, space: SubDesignSpace, color: Any, outline_only: bool) -> Artist:
    """One sub-design space (a rectangle, a line or the point (90, 90)); its legend handle."""
    corners = rectangle_corners(space.d1_deg, space.d2_deg)
    fill = (0.0, 0.0, 0.0, 0.0) if outline_only else (*color[:3], 0.12)
    if min(space.d1_deg, space.d2_deg) > 1e-7:
        ax.add_patch(Polygon(corners, closed=True, fc=fill, ec=color,
                             lw=1.0 if outline_only else 1.8, zorder=3))  # fmt: skip
        return Patch(fc=fill, ec=color, lw=1.8, label=_space_label(space, ""))
    if max(space.d1_deg, space.d2_deg) > 1e-7:
        ends = corners[[0, 2]]
        ax.plot(ends[:, 0], ends[:, 1], color=color, lw=3.0, solid_capstyle="round", zorder=4)
        return Line2D([], [], color=color, lw=3.0,
                      label=_space_label(space, " (degenerate: a line)"))  # fmt: skip
    ax.plot([90.0], [90.0], marker="X", ms=10, color=color, zorder=4)
    return Line2D([], [], color=color, lw=0, marker="X", ms=10,
                  label=_space_label(space, " (empty: only (90, 90))"))  # fmt: skip


def _widths_panel(ax: Axes, spaces: Sequence[SubDesignSpace]) -> None:
    """D1 and D2 against beta: where the design space is wide, and where it degenerates."""
    order = np.argsort([s.beta_deg for s in spaces])
    betas = np.array([spaces[k].beta_deg for k in order])
    d1 = np.array([spaces[k].d1_deg for k in order])
    d2 = np.array([spaces[k].d2_deg for k in order])
    ax.plot(betas, d1, color="#1f5fa8", lw=2.0, marker="o", ms=3.5,
            label=r"$D_1 = \cos^{-1}(-f_{min})$: bound on $|\alpha_1-\alpha_2|$")  # fmt: skip
    ax.plot(betas, d2, color="#d1495b", lw=2.0, marker="s", ms=3.5,
            label=r"$D_2 = \cos^{-1}(f_{max})$: bound on $|\alpha_1+\alpha_2-180°|$")  # fmt: skip
    thin = np.minimum(d1, d2) <= 1e-7
    if thin.any():
        ax.plot(betas[thin], np.zeros(int(thin.sum())), ls="none", marker="x", ms=9,
                color="black", label="degenerate (no interior)")  # fmt: skip
    ax.set_xlabel(r"mobile pyramid half-angle $\beta$ [°]", fontsize=11)
    ax.set_ylabel("half-width of the design space [°]", fontsize=11)
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=9, loc="best")
    ax.set_title("half-widths of the rectangles (eq 19)", fontsize=10, color="0.25")


def design_space_figure(
    spaces: Sequence[SubDesignSpace],
    *,
    title: str,
    subtitle: str = "",
    markers: Sequence[DesignMarker] = (),
) -> Figure:
    """The sub-design spaces of eq 19 in the alpha1-alpha2 plane, one per beta (Fig. 5).

    A rectangle of zero width is drawn as a line (degenerate), two zero widths as the
    point (90, 90). Up to 10 spaces get a legend entry each; more are drawn as outlines
    coloured by beta, with a colour bar and a second panel of the half-widths D1, D2
    against beta.
    """
    where = "design_space_figure"
    if not spaces:
        raise bad_figure_argument("spaces", where, "at least one SubDesignSpace", "none")
    if any(not (np.isfinite([s.d1_deg, s.d2_deg]).all() and min(s.d1_deg, s.d2_deg) >= 0)
           for s in spaces):  # fmt: skip
        raise bad_figure_argument("spaces", where, "widths d1_deg, d2_deg finite and >= 0",
                            str([(s.d1_deg, s.d2_deg) for s in spaces]))  # fmt: skip
    many = len(spaces) > _LEGEND_LIMIT
    fig = Figure(figsize=(14.0 if many else 7.6, 7.8), layout="constrained")
    ax = fig.add_subplot(1, 2 if many else 1, 1)
    _reference_lines(ax)
    betas = np.array([s.beta_deg for s in spaces])
    low, high = float(betas.min()), float(betas.max())
    norm = Normalize(low, high if high > low else low + 1.0)
    by_beta = ListedColormap(colormaps["plasma"](np.linspace(0.0, 0.9, 256)))  # no pale yellow
    handles: list[Artist] = []
    for k, space in enumerate(spaces):
        color = by_beta(norm(space.beta_deg)) if many else colormaps["tab10"](k % 10)
        handles.append(_draw_space(ax, space, color, outline_only=many))
    if many:
        handles = []
        fig.colorbar(ScalarMappable(norm, by_beta), ax=ax, shrink=0.7).set_label(
            r"$\beta$ [°]", fontsize=11)  # fmt: skip
        _widths_panel(fig.add_subplot(1, 2, 2), spaces)
    handles += _markers(ax, markers)
    half = max(0.5 * (s.d1_deg + s.d2_deg) for s in spaces)
    points = np.array([[m.alpha1_deg, m.alpha2_deg] for m in markers]).reshape(-1, 2)
    reach = max(half, *(np.abs(points - 90.0).max(axis=1) if points.size else [0.0]))
    view = min(90.0, 10.0 * np.ceil((reach + 8.0) / 10.0))
    ax.set_xlim(90.0 - view, 90.0 + view)
    ax.set_ylim(90.0 - view, 90.0 + view)
    ax.set_aspect("equal")
    ax.set_xlabel(r"base-side link angle $\alpha_1$ [°]", fontsize=11)
    ax.set_ylabel(r"platform-side link angle $\alpha_2$ [°]", fontsize=11)
    ax.grid(alpha=0.25)
    ax.set_title(subtitle, fontsize=10, color="0.25")
    fig.suptitle(title, fontsize=12.5, fontweight="bold")
    handles.append(
        Line2D(
            [],
            [],
            color="0.6",
            lw=0.8,
            ls=(0, (4, 3)),
            label=r"$\alpha_1 = \alpha_2$ and $\alpha_1 + \alpha_2 = 180°$",
        )
    )
    fig.legend(handles=handles, loc="outside lower center", ncols=1, fontsize=9, frameon=False)
    return fig


def index_distribution_figure(
    alpha1_deg: ArrayLike,
    alpha2_deg: ArrayLike,
    values: ArrayLike,
    *,
    title: str,
    subtitle: str = "",
    value_label: str = r"mean$(1/\kappa^2)$ over the workspace samples (eq 28)",
    markers: Sequence[DesignMarker] = (),
) -> Figure:
    """The conditioning index over one sub-design space (the paper's Fig. 6).

    alpha1_deg, alpha2_deg, values: (p, q) node grids spanning the rectangle (NaN: the
    design misses part of the workspace). Contours and the marked designs on top; an index
    flat to :data:`FLAT_RANGE` is drawn in one colour on a scale around its value.
    """
    where = "index_distribution_figure"
    a1, a2 = np.asarray(alpha1_deg, dtype=float), np.asarray(alpha2_deg, dtype=float)
    grid = np.asarray(values, dtype=float)
    if a1.ndim != 2 or min(a1.shape) < 2 or a2.shape != a1.shape or grid.shape != a1.shape:
        raise bad_figure_argument("values", where, "three arrays of one shape (p, q), p, q >= 2",
                            f"shapes {a1.shape}, {a2.shape}, {grid.shape}")  # fmt: skip
    if not (np.isfinite(a1).all() and np.isfinite(a2).all()):
        raise bad_figure_argument("alpha1_deg", where, "finite angles", "non-finite values")
    fig = Figure(figsize=(8.0, 7.4), layout="constrained")
    ax = fig.add_subplot()
    _reference_lines(ax)
    finite = grid[np.isfinite(grid)]
    top = float(finite.max()) if finite.size else 1.0
    bottom = float(finite.min()) if finite.size else 0.0
    varies = top - bottom > FLAT_RANGE * max(abs(top), abs(bottom), 1.0)
    # A flat index (to rounding) gets a readable scale around its value, in one colour.
    pad = 0.0 if varies else max(0.01 * abs(top), 1e-3)
    norm = Normalize(bottom - pad, top + pad)
    cmap = colormaps["viridis"].with_extremes(bad=NO_SOLUTION_COLOR)
    masked = np.ma.masked_invalid(grid)
    ax.pcolormesh(a1, a2, masked, shading="gouraud", cmap=cmap, norm=norm, rasterized=True,
                  zorder=2)  # fmt: skip
    lines = (ax.contour(a1, a2, masked, levels=8, colors="white", linewidths=0.8, zorder=3)
             if finite.size and varies else None)  # fmt: skip
    outline = np.concatenate([a1[0, :], a1[:, -1], a1[-1, ::-1], a1[::-1, 0]])
    outline2 = np.concatenate([a2[0, :], a2[:, -1], a2[-1, ::-1], a2[::-1, 0]])
    ax.plot(outline, outline2, color="black", lw=1.2, zorder=4)
    handles = _markers(ax, markers)
    pad = 0.08 * max(float(np.ptp(a1)), float(np.ptp(a2)), 1.0)
    ax.set_xlim(float(a1.min()) - pad, float(a1.max()) + pad)
    ax.set_ylim(float(a2.min()) - pad, float(a2.max()) + pad)
    ax.set_aspect("equal")
    ax.set_xlabel(r"base-side link angle $\alpha_1$ [°]", fontsize=11)
    ax.set_ylabel(r"platform-side link angle $\alpha_2$ [°]", fontsize=11)
    ax.grid(alpha=0.25)
    ax.set_title(subtitle, fontsize=10, color="0.25")
    bar = fig.colorbar(ScalarMappable(norm, cmap), ax=ax, shrink=0.8)
    bar.set_label(value_label, fontsize=10)
    dimensionless(bar.ax.yaxis)
    fig.suptitle(title, fontsize=12.5, fontweight="bold")
    handles.append(Line2D([], [], color="black", lw=1.2, label="edge of the design space (eq 19)"))
    if np.isnan(grid).any():
        handles.append(Patch(color=NO_SOLUTION_COLOR, label="misses part of the workspace"))
    fig.legend(handles=handles, loc="outside lower center", ncols=2, fontsize=9, frameon=False)
    if lines is not None:  # last, on the final layout: the gaps stay under the labels
        freeze_layout(fig)
        contour_labels(ax, lines, fmt="%.3f", fontsize=8)
    return fig
