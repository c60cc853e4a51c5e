"""Figures for 2-DOF planar parallel robots (Huang et al. 2004, Figs 4-9, redrawn).

Every function takes numpy arrays (lengths in ``length_unit``, angles in degrees) and
returns a :class:`matplotlib.figure.Figure`; :func:`worker.common.figures.figure_artifacts`
turns it into PNG/SVG bytes.  Conventions shared by all figures:

* grids: ``x`` (nx,), ``y`` (ny,) node coordinates, values (ny, nx); NaN marks a node
  unreachable in the working mode and shows hatched;
* two banded colour scales: viridis over 1/kappa in [0, 1] (bands of 0.05), cividis over
  beta_min in [0°, 90°] (bands of 5°), with labelled contour lines;
* the red line is the boundary of W_kappa0 = {1/kappa >= 1/kappa0}; black squares the
  actuated joints (±e, 0); the white star the isotropic point.

Titles and subtitles are the caller's, mathtext allowed (a caller passes user text
through :func:`worker.common.figures.plain_text`); point labels and the length unit are
shown literally, ``$`` included.  A field that is the same everywhere says why
(``constant_reason``).

This module holds the conditioning-map figures (Figs 4-5); the optimisation's figures
(Figs 7-9 and the rectangle in W_kappa0) are in :mod:`worker.families.planar_parallel.plots.design`,
the shared panel in :mod:`worker.families.planar_parallel.plots.panels`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from worker.common.figures import explained_constant, plain_text
from worker.families.planar_parallel.plots.panels import (
    INVERSE_CONDITION,
    MIN_PRESSURE_ANGLE,
    ColourScale,
    checked_grid,
    checked_overlay,
    colour_bar,
    contour_panel,
    map_figure_size,
    overlay_legend,
)

__all__ = ["inverse_condition_map_figure", "pressure_angle_map_figure"]


def inverse_condition_map_figure(
    x: ArrayLike,
    y: ArrayLike,
    inverse_condition: ArrayLike,
    *,
    inverse_condition_limit: float | None = None,
    points: ArrayLike | None = None,
    point_labels: Sequence[str] | None = None,
    joints: ArrayLike | None = None,
    isotropic_point: Sequence[float] | None = None,
    title: str,
    subtitle: str = "",
    length_unit: str = "units",
    constant_reason: str | None = None,
    isotropic_line: bool = False,
) -> Figure:
    """Contours of 1/kappa over the workspace with W_kappa0 outlined (the paper's Fig. 4).

    ``inverse_condition`` (ny, nx), NaN where unreachable; W_kappa0 is outlined by the
    contour 1/kappa = ``inverse_condition_limit`` of the map (None: no outline);
    ``points`` (k, 2), labelled ``point_labels`` (default 1, 2, ...).
    """
    return _map_figure(
        "inverse_condition_map_figure", INVERSE_CONDITION, x, y, inverse_condition,
        inverse_condition=inverse_condition, limit=inverse_condition_limit, points=points,
        point_labels=point_labels, joints=joints, isotropic_point=isotropic_point,
        title=title, subtitle=subtitle, length_unit=length_unit,
        constant_reason=constant_reason, isotropic_line=isotropic_line,
    )  # fmt: skip


def pressure_angle_map_figure(
    x: ArrayLike,
    y: ArrayLike,
    min_pressure_angle_deg: ArrayLike,
    *,
    inverse_condition: ArrayLike | None = None,
    inverse_condition_limit: float | None = None,
    points: ArrayLike | None = None,
    point_labels: Sequence[str] | None = None,
    joints: ArrayLike | None = None,
    isotropic_point: Sequence[float] | None = None,
    title: str,
    subtitle: str = "",
    length_unit: str = "units",
    constant_reason: str | None = None,
    isotropic_line: bool = False,
) -> Figure:
    """Contours of beta_min = min(beta_1, beta_2) in degrees (the paper's Fig. 5).

    Same arguments as :func:`inverse_condition_map_figure`, with the minimum pressure
    angle (ny, nx) in degrees in place of 1/kappa; W_kappa0 is outlined on the
    ``inverse_condition`` grid (ny, nx) when it and the limit are given.
    """
    return _map_figure(
        "pressure_angle_map_figure", MIN_PRESSURE_ANGLE, x, y, min_pressure_angle_deg,
        inverse_condition=inverse_condition, limit=inverse_condition_limit, points=points,
        point_labels=point_labels, joints=joints, isotropic_point=isotropic_point,
        title=title, subtitle=subtitle, length_unit=length_unit,
        constant_reason=constant_reason, isotropic_line=isotropic_line,
    )  # fmt: skip


def _map_figure(
    where: str,
    scale: ColourScale,
    x: ArrayLike,
    y: ArrayLike,
    values: ArrayLike,
    *,
    inverse_condition: ArrayLike | None,
    limit: float | None,
    points: ArrayLike | None,
    point_labels: Sequence[str] | None,
    joints: ArrayLike | None,
    isotropic_point: Sequence[float] | None,
    title: str,
    subtitle: str,
    length_unit: str,
    constant_reason: str | None,
    isotropic_line: bool,
) -> Figure:
    grid = checked_grid(x, y, values, where)
    outline = None
    if inverse_condition is not None and limit is not None:
        outline = (checked_grid(x, y, inverse_condition, where), limit)
    outline_label = (
        rf"boundary of $W_{{\kappa 0}}$: $1/\kappa = {limit:g}$" if limit is not None else ""
    )
    overlay = checked_overlay(
        where, outline=outline, outline_label=outline_label, points=points,
        labels=point_labels, joints=joints, isotropic_point=isotropic_point,
        isotropic_line=isotropic_line,
    )  # fmt: skip
    fig = Figure(figsize=map_figure_size(grid, axes_width=6.0), layout="compressed")
    ax = fig.add_subplot()
    unit = plain_text(length_unit)
    contour_panel(ax, grid, scale, overlay, x_label=f"x [{unit}]", y_label=f"y [{unit}]")
    if subtitle:
        ax.set_title(subtitle, fontsize=10, color="0.25")
    colour_bar(ax, scale)
    finite = grid.values[np.isfinite(grid.values)]
    if finite.size and float(np.ptp(finite)) == 0.0:
        explained_constant(ax, constant_reason or f"{finite[0]:g} at every reachable point")
    fig.suptitle(title, fontsize=13, fontweight="bold")
    overlay_legend(fig, overlay, unreachable=bool(np.isnan(grid.values).any()), ncols=3)
    return fig
