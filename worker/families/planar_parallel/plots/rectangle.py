"""The paper's Fig. 9: 1/kappa and beta_min over the rectangle W_lambda of the optimum
design, in the normalised coordinates x/b, (y + H')/b (Huang et al. 2004).

Re-exported by :mod:`worker.families.planar_parallel.plots.design`; conventions as in
:mod:`worker.families.planar_parallel.plots.conditioning`.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from worker.common.figures import contour_labels, dimensionless
from worker.families.planar_parallel.plots.panels import (
    INVERSE_CONDITION,
    MIN_PRESSURE_ANGLE,
    ScalarGrid,
    checked_grid,
    checked_overlay,
    colour_bar,
    contour_panel,
)

__all__ = ["MAX_TO_SCALE", "normalised_rectangle_figure"]

_CHOSEN = "#d62728"
#: Fig. 9 is drawn to scale while the rectangle is at most this much wider than high, or
#: higher than wide (the paper's lambda = 4 is).
MAX_TO_SCALE = 8.0


def normalised_rectangle_figure(
    x_normalised: ArrayLike,
    y_normalised: ArrayLike,
    inverse_condition: ArrayLike,
    min_pressure_angle_deg: ArrayLike,
    *,
    inverse_condition_limit: float,
    allowable_angle_deg: float | None,
    title: str,
    subtitle: str = "",
) -> Figure:
    """1/kappa and beta_min over W_lambda in x/b, (y + H')/b (the paper's Fig. 9).

    ``x_normalised`` (nx,) in [-1/2, 1/2], ``y_normalised`` (ny,) in [-1/(2 lambda),
    1/(2 lambda)], maps (ny, nx). The contour 1/kappa = 1/kappa0 and, when given, the
    contour beta_min = [beta] are drawn in red. Drawn to scale unless lambda is beyond
    :data:`MAX_TO_SCALE` either way (a sliver otherwise): then stretched, and titled so.
    """
    where = "normalised_rectangle_figure"
    ic = checked_grid(x_normalised, y_normalised, inverse_condition, where)
    beta = checked_grid(x_normalised, y_normalised, min_pressure_angle_deg, where)
    width = float(ic.x[-1] - ic.x[0])
    height = float(ic.y[-1] - ic.y[0])
    panel_h = min(max(7.0 * height / width, 1.2), 4.5)
    to_scale = 1.0 / MAX_TO_SCALE <= height / width <= MAX_TO_SCALE
    fig = Figure(figsize=(9.2, 2 * panel_h + 2.4), layout="compressed")
    axes = fig.subplots(2, 1)
    limit_label = rf"$1/\kappa$ = {inverse_condition_limit:.4g}"
    angle_label = rf"$\beta_{{\min}}$ = {allowable_angle_deg:g}°" if allowable_angle_deg else ""
    panels = (
        (ic, INVERSE_CONDITION, inverse_condition_limit, limit_label),
        (beta, MIN_PRESSURE_ANGLE, allowable_angle_deg, angle_label),
    )
    for ax, (grid, base, level, label) in zip(axes, panels, strict=True):
        finite = grid.values[np.isfinite(grid.values)]
        low = float(finite.min()) if finite.size else float("nan")
        scale = base.restricted(low, float(finite.max()) if finite.size else low)
        contour_panel(ax, grid, scale, checked_overlay(where), x_label=r"$\bar x = x / b$",
                      y_label=r"$\bar y = (y + H') / b$")  # fmt: skip
        if level is not None and finite.size and low < level < float(finite.max()):
            lines = ax.contour(grid.x, grid.y, grid.values, levels=[level], colors=_CHOSEN,
                               linewidths=2.0, zorder=3)  # fmt: skip
            contour_labels(ax, lines, fmt={level: label}, fontsize=9, inline=True)
        # The minima sit on the rectangle's edge: a margin keeps their markers whole
        # inside the frame; the margin is outside the rectangle, so it is left plain.
        ax.patch.set_hatch(None)
        pad_x, pad_y = 0.04 * np.ptp(grid.x), 0.04 * np.ptp(grid.y)
        ax.set_xlim(grid.x[0] - pad_x, grid.x[-1] + pad_x)
        ax.set_ylim(grid.y[0] - pad_y, grid.y[-1] + pad_y)
        for kx, ky in _minima(grid):
            ax.plot(grid.x[kx], grid.y[ky], "v", ms=10, color=_CHOSEN, mec="white",
                    clip_on=False, zorder=6)  # fmt: skip
        unit = "°" if base is MIN_PRESSURE_ANGLE else ""
        name = base.label.split(" (")[0]
        dimensionless(ax.xaxis, ax.yaxis)  # lengths over b
        stretched = "" if to_scale else ", axes not to scale"
        ax.set_title(f"{name}: minimum {low:.4g}{unit} (▼){stretched}", fontsize=10.5)
        if not to_scale:
            ax.set_aspect("auto")
        colour_bar(ax, scale, f"{name} [{unit}]" if unit else name,
                   max(1, (len(scale.levels) - 1) // 6))  # fmt: skip
    fig.suptitle(title, fontsize=12.5, fontweight="bold")
    if subtitle:  # the design's numbers, small, under the panels (not a block of bold)
        fig.supxlabel(subtitle, fontsize=9.5, color="0.3")
    return fig


def _minima(grid: ScalarGrid) -> list[tuple[int, int]]:
    """(ix, iy) of the smallest value, and of the smallest on the other side of x = 0 when
    it is as small (to 1e-3): the mirror-symmetric minima of Fig. 9."""
    values = np.where(np.isfinite(grid.values), grid.values, np.inf)
    if not np.isfinite(values).any():
        return []
    iy, ix = np.unravel_index(int(np.argmin(values)), values.shape)
    found = [(int(ix), int(iy))]
    other = grid.x < 0 if grid.x[ix] >= 0 else grid.x > 0
    if other.any():
        masked = np.where(other[None, :], values, np.inf)
        jy, jx = np.unravel_index(int(np.argmin(masked)), values.shape)
        if masked[jy, jx] <= values[iy, ix] + 1e-3:
            found.append((int(jx), int(jy)))
    return found
