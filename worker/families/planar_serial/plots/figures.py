"""Figures for the three-link planar serial arm (Patel & Sobh, Figs 6-12, redrawn).

Every function takes numpy arrays (lengths in ``length_unit``) and returns a
:class:`matplotlib.figure.Figure`; :func:`worker.common.figures.figure_artifacts` turns
it into PNG/SVG bytes.  Conventions shared by all figures:

* grids: ``x`` (nx,), ``y`` (ny,) node coordinates, ``d_z`` (ny, nx); NaN marks an
  unreachable node and shows as the grey background;
* one colour scale: viridis over d_z in [0, 1] (D = d_z / 3, eqs 2-5; see
  docs/methods/planar-serial.md);
* dashed circles: the paper's region boundaries d = l3, l1+l2-l3, l1+l2+l3 (its Fig 8);
  solid red circles: the edges of the exact full-dexterity bands for unlimited joints;
  under joint limits the solid red line is the edge of the map's own d_z = 1 region
  and the unlimited bands are dotted, a reference.

User-supplied text (titles, labels, units) is shown literally, ``$`` included.

The shared panels and drawing helpers live in :mod:`worker.families.planar_serial.plots.panels`,
the input checks in :mod:`worker.families.planar_serial.plots.inputs`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from numpy.typing import ArrayLike, NDArray

from worker.common.figures import bad_figure_argument, dimensionless, plain_text
from worker.families.planar_serial.plots.inputs import FloatArray as FloatArray
from worker.families.planar_serial.plots.inputs import (
    checked_bands,
    checked_labels,
    checked_lengths,
    checked_map,
    checked_overlay,
)
from worker.families.planar_serial.plots.panels import (
    distance_marks,
    figure_legend,
    heatmap_panel,
    mappable,
    shade_regions,
)

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from mpl_toolkits.mplot3d.axes3d import Axes3D

__all__ = [
    "CasePanel",
    "dexterity_heatmap_figure",
    "dexterity_surface_figure",
    "radial_section_figure",
    "synthesis_cases_figure",
]

_DZ_LABEL = r"orientation dexterity $d_z$  ($D = d_z/3$)"
_REGIONS_LABEL = r"region boundaries $d = l_3,\ l_1{+}l_2{-}l_3,\ l_1{+}l_2{+}l_3$"
_BANDS_LABEL = r"full dexterity $d_z = 1$ (unlimited joints)"
_LIMITED_LABEL = r"edge of full dexterity $d_z = 1$ (joint limits included)"
_CURVE_COLOR = "#2c5d8a"
_BAND_FILL = "#fef287"  # viridis' d_z = 1 yellow at 55 % on white, made opaque
_MAX_SURFACE_NODES = 201


def _dz_colourbar(bar: Any) -> None:
    """Label a colour bar of d_z (a fraction of a turn: dimensionless)."""
    bar.set_label(_DZ_LABEL, fontsize=11)
    dimensionless(bar.ax.yaxis)


@dataclass(frozen=True, eq=False)
class CasePanel:
    """One design case of :func:`synthesis_cases_figure` (the paper's Figs 10 and 12).

    ``x`` (nx,), ``y`` (ny,), ``d_z`` (ny, nx) as in :func:`dexterity_heatmap_figure`;
    ``bands``: the exact full-dexterity radii for unlimited joints; ``region_radii`` =
    (l3, l1+l2-l3, l1+l2+l3), circles about ``base`` (the arm's base in the map's
    frame).  Compared by identity, since it holds arrays.
    """

    label: str
    links: tuple[float, float, float]
    x: NDArray[Any]
    y: NDArray[Any]
    d_z: NDArray[Any]
    bands: tuple[tuple[float, float], ...]
    region_radii: tuple[float, float, float]
    joint_limited: bool = False
    base: tuple[float, float] = (0.0, 0.0)


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
    limited_method: str = "exact-events",
) -> Figure:
    """Heat map of d_z over the workspace, seen from above (the paper's Figs 8, 9, 11).

    ``joint_limited`` says ``d_z`` is under joint limits, computed by ``limited_method``
    ('exact-events' or 'orientation-sampling'): the solid red line is then the edge of
    its d_z = 1 region, the unlimited-joint bands dotted, for comparison.
    """
    where = "dexterity_heatmap_figure"
    dmap = checked_map(x, y, d_z, region_radii, bands, where)
    l1, l2, l3 = checked_lengths(links, "links", where, 3)
    overlay = checked_overlay(task_points, task_labels, trajectory, where)

    fig = Figure(figsize=(7.4, 7.6), layout="constrained")
    ax = fig.add_subplot()
    heatmap_panel(ax, dmap, overlay, length_unit, axes_inches=5.2, joint_limited=joint_limited)
    subtitle = f"links $l_1, l_2, l_3$ = {l1:g}, {l2:g}, {l3:g} {plain_text(length_unit)}"
    if joint_limited:
        how = "sampled" if limited_method == "orientation-sampling" else "exact"
        subtitle += f"  ·  $d_z$ {how} under joint limits"
    ax.set_title(subtitle, fontsize=10, color="0.25")
    _dz_colourbar(fig.colorbar(mappable(), ax=ax, shrink=0.82, pad=0.02))
    fig.suptitle(plain_text(title), fontsize=13, fontweight="bold")
    radii = ", ".join(f"{r:g}" for r in dmap.region_radii)
    bands_text = r" $\cup$ ".join(f"[{lo:g}, {hi:g}]" for lo, hi in dmap.bands) or "none"
    figure_legend(fig, [dmap], overlay, f"{_REGIONS_LABEL} = {radii}",
                  f"{_BANDS_LABEL}: {bands_text}", ncols=2,
                  limited_label=_LIMITED_LABEL if joint_limited else None)  # fmt: skip
    return fig


def dexterity_surface_figure(
    x: ArrayLike, y: ArrayLike, d_z: ArrayLike, *, title: str, length_unit: str = "units"
) -> Figure:
    """3-D surface of d_z over the workspace (the paper's Fig 6).

    Grids over 201 nodes a side are strided down to at most 201, so a 2001 x 2001 map
    draws in about a second; the surface is rasterised inside the SVG.
    """
    dmap = checked_map(x, y, d_z, (), (), "dexterity_surface_figure")
    sx = math.ceil(dmap.x.size / _MAX_SURFACE_NODES)
    sy = math.ceil(dmap.y.size / _MAX_SURFACE_NODES)
    xs, ys = dmap.x[::sx], dmap.y[::sy]
    xx, yy = np.meshgrid(xs, ys)
    fig = Figure(figsize=(8.6, 6.4), layout="constrained")
    ax = cast("Axes3D", fig.add_subplot(projection="3d"))
    colours = mappable()
    ax.plot_surface(xx, yy, _drop_rim_to_zero(dmap.d_z[::sy, ::sx]), cmap=colours.get_cmap(),
                    norm=Normalize(0.0, 1.0), rstride=1, cstride=1, linewidth=0, antialiased=False,
                    rasterized=True)  # fmt: skip
    unit = plain_text(length_unit)
    ax.set_xlabel(f"x [{unit}]", fontsize=11, labelpad=8)
    ax.set_ylabel(f"y [{unit}]", fontsize=11, labelpad=8)
    ax.set_zlabel(r"$d_z$", fontsize=11, labelpad=6)
    dimensionless(ax.zaxis)
    ax.set_zlim(0.0, 1.05)
    span = max(float(np.ptp(xs)), float(np.ptp(ys)))
    ax.set_box_aspect((float(np.ptp(xs)) / span, float(np.ptp(ys)) / span, 0.45), zoom=0.98)
    ax.view_init(elev=52, azim=-58)  # high enough to see over the near rim
    ax.tick_params(labelsize=9)
    # The wide pad keeps the colour bar off the z label, which the layout engine misses.
    _dz_colourbar(fig.colorbar(colours, ax=ax, shrink=0.6, pad=0.1))
    fig.suptitle(plain_text(title), fontsize=13, fontweight="bold")
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
    note: str = "",
) -> Figure:
    """d_z against the distance d from the base along one ray (the paper's Fig 7).

    ``distance`` (n,), ``d_z`` (n,), 0 or NaN where the arm cannot reach: the curve
    stops there (it is drawn only where d_z > 0).  The paper's regions 1-4 are shaded and numbered
    above the plot, the full-dexterity bands filled, and task points marked at their
    distances from the base (with unlimited joints d_z depends on d only).  ``note``
    (mathtext allowed) is written under the title: what a reader needs to read the
    curve, e.g. that sampled values come in steps.
    """
    where = "radial_section_figure"
    dist, dz = np.asarray(distance, dtype=float), np.asarray(d_z, dtype=float)
    if dist.ndim != 1 or dist.size < 2 or not np.isfinite(dist).all():
        raise bad_figure_argument("distance", where, "a finite array of shape (n,), n >= 2",
                            f"shape {dist.shape}")  # fmt: skip
    if dz.shape != dist.shape:
        raise bad_figure_argument(
            "d_z", where, f"an array of shape {dist.shape}", f"shape {dz.shape}"
        )
    radii = checked_lengths(region_radii, "region_radii", where, 3, signed=True)
    band_list = checked_bands(bands, where)
    marks = checked_lengths(task_distances or (), "task_distances", where, None)
    labels = checked_labels(task_labels, len(marks), where)

    fig = Figure(figsize=(9.0, 5.4), layout="constrained")
    ax = fig.add_subplot()
    # Far task points (out of reach) widen the view rather than fall off it.
    d_end = max(float(dist.max()), radii[2] * 1.08, max(marks, default=0.0) * 1.05)
    ax.set_xlim(0.0, d_end)
    ax.set_ylim(0.0, 1.05)
    shade_regions(ax, radii, d_end)
    for lo, hi in band_list:
        ax.axvspan(lo, hi, ymax=1 / 1.05, color=_BAND_FILL, lw=0, zorder=1)
    # Out of reach the curve stops (no d_z = 0 drawn along the floor beyond the reach).
    ax.plot(dist, np.where(dz > 0.0, dz, np.nan), color=_CURVE_COLOR, lw=2.2, zorder=3)
    distance_marks(ax, marks, labels, d_end)
    ax.set_xlabel(f"distance from the base d along the ray at {angle_deg:g}° "
                  f"[{plain_text(length_unit)}]", fontsize=11)  # fmt: skip
    ax.set_ylabel(r"orientation dexterity $d_z$", fontsize=11)
    right = ax.secondary_yaxis("right", functions=(_dz_to_index, _index_to_dz))
    right.set_ylabel(r"dexterity index $D = d_z/3$", fontsize=11)
    dimensionless(ax.yaxis, right.yaxis)
    ax.tick_params(labelsize=10)
    right.tick_params(labelsize=10)
    if note:  # top right: the curve is falling there, the region labels are above
        ax.text(0.99, 0.97, note, transform=ax.transAxes, ha="right", va="top", fontsize=9,
                color="0.2", wrap=True, bbox={"boxstyle": "round,pad=0.3", "fc": "white",
                                              "ec": "0.75", "alpha": 0.9}, zorder=8)  # fmt: skip
    fig.suptitle(plain_text(title), fontsize=13, fontweight="bold")
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
        raise bad_figure_argument("cases", where, "1 to 3 CasePanel records", f"{len(cases)}")
    maps = [checked_map(c.x, c.y, c.d_z, c.region_radii, c.bands, where, c.base) for c in cases]
    overlay = checked_overlay(task_points, task_labels, trajectory, where)

    fig = Figure(figsize=(4.7 * len(cases) + 1.3, 6.0), layout="constrained")
    axes = [fig.add_subplot(1, len(cases), i + 1) for i in range(len(cases))]
    for ax, case, dmap in zip(axes, cases, maps, strict=True):
        heatmap_panel(ax, dmap, overlay, length_unit, axes_inches=4.2,
                      joint_limited=case.joint_limited)  # fmt: skip
        detail = ("$l_1, l_2, l_3$ = " + ", ".join(f"{v:.4g}" for v in case.links)
                  + f" {plain_text(length_unit)}")  # fmt: skip
        if case.joint_limited:
            detail += " · joint-limited"
        ax.set_title(f"{case.label}\n{detail}", fontsize=11)
    _dz_colourbar(fig.colorbar(mappable(), ax=axes, shrink=0.8, pad=0.015))
    fig.suptitle(plain_text(title), fontsize=13, fontweight="bold")
    limited = any(case.joint_limited for case in cases)
    figure_legend(fig, maps, overlay, _REGIONS_LABEL, _BANDS_LABEL, ncols=3 if limited else 4,
                  limited_label=_LIMITED_LABEL if limited else None)  # fmt: skip
    return fig


# -- figure-specific helpers ---------------------------------------------------------


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


def _dz_to_index(v: ArrayLike) -> ArrayLike:
    return np.asarray(v) / 3.0


def _index_to_dz(v: ArrayLike) -> ArrayLike:
    return np.asarray(v) * 3.0
