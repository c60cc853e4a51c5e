"""The drawing pieces shared by the three-link planar arm's figures.

The heat-map panel (d_z cell-centred on the nodes, region and band circles, base,
trajectory and task points with non-overlapping labels), the legend under the axes,
the radial section's regions and task distances, and the one d_z colour scale.
Conventions as in :mod:`worker.families.planar_serial.plots.figures`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib import colormaps
from matplotlib.cm import ScalarMappable
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.patheffects import withStroke

from worker.common.figures import plain_text
from worker.families.planar_serial.plots.inputs import DexterityMap, FloatArray, Overlay

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes

__all__ = ["distance_marks", "figure_legend", "heatmap_panel", "mappable", "shade_regions"]

_Box = tuple[float, float, float, float]

_UNREACHABLE = "#d9d9d9"
_REGION_COLOR, _BAND_COLOR, _PATH_COLOR = "#1a1a1a", "#e8373f", "#111"
_DASH = (0, (5, 3))
_BAND: dict[str, Any] = {"color": _BAND_COLOR, "lw": 1.6}
_REFERENCE_BAND: dict[str, Any] = {"color": _BAND_COLOR, "lw": 1.1, "ls": (0, (1, 2))}
_HALO = [withStroke(linewidth=3.2, foreground="white")]
# A box, not a halo, behind labels: text drawn through path effects loses its SVG comment.
_LABEL_BOX: dict[str, Any] = {"boxstyle": "round,pad=0.12", "fc": "white", "ec": "none",
                              "alpha": 0.85}  # fmt: skip
_BASE: dict[str, Any] = {"marker": "s", "ms": 7, "color": "black", "mec": "white", "mew": 1.2}
_POINT: dict[str, Any] = {"marker": "o", "ms": 8, "mfc": "white", "mec": "black", "mew": 1.3}
_MARKER_PT = 4.0  # radius of a task-point marker, in points
_LABEL_PT = 11.0  # font size of the task-point labels


# -- the shared heat-map panel -------------------------------------------------------


def heatmap_panel(
    ax: Axes, dmap: DexterityMap, overlay: Overlay, length_unit: str, *, axes_inches: float,
    joint_limited: bool = False,
) -> None:  # fmt: skip
    """d_z cell-centred on the nodes, the region and band circles, base and overlay.

    ``axes_inches`` estimates the drawn panel's size, for placing the task labels.
    ``joint_limited``: the solid red line is the edge of the map's own d_z = 1 region
    and the unlimited-joint bands are drawn dotted, as a reference.  Circles and the
    base marker are centred on ``dmap.base``.
    """
    ax.set_facecolor(_UNREACHABLE)
    cmap, norm = mappable().get_cmap(), Normalize(0.0, 1.0)
    if _is_uniform(dmap.x) and _is_uniform(dmap.y):
        ax.imshow(dmap.d_z, origin="lower", extent=_cell_extent(dmap), cmap=cmap, norm=norm,
                  interpolation="auto", zorder=0)  # fmt: skip
    else:  # rasterised so a fine irregular grid does not become a huge SVG
        ax.pcolormesh(dmap.x, dmap.y, dmap.d_z, shading="nearest", cmap=cmap, norm=norm,
                      rasterized=True, zorder=0)  # fmt: skip
    turn = np.linspace(0.0, 2.0 * np.pi, 721)
    bx, by = dmap.base
    for r in (r for r in dmap.region_radii if r > 0):
        ax.plot(bx + r * np.cos(turn), by + r * np.sin(turn), c=_REGION_COLOR, lw=1, ls=_DASH,
                zorder=2)  # fmt: skip
    band_style = _REFERENCE_BAND if joint_limited else _BAND
    for r in sorted({edge for band in dmap.bands for edge in band if edge > 0}):
        ax.plot(bx + r * np.cos(turn), by + r * np.sin(turn), zorder=3, **band_style)
    if joint_limited:
        _full_dexterity_edge(ax, dmap)
    ax.plot([bx], [by], zorder=6, **_BASE)
    if overlay.trajectory is not None:
        path = overlay.trajectory
        ax.plot(path[:, 0], path[:, 1], color=_PATH_COLOR, lw=1.8, path_effects=_HALO, zorder=4)
    x0, x1, y0, y1 = _view_limits(dmap, overlay)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    if overlay.points.size:
        _task_points(ax, overlay, pt_per_unit=72.0 * axes_inches / max(x1 - x0, y1 - y0))
    ax.set_xlabel(f"x [{plain_text(length_unit)}]", fontsize=11)
    ax.set_ylabel(f"y [{plain_text(length_unit)}]", fontsize=11)
    ax.tick_params(labelsize=10)


def _full_dexterity_edge(ax: Axes, dmap: DexterityMap) -> None:
    """The edge of the nodes with d_z = 1 (to 1e-12), as a solid red contour."""
    full = np.where(np.isnan(dmap.d_z), 0.0, (dmap.d_z >= 1.0 - 1e-12).astype(float))
    if 0.0 < full.mean() < 1.0 and min(full.shape) >= 2:
        ax.contour(dmap.x, dmap.y, full, levels=[0.5], colors=_BAND_COLOR, linewidths=1.6,
                   zorder=3)  # fmt: skip


def _task_points(ax: Axes, overlay: Overlay, *, pt_per_unit: float) -> None:
    """Markers, and each label on the first free side of its point."""
    pts = overlay.points
    ax.plot(pts[:, 0], pts[:, 1], ls="none", zorder=7, **_POINT)
    obstacles = [pts * pt_per_unit]
    if overlay.trajectory is not None:
        obstacles.append(_densify(overlay.trajectory * pt_per_unit, step=2.0))
    offsets = _label_offsets(pts * pt_per_unit, overlay.labels, np.concatenate(obstacles))
    for (px, py), label, offset in zip(pts, overlay.labels, offsets, strict=True):
        ax.annotate(plain_text(label), (px, py), xytext=offset, textcoords="offset points",
                    ha="center", va="center", fontsize=_LABEL_PT, fontweight="bold",
                    bbox=_LABEL_BOX, zorder=8, annotation_clip=False)  # fmt: skip


def _label_offsets(
    points: FloatArray, labels: Sequence[str], obstacles: FloatArray
) -> list[tuple[float, float]]:
    """Offsets of label centres from their points (k, 2), avoiding overlaps.

    Everything is in points (1/72 in).  Eight sides are tried, starting radially
    outward (away from the base); the winner has the fewest obstacles (m, 2) and earlier
    labels in its box.  Text sizes are estimated from the character count.
    """
    placed: list[_Box] = []
    offsets: list[tuple[float, float]] = []
    for (px, py), label in zip(points, labels, strict=True):
        w, h = 0.68 * _LABEL_PT * max(len(label), 1) + 2.0, _LABEL_PT + 1.0
        outward = math.atan2(py, px) if math.hypot(px, py) > 1e-9 else math.pi / 4
        candidates: list[tuple[float, tuple[float, float], _Box]] = []
        for rank, k in enumerate((0, 1, -1, 2, -2, 3, -3, 4)):
            c, s = math.cos(outward + k * math.pi / 4), math.sin(outward + k * math.pi / 4)
            r = _MARKER_PT + 2.5 + abs(c) * w / 2 + abs(s) * h / 2
            cx, cy = px + r * c, py + r * s
            box = (cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2)
            crowd = 10 * sum(_overlap(box, b) for b in placed) + _inside(obstacles, box)
            candidates.append((crowd + 0.01 * rank, (r * c, r * s), box))
        _, offset, box = min(candidates, key=lambda candidate: candidate[0])
        offsets.append(offset)
        placed.append(box)
    return offsets


# -- drawing helpers -----------------------------------------------------------------


def figure_legend(
    fig: Figure, maps: Sequence[DexterityMap], overlay: Overlay, regions_label: str,
    bands_label: str, *, ncols: int, limited_label: str | None = None,
) -> None:  # fmt: skip
    """One legend under the axes, so it never covers a map.

    ``limited_label``: a panel is joint-limited; the solid red line is its own d_z = 1
    edge (so labelled) and ``bands_label`` goes with the dotted reference circles.
    """
    handles: list[Artist] = [
        Line2D([], [], color=_REGION_COLOR, lw=1.0, ls=_DASH, label=regions_label),
    ]
    if limited_label is not None:
        handles.append(Line2D([], [], **_BAND, label=limited_label))
        handles.append(Line2D([], [], **_REFERENCE_BAND, label=bands_label))
    else:
        handles.append(Line2D([], [], **_BAND, label=bands_label))
    handles.append(Line2D([], [], ls="none", label="base", **_BASE))
    if overlay.points.size:
        handles.append(Line2D([], [], ls="none", label="task points", **_POINT))
    if overlay.trajectory is not None:
        handles.append(Line2D([], [], color=_PATH_COLOR, lw=1.8, label="trajectory"))
    if any(np.isnan(m.d_z).any() for m in maps):
        handles.append(Patch(color=_UNREACHABLE, label="unreachable"))
    fig.legend(handles=handles, loc="outside lower center", ncols=ncols, fontsize=9.5,
               frameon=False, columnspacing=1.6)  # fmt: skip


def shade_regions(ax: Axes, radii: tuple[float, ...], d_end: float) -> None:
    """The paper's regions 1-4 (empty ones skipped), numbered in a strip above the plot."""
    edges = np.maximum.accumulate(np.array([0.0, *radii, d_end]))
    for number, (lo, hi) in enumerate(itertools.pairwise(edges), start=1):
        if hi - lo <= 1e-9 * d_end:
            continue
        if number == 4:
            ax.axvspan(lo, hi, facecolor="white", edgecolor="0.6", hatch="///", lw=0, zorder=0)
        elif number % 2:
            ax.axvspan(lo, hi, color="0.93", lw=0, zorder=0)
        text = f"region {number}" if hi - lo > 0.09 * d_end else str(number)
        ax.text((lo + hi) / 2, 1.01, text, transform=ax.get_xaxis_transform(), ha="center",
                va="bottom", fontsize=10, color="0.3")  # fmt: skip
    for r in edges[1:-1]:
        ax.axvline(r, color=_REGION_COLOR, lw=0.9, ls=_DASH, alpha=0.7, zorder=2)


def distance_marks(
    ax: Axes, marks: tuple[float, ...], labels: tuple[str, ...], d_end: float
) -> None:
    """Dotted verticals at the task distances; labels too close together are stacked."""
    row_ends: list[float] = []  # right end of the last label in each row, data units
    box = {"boxstyle": "round,pad=0.2", "fc": "white", "ec": "0.5", "lw": 0.6}
    for d, label in sorted(zip(marks, labels, strict=True)):
        ax.axvline(d, color="0.3", ls=":", lw=1.2, zorder=4)
        half = 0.011 * d_end * (max(len(label), 1) + 1)
        row = next((i for i, end in enumerate(row_ends) if d - half > end), len(row_ends))
        row_ends[row : row + 1] = [d + half]
        ax.text(d, 0.04 + 0.075 * row, plain_text(label), transform=ax.get_xaxis_transform(),
                ha="center", va="bottom", fontsize=10, fontweight="bold", bbox=box,
                zorder=5)  # fmt: skip


def _view_limits(dmap: DexterityMap, overlay: Overlay) -> _Box:
    """The map's extent (x0, x1, y0, y1), grown to show every task point and the path."""
    x0, x1, y0, y1 = _cell_extent(dmap)
    path = overlay.trajectory if overlay.trajectory is not None else np.empty((0, 2))
    pts = np.concatenate([overlay.points, path])
    pts = pts[np.isfinite(pts).all(axis=1)]
    if pts.size:
        pad = 0.04 * max(x1 - x0, y1 - y0)
        x0, x1 = min(x0, pts[:, 0].min() - pad), max(x1, pts[:, 0].max() + pad)
        y0, y1 = min(y0, pts[:, 1].min() - pad), max(y1, pts[:, 1].max() + pad)
    return float(x0), float(x1), float(y0), float(y1)


def _cell_extent(dmap: DexterityMap) -> _Box:
    """Outer edges (x0, x1, y0, y1) of the cells centred on the nodes."""
    hx = (dmap.x[-1] - dmap.x[0]) / (dmap.x.size - 1) / 2
    hy = (dmap.y[-1] - dmap.y[0]) / (dmap.y.size - 1) / 2
    return dmap.x[0] - hx, dmap.x[-1] + hx, dmap.y[0] - hy, dmap.y[-1] + hy


def _is_uniform(v: FloatArray) -> bool:
    step = np.diff(v)
    return bool(np.allclose(step, step[0], rtol=1e-6, atol=0.0))


def _densify(path: FloatArray, *, step: float) -> FloatArray:
    """Points along a polyline (m, 2), at most ``step`` apart."""
    path = path[np.isfinite(path).all(axis=1)]
    if len(path) < 2:
        return path
    along = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(path, axis=0).T))])
    t = np.linspace(0.0, along[-1], int(along[-1] / step) + 2)
    return np.column_stack([np.interp(t, along, path[:, 0]), np.interp(t, along, path[:, 1])])


def _overlap(a: _Box, b: _Box) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def _inside(pts: FloatArray, box: _Box) -> int:
    """How many of the points (m, 2) lie within ``box`` grown by a marker radius."""
    lo = np.array(box[:2]) - _MARKER_PT
    hi = np.array(box[2:]) + _MARKER_PT
    return int(((pts > lo) & (pts < hi)).all(axis=1).sum())


def mappable() -> ScalarMappable:
    """The one colour scale: viridis over [0, 1], NaN transparent (shows the background)."""
    cmap = colormaps["viridis"].with_extremes(bad=(0.0, 0.0, 0.0, 0.0))
    return ScalarMappable(norm=Normalize(0.0, 1.0), cmap=cmap)
