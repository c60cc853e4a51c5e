"""Figures for spherical parallel manipulators over their workspace (Bai 2010, Figs 6-7).

Every function takes numpy arrays (angles in degrees) and returns a
:class:`matplotlib.figure.Figure`; :func:`worker.common.figures.figure_artifacts` turns
it into PNG/SVG bytes. Conventions shared by the spm figures:

* one colour scale for 1/kappa: viridis over [0, 1] (1 = isotropic, 0 = singular);
* NaN marks a pose with no real inverse kinematics and shows as grey.

The design-space figures (Figs 5-6, optimisation starts) are in
:mod:`worker.families.spherical_parallel.plots.design_space`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib import colormaps
from matplotlib.cm import ScalarMappable
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from numpy.typing import ArrayLike, NDArray

from worker.common.figures import bad_figure_argument, contour_labels, dimensionless, plain_text
from worker.families.spherical_parallel.plots.cone_panel import (
    RING_LABEL_ANGLE_DEG,
    disk_image,
    disk_panel,
)

if TYPE_CHECKING:
    from matplotlib.artist import Artist

__all__ = [
    "INVERSE_CONDITION_LABEL",
    "NO_SOLUTION_COLOR",
    "SweepSeries",
    "inverse_condition_map_figure",
    "inverse_condition_scale",
    "torsion_sweep_figure",
]

FloatArray = NDArray[np.float64]

INVERSE_CONDITION_LABEL = r"$1/\kappa$  (eqs 21-22, weighted norm $W = I/3$)"
NO_SOLUTION_COLOR = "#c8c8c8"
_CONTOUR_LEVELS = (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9)
_SERIES_COLORS = ("#1f5fa8", "#d1495b", "#2a9d8f", "#e9a23b")
_SERIES_STYLES = ("-", "--", "-.", ":")
_SAMPLE_MARK: dict[str, Any] = {
    "marker": "o",
    "ms": 3.6,
    "mfc": "white",
    "mec": "black",
    "mew": 0.7,
}


def inverse_condition_scale() -> ScalarMappable:
    """viridis over 1/kappa in [0, 1]; NaN is drawn in :data:`NO_SOLUTION_COLOR`."""
    cmap = colormaps["viridis"].with_extremes(bad=NO_SOLUTION_COLOR)
    return ScalarMappable(norm=Normalize(0.0, 1.0), cmap=cmap)


def _vector(value: ArrayLike, name: str, where: str, minimum: int) -> FloatArray:
    arr = np.asarray(value, dtype=np.float64)
    if arr.ndim != 1 or arr.size < minimum or not np.isfinite(arr).all():
        raise bad_figure_argument(name, where, f"a finite array of shape (n,), n >= {minimum}",
                            f"shape {arr.shape}")  # fmt: skip
    return arr


def _readable_at(radius: float) -> Callable[[float, float], bool]:
    """Where a contour label reads well: off the tilt rings' own labels (along the
    100° spoke, :func:`disk_panel`) and away from the rim, where the contours crowd."""
    spoke = np.radians(RING_LABEL_ANGLE_DEG)

    def readable(x: float, y: float) -> bool:
        along = x * np.cos(spoke) + y * np.sin(spoke)
        across = abs(-x * np.sin(spoke) + y * np.cos(spoke))
        on_ring_labels = along > 0.0 and across < 0.18 * radius
        return not on_ring_labels and math.hypot(x, y) <= 0.88 * radius

    return readable


def inverse_condition_map_figure(
    azimuth_deg: ArrayLike,
    tilt_deg: ArrayLike,
    values: ArrayLike,
    torsions_deg: ArrayLike,
    *,
    title: str,
    subtitle: str = "",
    samples_deg: ArrayLike | None = None,
) -> Figure:
    """1/kappa over the pointing cone, one disk per torsion (the paper's Fig. 6 style).

    azimuth_deg (na,) ascending over [0, 360] is the angle around the disk (psi1, the
    direction the platform axis leans to), tilt_deg (nt,) ascending over [0, T] the
    distance from its centre (psi2); values (k, nt, na);
    torsions_deg (k,) with 1 <= k <= 6. samples_deg (n, 3): the workspace samples, marked
    on the panel whose torsion they share.
    """
    where = "inverse_condition_map_figure"
    azimuth = _vector(azimuth_deg, "azimuth_deg", where, 2)
    tilt = _vector(tilt_deg, "tilt_deg", where, 2)
    torsions = _vector(torsions_deg, "torsions_deg", where, 1)
    grid = np.asarray(values, dtype=np.float64)
    if grid.shape != (torsions.size, tilt.size, azimuth.size) or torsions.size > 6:
        raise bad_figure_argument("values", where, "an array of shape (k, nt, na), 1 <= k <= 6, "
                            f"here ({torsions.size}, {tilt.size}, {azimuth.size})",
                            f"shape {grid.shape}")  # fmt: skip
    marks = np.empty((0, 3)) if samples_deg is None else np.asarray(samples_deg, dtype=float)

    cols = min(3, torsions.size)
    rows = -(-torsions.size // cols)
    fig = Figure(figsize=(4.3 * cols + 1.4, 4.5 * rows + 1.3), layout="constrained")
    scale = inverse_condition_scale()
    # The scale ends at the data's peak (rounded up to 0.1), not at 1: more contrast.
    peak = float(np.nanmax(grid)) if np.isfinite(grid).any() else 1.0
    norm, cmap = (
        Normalize(0.0, min(1.0, max(0.1, math.ceil(10.0 * peak - 1e-9) / 10.0))),
        scale.get_cmap(),
    )
    scale.set_norm(norm)
    radius = float(tilt[-1])
    axes = []
    for index, (torsion, panel) in enumerate(zip(torsions, grid, strict=True)):
        ax = fig.add_subplot(rows, cols, index + 1)
        axes.append(ax)
        image = disk_image(azimuth, tilt, panel)
        disk_panel(ax, image, radius, norm, cmap, NO_SOLUTION_COLOR)
        finite = image[np.isfinite(image)]
        levels = [v for v in _CONTOUR_LEVELS if finite.size and finite.min() < v < finite.max()]
        if levels:
            axis = np.linspace(-radius, radius, image.shape[0])
            lines = ax.contour(axis, axis, np.ma.masked_invalid(image), levels=levels,
                               colors="white", linewidths=0.8, zorder=3)  # fmt: skip
            labelled = [v for v in levels if round(10 * v) % 2 == 0]  # every 0.2: less clutter
            contour_labels(ax, lines, levels=labelled, fmt="%.1f", fontsize=7.5,
                           inline_spacing=2, keep=_readable_at(radius))  # fmt: skip
        here = marks[_same_angle(marks[:, 2], torsion)]
        if here.size:
            angle = np.radians(here[:, 0])
            ax.plot(here[:, 1] * np.cos(angle), here[:, 1] * np.sin(angle), ls="none",
                    zorder=5, **_SAMPLE_MARK)  # fmt: skip
        ax.set_title(rf"torsion $\psi_3$ = {torsion:g}°", fontsize=11)
    bar = fig.colorbar(scale, ax=axes, shrink=0.85, pad=0.03)
    bar.set_label(INVERSE_CONDITION_LABEL, fontsize=10.5)
    dimensionless(bar.ax.yaxis)
    heading = title + (f"\n{subtitle}" if subtitle else "")
    fig.suptitle(heading, fontsize=12.5, fontweight="bold")
    handles: list[Artist] = [
        Line2D([], [], color="0.45", lw=0.8, label=r"contours of $1/\kappa$ every 0.1"),
    ]
    if any(_same_angle(marks[:, 2], t).any() for t in torsions):
        handles.append(Line2D([], [], ls="none", label="workspace samples at this torsion",
                              **_SAMPLE_MARK))  # fmt: skip
    if np.isnan(grid).any():
        handles.append(Patch(color=NO_SOLUTION_COLOR, label="no real inverse kinematics"))
    fig.legend(handles=handles, loc="outside lower center", ncols=len(handles), fontsize=9,
               frameon=False, title=r"angle around the disk: azimuth $\psi_1$;  distance from "
               r"its centre: tilt $\psi_2$ (0 at the centre, T on the rim)",
               title_fontsize=9.5)  # fmt: skip
    return fig


def _same_angle(angles: FloatArray, target: float) -> NDArray[np.bool_]:
    """Which angles (deg) equal ``target`` modulo 360."""
    return np.isclose(np.mod(angles - target + 180.0, 360.0), 180.0, atol=1e-6)


@dataclass(frozen=True, eq=False)
class SweepSeries:
    """One design's 1/kappa along the sweeps: values (s, m), NaN where no real solution."""

    label: str
    values: NDArray[np.float64]


def torsion_sweep_figure(
    psi3_deg: ArrayLike,
    azimuth_tilt_deg: ArrayLike,
    series: Sequence[SweepSeries],
    *,
    title: str,
    tilt_max_deg: float | None = None,
    torsion_range_deg: tuple[float, float] | None = None,
) -> Figure:
    """1/kappa along a torsion turn, one panel per (psi1, psi2) (the paper's Fig. 7).

    psi3_deg (m,); azimuth_tilt_deg (s, 2) with 1 <= s <= 6; each series' values (s, m),
    at most 4 series. torsion_range_deg: a limited prescribed range, shaded.
    """
    where = "torsion_sweep_figure"
    psi3 = _vector(psi3_deg, "psi3_deg", where, 2)
    pairs = np.asarray(azimuth_tilt_deg, dtype=np.float64).reshape(-1, 2)
    if not 1 <= len(pairs) <= 6:
        raise bad_figure_argument("azimuth_tilt_deg", where, "1 to 6 pairs [psi1, psi2]",
                            f"{len(pairs)}")  # fmt: skip
    if not 1 <= len(series) <= 4 or any(
        np.shape(s.values) != (len(pairs), psi3.size) for s in series
    ):
        raise bad_figure_argument("series", where, f"1 to 4 SweepSeries with values of shape "
                            f"({len(pairs)}, {psi3.size})",
                            str([np.shape(s.values) for s in series]))  # fmt: skip

    stacked = np.concatenate([np.asarray(s.values, dtype=float).ravel() for s in series])
    low = float(np.nanmin(stacked)) if np.isfinite(stacked).any() else 0.0
    bottom = max(0.0, low - 0.08 * (1.0 - low) - 0.02)  # one scale for every panel
    fig = Figure(figsize=(9.0, 2.3 * len(pairs) + 1.5), layout="constrained")
    axes = fig.subplots(len(pairs), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (psi1, psi2), row in zip(axes, pairs, range(len(pairs)), strict=True):
        if torsion_range_deg is not None:
            lo, hi = torsion_range_deg
            for shift in (-360.0, 0.0, 360.0):
                ax.axvspan(lo + shift, hi + shift, color="#fde9b8", lw=0, zorder=0)
        for k, item in enumerate(series):
            curve = np.asarray(item.values, dtype=float)[row]
            ax.plot(psi3, curve, color=_SERIES_COLORS[k], ls=_SERIES_STYLES[k], lw=1.8, zorder=3)
        outside = tilt_max_deg is not None and psi2 > tilt_max_deg + 1e-9
        label = rf"$\psi_1$ = {psi1:g}°, $\psi_2$ = {psi2:.4g}°"
        ax.set_title(label + ("  (outside the prescribed cone)" if outside else ""),
                     fontsize=10, loc="left")  # fmt: skip
        ax.set_ylim(bottom, 1.0)
        ax.set_ylabel(r"$1/\kappa$ [-]", fontsize=11)
        ax.grid(alpha=0.3)
        ax.tick_params(labelsize=9)
    axes[-1].set_xlim(float(psi3[0]), float(psi3[-1]))
    axes[-1].set_xticks(np.arange(float(psi3[0]), float(psi3[-1]) + 1e-9, 60.0))
    axes[-1].set_xlabel(r"torsion $\psi_3$ [°]", fontsize=11)
    fig.suptitle(title, fontsize=12.5, fontweight="bold")
    handles: list[Artist] = [
        Line2D([], [], color=_SERIES_COLORS[k], ls=_SERIES_STYLES[k], lw=1.8,
               label=plain_text(item.label))
        for k, item in enumerate(series)
    ]  # fmt: skip
    if torsion_range_deg is not None:
        handles.append(Patch(color="#fde9b8", label="prescribed torsion range"))
    if any(np.isnan(np.asarray(s.values, dtype=float)).any() for s in series):
        handles.append(Line2D([], [], ls="none", label="gaps: no real inverse kinematics"))
    sizes = [len(str(h.get_label())) for h in handles]
    ncols = len(handles) if sum(sizes) <= 90 else 2 if max(sizes) <= 55 else 1
    fig.legend(handles=handles, loc="outside lower center", ncols=ncols, fontsize=9.5,
               frameon=False)  # fmt: skip
    return fig
