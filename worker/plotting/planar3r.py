"""Figures for the three-link planar serial arm (Patel & Sobh, Figs 6-12, redrawn).

Every function takes numpy arrays (lengths in ``length_unit``) and returns a
:class:`matplotlib.figure.Figure`; :func:`worker.plotting.render.figure_artifacts` turns
it into PNG/SVG bytes.  Conventions shared by all figures:

* grids: ``x`` (nx,), ``y`` (ny,) node coordinates, ``d_z`` (ny, nx); NaN marks an
  unreachable node and shows as the grey background;
* one colour scale: viridis over d_z in [0, 1] (D = d_z / 3, METHODS.md §1, eqs 2-5);
* dashed circles: the paper's region boundaries d = l3, l1+l2-l3, l1+l2+l3 (its Fig 8);
  solid red circles: the edges of the exact full-dexterity bands for unlimited joints.

User-supplied text (titles, labels, units) is shown literally, ``$`` included.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from matplotlib import colormaps
from matplotlib.cm import ScalarMappable
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.patheffects import withStroke
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes
    from mpl_toolkits.mplot3d.axes3d import Axes3D

__all__ = [
    "CasePanel",
    "dexterity_heatmap_figure",
    "dexterity_surface_figure",
    "radial_section_figure",
    "synthesis_cases_figure",
]

FloatArray = NDArray[np.float64]
_Box = tuple[float, float, float, float]

_DZ_LABEL = r"orientation dexterity $d_z$  ($D = d_z/3$)"
_REGIONS_LABEL = r"region boundaries $d = l_3,\ l_1{+}l_2{-}l_3,\ l_1{+}l_2{+}l_3$"
_BANDS_LABEL = r"full dexterity $d_z = 1$ (unlimited joints)"
_UNREACHABLE = "#d9d9d9"
_REGION_COLOR, _BAND_COLOR, _PATH_COLOR, _CURVE_COLOR = "#1a1a1a", "#e8373f", "#111", "#2c5d8a"
_BAND_FILL = "#fef287"  # viridis' d_z = 1 yellow at 55 % on white, made opaque
_DASH = (0, (5, 3))
_HALO = [withStroke(linewidth=3.2, foreground="white")]
# A box, not a halo, behind labels: text drawn through path effects loses its SVG comment.
_LABEL_BOX: dict[str, Any] = {"boxstyle": "round,pad=0.12", "fc": "white", "ec": "none",
                              "alpha": 0.85}  # fmt: skip
_BASE: dict[str, Any] = {"marker": "s", "ms": 7, "color": "black", "mec": "white", "mew": 1.2}
_POINT: dict[str, Any] = {"marker": "o", "ms": 8, "mfc": "white", "mec": "black", "mew": 1.3}
_MARKER_PT = 4.0  # radius of a task-point marker, in points
_LABEL_PT = 11.0  # font size of the task-point labels
_MAX_SURFACE_NODES = 201


@dataclass(frozen=True, eq=False)
class CasePanel:
    """One design case of :func:`synthesis_cases_figure` (the paper's Figs 10 and 12).

    ``x`` (nx,), ``y`` (ny,), ``d_z`` (ny, nx) as in :func:`dexterity_heatmap_figure`;
    ``bands``: the exact full-dexterity radii for unlimited joints; ``region_radii`` =
    (l3, l1+l2-l3, l1+l2+l3).  Compared by identity, since it holds arrays.
    """

    label: str
    links: tuple[float, float, float]
    x: NDArray[Any]
    y: NDArray[Any]
    d_z: NDArray[Any]
    bands: tuple[tuple[float, float], ...]
    region_radii: tuple[float, float, float]
    joint_limited: bool = False


@dataclass(frozen=True)
class _Map:
    """A validated map: ascending ``x`` (nx,), ``y`` (ny,), ``d_z`` (ny, nx), circles."""

    x: FloatArray
    y: FloatArray
    d_z: FloatArray
    region_radii: tuple[float, ...]
    bands: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class _Overlay:
    """Drawn over every map: task points (k, 2) with their labels, a trajectory (m, 2)."""

    points: FloatArray
    labels: tuple[str, ...]
    trajectory: FloatArray | None


# -- public figures ------------------------------------------------------------------


def dexterity_heatmap_figure(
    x: ArrayLike,
    y: ArrayLike,
    d_z: ArrayLike,
    *,
    links: Sequence[float],
    region_radii: Sequence[float],
    bands: Sequence[tuple[float, float]],
    task_points: ArrayLike | None = None,
    task_labels: Sequence[str] | None = None,
    trajectory: ArrayLike | None = None,
    title: str,
    length_unit: str = "units",
    joint_limited: bool = False,
) -> Figure:
    """Heat map of d_z over the workspace, seen from above (the paper's Figs 8, 9, 11).

    ``joint_limited`` says ``d_z`` was sampled under joint limits; the red circles still
    show the unlimited-joint bands, for comparison.
    """
    where = "dexterity_heatmap_figure"
    dmap = _map(x, y, d_z, region_radii, bands, where)
    l1, l2, l3 = _lengths(links, "links", where, 3)
    overlay = _overlay(task_points, task_labels, trajectory, where)

    fig = Figure(figsize=(7.4, 7.6), layout="constrained")
    ax = fig.add_subplot()
    _heatmap_panel(ax, dmap, overlay, length_unit, axes_inches=5.2)
    subtitle = f"links $l_1, l_2, l_3$ = {l1:g}, {l2:g}, {l3:g} {_plain(length_unit)}"
    if joint_limited:
        subtitle += "  ·  $d_z$ sampled under joint limits"
    ax.set_title(subtitle, fontsize=10, color="0.25")
    fig.colorbar(_mappable(), ax=ax, shrink=0.82, pad=0.02).set_label(_DZ_LABEL, fontsize=11)
    fig.suptitle(_plain(title), fontsize=13, fontweight="bold")
    radii = ", ".join(f"{r:g}" for r in dmap.region_radii)
    bands_text = r" $\cup$ ".join(f"[{lo:g}, {hi:g}]" for lo, hi in dmap.bands) or "none"
    _figure_legend(fig, [dmap], overlay, f"{_REGIONS_LABEL} = {radii}",
                   f"{_BANDS_LABEL}: {bands_text}", ncols=2)  # fmt: skip
    return fig


def dexterity_surface_figure(
    x: ArrayLike, y: ArrayLike, d_z: ArrayLike, *, title: str, length_unit: str = "units"
) -> Figure:
    """3-D surface of d_z over the workspace (the paper's Fig 6).

    Grids over 201 nodes a side are strided down to at most 201, so a 2001 x 2001 map
    draws in about a second; the surface is rasterised inside the SVG.
    """
    dmap = _map(x, y, d_z, (), (), "dexterity_surface_figure")
    sx = math.ceil(dmap.x.size / _MAX_SURFACE_NODES)
    sy = math.ceil(dmap.y.size / _MAX_SURFACE_NODES)
    xs, ys = dmap.x[::sx], dmap.y[::sy]
    xx, yy = np.meshgrid(xs, ys)
    fig = Figure(figsize=(8.6, 6.4), layout="constrained")
    ax = cast("Axes3D", fig.add_subplot(projection="3d"))
    colours = _mappable()
    ax.plot_surface(xx, yy, _drop_rim_to_zero(dmap.d_z[::sy, ::sx]), cmap=colours.get_cmap(),
                    norm=Normalize(0.0, 1.0), rstride=1, cstride=1, linewidth=0, antialiased=False,
                    rasterized=True)  # fmt: skip
    unit = _plain(length_unit)
    ax.set_xlabel(f"x [{unit}]", fontsize=11, labelpad=8)
    ax.set_ylabel(f"y [{unit}]", fontsize=11, labelpad=8)
    ax.set_zlabel(r"$d_z$", fontsize=11, labelpad=6)
    ax.set_zlim(0.0, 1.05)
    span = max(float(np.ptp(xs)), float(np.ptp(ys)))
    ax.set_box_aspect((float(np.ptp(xs)) / span, float(np.ptp(ys)) / span, 0.45), zoom=0.98)
    ax.view_init(elev=32, azim=-58)
    ax.tick_params(labelsize=9)
    # The wide pad keeps the colour bar off the z label, which the layout engine misses.
    fig.colorbar(colours, ax=ax, shrink=0.6, pad=0.1).set_label(_DZ_LABEL, fontsize=11)
    fig.suptitle(_plain(title), fontsize=13, fontweight="bold")
    return fig


def radial_section_figure(
    distance: ArrayLike,
    d_z: ArrayLike,
    *,
    region_radii: Sequence[float],
    bands: Sequence[tuple[float, float]],
    task_distances: Sequence[float] | None = None,
    task_labels: Sequence[str] | None = None,
    title: str,
    length_unit: str = "units",
    angle_deg: float = 0.0,
) -> Figure:
    """d_z against the distance d from the base along one ray (the paper's Fig 7).

    ``distance`` (n,), ``d_z`` (n,).  The paper's regions 1-4 are shaded and numbered
    above the plot, the full-dexterity bands filled, and task points marked at their
    distances from the base (with unlimited joints d_z depends on d only).
    """
    where = "radial_section_figure"
    dist, dz = np.asarray(distance, dtype=float), np.asarray(d_z, dtype=float)
    if dist.ndim != 1 or dist.size < 2 or not np.isfinite(dist).all():
        raise _bad_parameter("distance", where, "a finite array of shape (n,), n >= 2",
                             f"shape {dist.shape}")  # fmt: skip
    if dz.shape != dist.shape:
        raise _bad_parameter("d_z", where, f"an array of shape {dist.shape}", f"shape {dz.shape}")
    radii = _lengths(region_radii, "region_radii", where, 3, signed=True)
    band_list = _bands(bands, where)
    marks = _lengths(task_distances or (), "task_distances", where, None)
    labels = _labels(task_labels, len(marks), where)

    fig = Figure(figsize=(9.0, 5.4), layout="constrained")
    ax = fig.add_subplot()
    d_end = max(float(dist.max()), radii[2] * 1.08)
    ax.set_xlim(0.0, d_end)
    ax.set_ylim(0.0, 1.05)
    _shade_regions(ax, radii, d_end)
    for lo, hi in band_list:
        ax.axvspan(lo, hi, ymax=1 / 1.05, color=_BAND_FILL, lw=0, zorder=1)
    ax.plot(dist, dz, color=_CURVE_COLOR, lw=2.2, zorder=3)
    _distance_marks(ax, marks, labels, d_end)
    ax.set_xlabel(f"distance from the base d along the ray at {angle_deg:g}° "
                  f"[{_plain(length_unit)}]", fontsize=11)  # fmt: skip
    ax.set_ylabel(r"orientation dexterity $d_z$", fontsize=11)
    right = ax.secondary_yaxis("right", functions=(_dz_to_index, _index_to_dz))
    right.set_ylabel(r"dexterity index $D = d_z/3$", fontsize=11)
    ax.tick_params(labelsize=10)
    right.tick_params(labelsize=10)
    fig.suptitle(_plain(title), fontsize=13, fontweight="bold")
    handles: list[Artist] = [
        Line2D([], [], color=_CURVE_COLOR, lw=2.2, label=r"$d_z(d)$"),
        Patch(color=_BAND_FILL, label=_BANDS_LABEL),
        Patch(facecolor="white", edgecolor="0.6", hatch="///", label="region 4: out of reach"),
    ]
    if marks:
        handles.append(Line2D([], [], color="0.3", ls=":", lw=1.2, label="task points"))
    fig.legend(handles=handles, loc="outside lower center", ncols=len(handles), fontsize=9.5,
               frameon=False)  # fmt: skip
    return fig


def synthesis_cases_figure(
    cases: Sequence[CasePanel],
    *,
    task_points: ArrayLike | None,
    task_labels: Sequence[str] | None,
    trajectory: ArrayLike | None,
    title: str,
    length_unit: str = "units",
) -> Figure:
    """1 to 3 heat maps side by side on one colour scale (the paper's Figs 10 and 12)."""
    where = "synthesis_cases_figure"
    if not 1 <= len(cases) <= 3:
        raise _bad_parameter("cases", where, "1 to 3 CasePanel records", f"{len(cases)}")
    maps = [_map(c.x, c.y, c.d_z, c.region_radii, c.bands, where) for c in cases]
    overlay = _overlay(task_points, task_labels, trajectory, where)

    fig = Figure(figsize=(4.7 * len(cases) + 1.3, 6.0), layout="constrained")
    axes = [fig.add_subplot(1, len(cases), i + 1) for i in range(len(cases))]
    for ax, case, dmap in zip(axes, cases, maps, strict=True):
        _heatmap_panel(ax, dmap, overlay, length_unit, axes_inches=4.2)
        detail = "$l_1, l_2, l_3$ = " + ", ".join(f"{v:g}" for v in case.links)
        if case.joint_limited:
            detail += " · joint-limited"
        ax.set_title(f"{_plain(case.label)}\n{detail}", fontsize=11)
    for ax in axes[1:]:
        ax.set_ylabel("")
    fig.colorbar(_mappable(), ax=axes, shrink=0.8, pad=0.015).set_label(_DZ_LABEL, fontsize=11)
    fig.suptitle(_plain(title), fontsize=13, fontweight="bold")
    _figure_legend(fig, maps, overlay, _REGIONS_LABEL, _BANDS_LABEL, ncols=4)
    return fig


# -- the shared heat-map panel -------------------------------------------------------


def _heatmap_panel(
    ax: Axes, dmap: _Map, overlay: _Overlay, length_unit: str, *, axes_inches: float
) -> None:
    """d_z cell-centred on the nodes, the region and band circles, base and overlay.

    ``axes_inches`` estimates the drawn panel's size, for placing the task labels.
    """
    ax.set_facecolor(_UNREACHABLE)
    cmap, norm = _mappable().get_cmap(), Normalize(0.0, 1.0)
    if _is_uniform(dmap.x) and _is_uniform(dmap.y):
        ax.imshow(dmap.d_z, origin="lower", extent=_cell_extent(dmap), cmap=cmap, norm=norm,
                  interpolation="auto", zorder=0)  # fmt: skip
    else:  # rasterised so a fine irregular grid does not become a huge SVG
        ax.pcolormesh(dmap.x, dmap.y, dmap.d_z, shading="nearest", cmap=cmap, norm=norm,
                      rasterized=True, zorder=0)  # fmt: skip
    turn = np.linspace(0.0, 2.0 * np.pi, 721)
    for r in (r for r in dmap.region_radii if r > 0):
        ax.plot(r * np.cos(turn), r * np.sin(turn), c=_REGION_COLOR, lw=1, ls=_DASH, zorder=2)
    for r in sorted({edge for band in dmap.bands for edge in band if edge > 0}):
        ax.plot(r * np.cos(turn), r * np.sin(turn), color=_BAND_COLOR, lw=1.6, zorder=3)
    ax.plot([0.0], [0.0], zorder=6, **_BASE)
    if overlay.trajectory is not None:
        path = overlay.trajectory
        ax.plot(path[:, 0], path[:, 1], color=_PATH_COLOR, lw=1.8, path_effects=_HALO, zorder=4)
    x0, x1, y0, y1 = _view_limits(dmap, overlay)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    if overlay.points.size:
        _task_points(ax, overlay, pt_per_unit=72.0 * axes_inches / max(x1 - x0, y1 - y0))
    ax.set_xlabel(f"x [{_plain(length_unit)}]", fontsize=11)
    ax.set_ylabel(f"y [{_plain(length_unit)}]", fontsize=11)
    ax.tick_params(labelsize=10)


def _task_points(ax: Axes, overlay: _Overlay, *, pt_per_unit: float) -> None:
    """Markers, and each label on the first free side of its point."""
    pts = overlay.points
    ax.plot(pts[:, 0], pts[:, 1], ls="none", zorder=7, **_POINT)
    obstacles = [pts * pt_per_unit]
    if overlay.trajectory is not None:
        obstacles.append(_densify(overlay.trajectory * pt_per_unit, step=2.0))
    offsets = _label_offsets(pts * pt_per_unit, overlay.labels, np.concatenate(obstacles))
    for (px, py), label, offset in zip(pts, overlay.labels, offsets, strict=True):
        ax.annotate(_plain(label), (px, py), xytext=offset, textcoords="offset points",
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


def _figure_legend(
    fig: Figure, maps: Sequence[_Map], overlay: _Overlay, regions_label: str,
    bands_label: str, *, ncols: int,
) -> None:  # fmt: skip
    """One legend under the axes, so it never covers a map."""
    handles: list[Artist] = [
        Line2D([], [], color=_REGION_COLOR, lw=1.0, ls=_DASH, label=regions_label),
        Line2D([], [], color=_BAND_COLOR, lw=1.6, label=bands_label),
        Line2D([], [], ls="none", label="base", **_BASE),
    ]
    if overlay.points.size:
        handles.append(Line2D([], [], ls="none", label="task points", **_POINT))
    if overlay.trajectory is not None:
        handles.append(Line2D([], [], color=_PATH_COLOR, lw=1.8, label="trajectory"))
    if any(np.isnan(m.d_z).any() for m in maps):
        handles.append(Patch(color=_UNREACHABLE, label="unreachable"))
    fig.legend(handles=handles, loc="outside lower center", ncols=ncols, fontsize=9.5,
               frameon=False, columnspacing=1.6)  # fmt: skip


def _shade_regions(ax: Axes, radii: tuple[float, ...], d_end: float) -> None:
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


def _distance_marks(
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
        ax.text(d, 0.04 + 0.075 * row, _plain(label), transform=ax.get_xaxis_transform(),
                ha="center", va="bottom", fontsize=10, fontweight="bold", bbox=box,
                zorder=5)  # fmt: skip


def _view_limits(dmap: _Map, overlay: _Overlay) -> _Box:
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


def _cell_extent(dmap: _Map) -> _Box:
    """Outer edges (x0, x1, y0, y1) of the cells centred on the nodes."""
    hx = (dmap.x[-1] - dmap.x[0]) / (dmap.x.size - 1) / 2
    hy = (dmap.y[-1] - dmap.y[0]) / (dmap.y.size - 1) / 2
    return dmap.x[0] - hx, dmap.x[-1] + hx, dmap.y[0] - hy, dmap.y[-1] + hy


def _is_uniform(v: FloatArray) -> bool:
    step = np.diff(v)
    return bool(np.allclose(step, step[0], rtol=1e-6, atol=0.0))


def _drop_rim_to_zero(d_z: FloatArray) -> FloatArray:
    """Unreachable nodes next to reachable ones set to 0, the exact d_z there.

    The surface then falls to the floor at the workspace boundary instead of ending in
    a ragged edge where the NaN cells are left out.
    """
    unreachable = np.isnan(d_z)
    reachable = np.pad(~unreachable, 1)
    ny, nx = d_z.shape
    near = np.zeros_like(unreachable)
    for dy, dx in itertools.product(range(3), range(3)):
        near |= reachable[dy : dy + ny, dx : dx + nx]
    return np.where(unreachable & near, 0.0, d_z)


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


def _mappable() -> ScalarMappable:
    """The one colour scale: viridis over [0, 1], NaN transparent (shows the background)."""
    cmap = colormaps["viridis"].with_extremes(bad=(0.0, 0.0, 0.0, 0.0))
    return ScalarMappable(norm=Normalize(0.0, 1.0), cmap=cmap)


def _dz_to_index(v: ArrayLike) -> ArrayLike:
    return np.asarray(v) / 3.0


def _index_to_dz(v: ArrayLike) -> ArrayLike:
    return np.asarray(v) * 3.0


# -- input normalisation, once at the public entry -----------------------------------


def _bad_parameter(name: str, where: str, expected: str, got: str) -> ValueError:
    return ValueError(f"The '{name}' parameter of {where} must be {expected}. Got {got} instead.")


def _plain(text: str) -> str:
    """Text shown literally: a user's ``$`` must not start mathtext."""
    return text.replace("$", r"\$")


def _map(
    x: ArrayLike, y: ArrayLike, d_z: ArrayLike, region_radii: Sequence[float],
    bands: Sequence[tuple[float, float]], where: str,
) -> _Map:  # fmt: skip
    xs, ys, dz = (np.asarray(v, dtype=float) for v in (x, y, d_z))
    for name, v in (("x", xs), ("y", ys)):
        step = np.diff(v) if v.ndim == 1 else np.array([np.nan])
        if v.size < 2 or not np.isfinite(v).all() or not (all(step > 0) or all(step < 0)):
            raise _bad_parameter(name, where, "a strictly monotonic finite array of shape (n,),"
                                 " n >= 2", f"shape {v.shape}")  # fmt: skip
    if dz.shape != (ys.size, xs.size):
        raise _bad_parameter("d_z", where, f"an array of shape (ny, nx) = {(ys.size, xs.size)}",
                             f"shape {dz.shape}")  # fmt: skip
    if xs[0] > xs[-1]:
        xs, dz = xs[::-1], dz[:, ::-1]
    if ys[0] > ys[-1]:
        ys, dz = ys[::-1], dz[::-1, :]
    radii = _lengths(region_radii, "region_radii", where, 3 if len(region_radii) else 0,
                     signed=True)  # l1 + l2 - l3 < 0 just means an empty region 2
    return _Map(xs, ys, dz, radii, _bands(bands, where))


def _lengths(
    value: Sequence[float], name: str, where: str, count: int | None, *, signed: bool = False
) -> tuple[float, ...]:
    arr = np.asarray(value, dtype=float)
    wrong_size = arr.ndim != 1 or (count is not None and arr.size != count)
    if wrong_size or not np.isfinite(arr).all() or (not signed and (arr < 0).any()):
        kind = "finite" if signed else "finite non-negative"
        expected = f"{'a list of' if count is None else count} {kind} lengths"
        raise _bad_parameter(name, where, expected, repr(value))
    return tuple(float(v) for v in arr)


def _bands(value: Sequence[tuple[float, float]], where: str) -> tuple[tuple[float, float], ...]:
    arr = np.asarray(value, dtype=float)
    arr = arr.reshape(0, 2) if arr.size == 0 else arr
    if arr.ndim != 2 or arr.shape[1] != 2 or not np.isfinite(arr).all() or (
        (arr[:, 0] < 0).any() or (arr[:, 0] > arr[:, 1]).any()
    ):
        raise _bad_parameter("bands", where, "a list of (lo, hi) radius pairs with "
                             "0 <= lo <= hi", repr(value))  # fmt: skip
    return tuple((float(lo), float(hi)) for lo, hi in arr)


def _labels(labels: Sequence[str] | None, count: int, where: str) -> tuple[str, ...]:
    """The given labels, or A, B, C, … when there are none."""
    if labels is None:
        return tuple(chr(ord("A") + i) if i < 26 else f"P{i + 1}" for i in range(count))
    if isinstance(labels, str) or len(labels) != count:
        raise _bad_parameter("task_labels", where, f"a list of {count} labels, one per point",
                             repr(labels))  # fmt: skip
    return tuple(str(label) for label in labels)


def _overlay(
    task_points: ArrayLike | None, task_labels: Sequence[str] | None,
    trajectory: ArrayLike | None, where: str,
) -> _Overlay:  # fmt: skip
    pts = np.asarray([] if task_points is None else task_points, dtype=float)
    pts = pts.reshape(0, 2) if pts.size == 0 else pts
    if pts.ndim != 2 or pts.shape[1] != 2 or not np.isfinite(pts).all():
        raise _bad_parameter("task_points", where, "a finite array of shape (k, 2)",
                             f"shape {pts.shape}")  # fmt: skip
    path = None if trajectory is None else np.asarray(trajectory, dtype=float)
    if path is not None and (path.ndim != 2 or path.shape[1] != 2 or len(path) < 2):
        raise _bad_parameter("trajectory", where, "an array of shape (m, 2), m >= 2",
                             f"shape {path.shape}")  # fmt: skip
    return _Overlay(pts, _labels(task_labels, len(pts), where), path)
