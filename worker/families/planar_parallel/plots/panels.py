"""The drawing pieces shared by the 2-DOF parallel robots' figures (Huang et al. 2004).

A contour panel (filled bands of 1/kappa or beta_min, labelled contour lines, the
W_kappa0 outline, the actuated joints, the isotropic point, given points and an optional
rectangle), the two colour scales, and the input checks run once at each public entry.
Conventions as in :mod:`worker.families.planar_parallel.plots.conditioning`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib import colormaps
from matplotlib.cm import ScalarMappable
from matplotlib.colors import BoundaryNorm
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.patches import Rectangle as RectanglePatch
from matplotlib.patheffects import withStroke
from numpy.typing import ArrayLike, NDArray

from worker.common.figures import bad_figure_argument, contour_labels, dimensionless, plain_text

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = [
    "INVERSE_CONDITION",
    "MIN_PRESSURE_ANGLE",
    "ColourScale",
    "FloatArray",
    "MapOverlay",
    "ScalarGrid",
    "checked_grid",
    "checked_overlay",
    "contour_panel",
    "map_figure_size",
    "overlay_legend",
]

FloatArray = NDArray[np.float64]

#: Unreachable points: white, hatched in grey (no band of viridis or cividis is hatched).
_UNREACHABLE_FILL: dict[str, Any] = {"facecolor": "white", "edgecolor": "0.72", "hatch": "////",
                                     "lw": 0.0}  # fmt: skip
_OUTLINE = "#e8373f"
_RECTANGLE = "#1f5fbf"
_HALO = [withStroke(linewidth=4.0, foreground="white")]
_JOINT: dict[str, Any] = {"marker": "s", "ms": 7, "color": "black", "mec": "white", "mew": 1.2}
_ISOTROPIC_LINE: dict[str, Any] = {
    "color": "white",
    "lw": 2.0,
    "ls": (0, (6, 3)),
    "path_effects": [withStroke(linewidth=3.6, foreground="black")],
}
_ISOTROPIC: dict[str, Any] = {"marker": "*", "ms": 13, "color": "white", "mec": "black",
                              "mew": 1.0}  # fmt: skip
_POINT: dict[str, Any] = {"marker": "o", "ms": 7, "mfc": "white", "mec": "black", "mew": 1.3}
_LABEL_BOX: dict[str, Any] = {"boxstyle": "round,pad=0.12", "fc": "white", "ec": "none",
                              "alpha": 0.85}  # fmt: skip
#: Grids finer than this (nodes a side) are strided down for drawing; the data keep all.
MAX_DRAWN_NODES = 601


@dataclass(frozen=True)
class ColourScale:
    """A banded colour scale: filled ``levels``, labelled ``line_levels``."""

    label: str
    cmap: str
    levels: tuple[float, ...]
    line_levels: tuple[float, ...]
    line_format: str
    #: A pure number (its colour bar needs no unit).
    dimensionless: bool = False

    def restricted(self, low: float, high: float) -> ColourScale:
        """The scale over the bands that hold [low, high] only (more contrast on a narrow
        range), its bands halved until there are at least 8 of them."""
        levels = np.asarray(self.levels)
        lo = levels[max(int(np.searchsorted(levels, low, side="right")) - 1, 0)]
        hi = levels[min(int(np.searchsorted(levels, high, side="left")), levels.size - 1)]
        if not np.isfinite(low + high) or hi <= lo:
            return self
        step = float(levels[1] - levels[0])
        while (hi - lo) / step < 8 and step > 1e-3 * (levels[-1] - levels[0]):
            step /= 2
        count = round((hi - lo) / step)
        fine = tuple(np.round(np.linspace(lo, hi, count + 1), 10).tolist())
        lines = tuple(v for v in fine[1:-1:2] if v not in (lo, hi))
        return ColourScale(self.label, self.cmap, fine, lines, self.line_format, self.dimensionless)

    def mappable(self) -> ScalarMappable:
        """The scale for a colour bar: one colour per band, NaN transparent."""
        cmap = colormaps[self.cmap].with_extremes(bad=(0.0, 0.0, 0.0, 0.0))
        return ScalarMappable(norm=BoundaryNorm(self.levels, cmap.N), cmap=cmap)


INVERSE_CONDITION = ColourScale(
    label=r"conditioning index $1/\kappa$ (eq 7)",
    cmap="viridis",
    levels=tuple(np.round(np.linspace(0.0, 1.0, 21), 10).tolist()),
    line_levels=(0.2, 0.4, 0.6, 0.8, 0.9),
    line_format="%.3g",
    dimensionless=True,
)
MIN_PRESSURE_ANGLE = ColourScale(
    label=r"minimum pressure angle $\beta_{\min}$ (eq 15) [°]",
    cmap="cividis",
    levels=tuple(float(v) for v in range(0, 95, 5)),
    line_levels=(15.0, 30.0, 45.0, 60.0, 75.0),
    line_format="%g°",
)


@dataclass(frozen=True)
class ScalarGrid:
    """A validated map: ascending ``x`` (nx,), ``y`` (ny,), ``values`` (ny, nx), NaN outside."""

    x: FloatArray
    y: FloatArray
    values: FloatArray

    def strided(self) -> ScalarGrid:
        """At most :data:`MAX_DRAWN_NODES` nodes a side, for drawing."""
        sx = math.ceil(self.x.size / MAX_DRAWN_NODES)
        sy = math.ceil(self.y.size / MAX_DRAWN_NODES)
        return ScalarGrid(self.x[::sx], self.y[::sy], self.values[::sy, ::sx])


@dataclass(frozen=True)
class MapOverlay:
    """Drawn over a map: the W_kappa0 outline, points with labels, the joints, a rectangle.

    ``outline``: (1/kappa grid, limit), outlined by its contour at the limit, which
    holds every part of W_kappa0 the grid resolves; ``rectangle`` is (x0, y0, width,
    height); ``joints`` the actuated joints (m, 2).
    """

    outline: tuple[ScalarGrid, float] | None = None
    outline_label: str = ""
    points: FloatArray | None = None
    labels: tuple[str, ...] = ()
    joints: FloatArray | None = None
    isotropic_point: tuple[float, float] | None = None
    rectangle: tuple[float, float, float, float] | None = None
    rectangle_label: str = ""
    #: Isotropy holds along the whole line y = isotropic_point[1] (the linear drive,
    #: whose 1/kappa does not depend on x): drawn as a line, not a star.
    isotropic_line: bool = False


def checked_grid(x: ArrayLike, y: ArrayLike, values: ArrayLike, where: str) -> ScalarGrid:
    """``x`` (nx,), ``y`` (ny,) strictly monotonic; ``values`` (ny, nx); flipped ascending."""
    xs, ys, vs = (np.asarray(v, dtype=float) for v in (x, y, values))
    for name, v in (("x", xs), ("y", ys)):
        step = np.diff(v) if v.ndim == 1 else np.array([np.nan])
        if v.size < 2 or not np.isfinite(v).all() or not (all(step > 0) or all(step < 0)):
            raise bad_figure_argument(
                name,
                where,
                "a strictly monotonic finite array of shape (n,), n >= 2",
                f"shape {v.shape}",
            )
    if vs.shape != (ys.size, xs.size):
        raise bad_figure_argument(
            "values",
            where,
            f"an array of shape (ny, nx) = {(ys.size, xs.size)}",
            f"shape {vs.shape}",
        )
    if xs[0] > xs[-1]:
        xs, vs = xs[::-1], vs[:, ::-1]
    if ys[0] > ys[-1]:
        ys, vs = ys[::-1], vs[::-1, :]
    return ScalarGrid(xs, ys, vs)


def checked_overlay(
    where: str,
    *,
    outline: tuple[ScalarGrid, float | None] | None = None,
    outline_label: str = "",
    points: ArrayLike | None = None,
    labels: Sequence[str] | None = None,
    joints: ArrayLike | None = None,
    isotropic_point: Sequence[float] | None = None,
    rectangle: Sequence[float] | None = None,
    rectangle_label: str = "",
    isotropic_line: bool = False,
) -> MapOverlay:
    """The overlay's pieces checked: points (k, 2) with k labels (default 1, 2, ...);
    ``outline`` = (1/kappa grid, limit), nothing drawn when the limit is None."""
    pts = None
    point_labels: tuple[str, ...] = ()
    if points is not None:
        pts = np.asarray(points, dtype=float).reshape(-1, 2) if np.size(points) else None
        if pts is not None and not np.isfinite(pts).all():
            raise bad_figure_argument(
                "points", where, "a finite array of shape (k, 2)", f"shape {np.shape(points)}"
            )
        count = 0 if pts is None else len(pts)
        if labels is None:
            point_labels = tuple(str(i + 1) for i in range(count))
        elif isinstance(labels, str) or len(labels) != count:
            raise bad_figure_argument(
                "labels", where, f"a list of {count} labels, one per point", repr(labels)
            )
        else:
            point_labels = tuple(str(label) for label in labels)
    joint_xy = None if joints is None else np.asarray(joints, dtype=float).reshape(-1, 2)
    iso = None if isotropic_point is None else _pair(isotropic_point, "isotropic_point", where)
    rect = None
    if rectangle is not None:
        rect_arr = np.asarray(rectangle, dtype=float)
        if rect_arr.shape != (4,) or not np.isfinite(rect_arr).all() or (rect_arr[2:] <= 0).any():
            raise bad_figure_argument(
                "rectangle",
                where,
                "(x0, y0, width, height) with positive width and height",
                repr(rectangle),
            )
        rect = (float(rect_arr[0]), float(rect_arr[1]), float(rect_arr[2]), float(rect_arr[3]))
    checked_outline: tuple[ScalarGrid, float] | None = None
    if outline is not None:
        grid, level = outline
        if level is not None:
            if not (math.isfinite(level) and 0.0 < level <= 1.0):
                raise bad_figure_argument(
                    "inverse_condition_limit", where, "a limit in (0, 1]", repr(level)
                )
            checked_outline = (grid, float(level))
    return MapOverlay(
        outline=checked_outline,
        outline_label=outline_label,
        points=pts,
        labels=point_labels,
        joints=joint_xy,
        isotropic_point=iso,
        rectangle=rect,
        rectangle_label=rectangle_label,
        isotropic_line=isotropic_line,
    )


def _pair(value: Sequence[float], name: str, where: str) -> tuple[float, float]:
    arr = np.asarray(value, dtype=float)
    if arr.shape != (2,) or not np.isfinite(arr).all():
        raise bad_figure_argument(name, where, "a finite (x, y) pair", repr(value))
    return float(arr[0]), float(arr[1])


def contour_panel(
    ax: Axes,
    grid: ScalarGrid,
    scale: ColourScale,
    overlay: MapOverlay,
    *,
    x_label: str,
    y_label: str,
    view: tuple[float, float, float, float] | None = None,
) -> None:
    """Filled bands, labelled contour lines, then the overlay; equal axes, hatched where
    unreachable (no colour of either scale looks like it)."""
    ax.patch.set(facecolor="white", edgecolor=_UNREACHABLE_FILL["edgecolor"],
                 hatch=_UNREACHABLE_FILL["hatch"], linewidth=0.0)  # fmt: skip

    drawn = grid.strided()
    mappable = scale.mappable()
    if np.isfinite(drawn.values).any():
        filled = ax.contourf(drawn.x, drawn.y, drawn.values, levels=scale.levels,
                             cmap=mappable.get_cmap(), norm=mappable.norm, zorder=0)  # fmt: skip
        filled.set_rasterized(True)  # a fine grid would make a huge SVG
        lines = ax.contour(drawn.x, drawn.y, drawn.values, levels=scale.line_levels,
                           colors="white", linewidths=0.8, alpha=0.9, zorder=1)  # fmt: skip
        view_box = view if view is not None else _extent(grid)
        ax.set_xlim(*view_box[:2])
        ax.set_ylim(*view_box[2:])
        contour_labels(ax, lines, fmt=scale.line_format, fontsize=8, inline=True)
    if overlay.outline is not None:
        values, level = overlay.outline
        shown = values.strided()
        if np.nanmax(shown.values, initial=-np.inf) >= level:
            zeroed = np.nan_to_num(shown.values, nan=0.0)  # 1/kappa -> 0 at the reach
            lines = ax.contour(shown.x, shown.y, zeroed, levels=[level], colors=_OUTLINE,
                               linewidths=2.2, zorder=3)  # fmt: skip
            lines.set(path_effects=_HALO)
    if overlay.rectangle is not None:
        x0, y0, w, h = overlay.rectangle
        ax.add_patch(RectanglePatch((x0, y0), w, h, fill=False, ec=_RECTANGLE, lw=2.2,
                                    path_effects=_HALO, zorder=4))  # fmt: skip
    if overlay.joints is not None:
        ax.plot(overlay.joints[:, 0], overlay.joints[:, 1], ls="none", zorder=6, **_JOINT)
    if overlay.isotropic_point is not None and overlay.isotropic_line:
        ax.axhline(overlay.isotropic_point[1], zorder=6, **_ISOTROPIC_LINE)
    elif overlay.isotropic_point is not None:
        ax.plot(*overlay.isotropic_point, ls="none", zorder=6, **_ISOTROPIC)
    x0, x1, y0, y1 = view if view is not None else _extent(grid)
    if overlay.points is not None:
        pts = overlay.points
        ax.plot(pts[:, 0], pts[:, 1], ls="none", zorder=7, **_POINT)
        for (px, py), label in zip(pts, overlay.labels, strict=True):
            if x0 <= px <= x1 and y0 <= py <= y1:  # a label far outside would wreck the layout
                ax.annotate(plain_text(label), (px, py), xytext=(7, 7),
                            textcoords="offset points", fontsize=10, fontweight="bold",
                            bbox=_LABEL_BOX, zorder=8, annotation_clip=False)  # fmt: skip
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel(x_label, fontsize=11)
    ax.set_ylabel(y_label, fontsize=11)
    ax.tick_params(labelsize=10)


def map_figure_size(
    extent: ScalarGrid | tuple[float, float, float, float], *, axes_width: float
) -> tuple[float, float]:
    """(width, height) in inches fitting one map (a grid or an (x0, x1, y0, y1) view) of
    ``axes_width`` inches at equal scale, with room for the colour bar, titles and the
    legend below."""
    x0, x1, y0, y1 = _extent(extent) if isinstance(extent, ScalarGrid) else extent
    height = axes_width * min(max((y1 - y0) / (x1 - x0), 0.4), 1.6)
    return axes_width + 2.0, height + 2.3


def _extent(grid: ScalarGrid) -> tuple[float, float, float, float]:
    return float(grid.x[0]), float(grid.x[-1]), float(grid.y[0]), float(grid.y[-1])


def colour_bar(ax: Axes, scale: ColourScale, label: str | None = None, ticks: int = 2) -> Any:
    """The scale's colour bar beside ``ax``, with every ``ticks``-th band edge labelled.
    In a figure with the "compressed" layout (made for equal-aspect maps) the bar is as
    tall as the axes."""
    fig = ax.get_figure()
    assert fig is not None, "an axes of a figure"
    bar = fig.colorbar(scale.mappable(), ax=ax, pad=0.02, aspect=30)
    bar.set_label(label or scale.label, fontsize=11)
    bar.set_ticks(scale.levels[::ticks])
    if scale.dimensionless:
        dimensionless(bar.ax.yaxis)
    return bar


def overlay_legend(fig: Figure, overlay: MapOverlay, *, unreachable: bool, ncols: int) -> None:
    """One legend under the axes naming every overlay element that is drawn."""
    handles: list[Artist] = []
    if overlay.outline is not None:
        handles.append(Line2D([], [], color=_OUTLINE, lw=2.2, label=overlay.outline_label))
    if overlay.rectangle is not None:
        handles.append(Line2D([], [], color=_RECTANGLE, lw=2.2, label=overlay.rectangle_label))
    if overlay.joints is not None:
        handles.append(Line2D([], [], ls="none", label="actuated joints (±e, 0)", **_JOINT))
    if overlay.isotropic_point is not None and overlay.isotropic_line:
        handles.append(Line2D([], [], label=r"isotropic line ($1/\kappa = 1$ at every $x$)",
                              **_ISOTROPIC_LINE))  # fmt: skip
    elif overlay.isotropic_point is not None:
        handles.append(Line2D([], [], ls="none", label=r"isotropic point ($1/\kappa = 1$)",
                              **_ISOTROPIC))  # fmt: skip
    if overlay.points is not None:
        handles.append(Line2D([], [], ls="none", label="given points", **_POINT))
    if unreachable:
        handles.append(Patch(label="unreachable in this working mode", **_UNREACHABLE_FILL))
    if handles:
        fig.legend(handles=handles, loc="outside lower center", ncols=ncols, fontsize=9.5,
                   frameon=False, columnspacing=1.4)  # fmt: skip
