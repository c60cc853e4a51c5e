"""Figures of the optimum design of the proximal-arm robot (Huang et al. 2004, Figs 6-9).

* :func:`conditioning_limit_figure`: 1/kappa0 from eq (17) against delta for several
  allowable pressure angles [beta] (Fig. 7), each curve's maximum marked;
* :func:`design_indices_figure`: S/S_max, the mean 1/kappa and eta against delta
  (Fig. 8), with the optimum and the flat window around it;
* :func:`normalised_rectangle_figure`: 1/kappa and beta_min over the rectangle W_lambda
  in the normalised coordinates x/b, (y + H')/b (Fig. 9; in
  :mod:`worker.families.planar_parallel.plots.rectangle`, re-exported here);
* :func:`rectangle_workspace_figure`: W_lambda drawn inside W_kappa0 over the 1/kappa
  map (Fig. 6).

Lengths are in units of l1 (the design is normalised, l1 = 1). Conventions as in
:mod:`worker.families.planar_parallel.plots.conditioning`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from worker.common.figures import bad_figure_argument, dimensionless
from worker.families.planar_parallel.plots.panels import (
    INVERSE_CONDITION,
    FloatArray,
    ScalarGrid,
    checked_grid,
    checked_overlay,
    colour_bar,
    contour_panel,
    map_figure_size,
    overlay_legend,
)
from worker.families.planar_parallel.plots.rectangle import (
    normalised_rectangle_figure as normalised_rectangle_figure,
)

__all__ = [
    "conditioning_limit_figure",
    "design_indices_figure",
    "normalised_rectangle_figure",
    "rectangle_workspace_figure",
]

_DELTA_LABEL = r"$\delta = l_2 / l_1$"
_CHOSEN = "#d62728"
_INDEX_COLOURS = {"S": "#1f77b4", "mean": "#2ca02c", "eta": "#d62728"}
_WINDOW = "#ffd8a8"


def _curve(value: ArrayLike, name: str, where: str, size: int | None = None) -> FloatArray:
    arr = np.asarray(value, dtype=float)
    if arr.ndim != 1 or arr.size < 1 or (size is not None and arr.size != size):
        expected = "an array of shape (n,)" if size is None else f"an array of shape ({size},)"
        raise bad_figure_argument(name, where, expected, f"shape {arr.shape}")
    return arr


def conditioning_limit_figure(
    deltas: ArrayLike,
    allowable_angles_deg: ArrayLike,
    limits: ArrayLike,
    *,
    chosen_angle_deg: float | None,
    chosen_limit: float,
    chosen_delta: float | None,
    title: str,
) -> Figure:
    """1/kappa0 against delta, one curve per [beta] (the paper's Fig. 7).

    ``deltas`` (n,), ``allowable_angles_deg`` (k,), ``limits`` (k, n) by eq (17) + eq (7)
    (NaN where eq 17 has no point). The chosen [beta]'s curve is drawn bold; the limit
    used (``chosen_limit``, at ``chosen_delta`` when it is a maximum) is marked.
    """
    where = "conditioning_limit_figure"
    d = _curve(deltas, "deltas", where)
    betas = _curve(allowable_angles_deg, "allowable_angles_deg", where)
    values = np.asarray(limits, dtype=float)
    if values.shape != (betas.size, d.size):
        raise bad_figure_argument(
            "limits",
            where,
            f"an array of shape (k, n) = {(betas.size, d.size)}",
            f"shape {values.shape}",
        )
    fig = Figure(figsize=(10.4, 5.8), layout="constrained")
    ax = fig.add_subplot()
    cmap = INVERSE_CONDITION.mappable().get_cmap()
    colours = [cmap(v) for v in np.linspace(0.1, 0.85, betas.size)]
    for beta, curve, colour in zip(betas, values, colours, strict=True):
        chosen = chosen_angle_deg is not None and bool(np.isclose(beta, chosen_angle_deg))
        colour = _CHOSEN if chosen else colour
        label = rf"$[\beta]$ = {beta:g}°"
        if np.isfinite(curve).any():
            k = int(np.nanargmax(curve))
            finite = np.flatnonzero(np.isfinite(curve))
            if finite[0] < k < finite[-1]:  # a maximum, not the end of the range drawn
                ax.plot(d[k], curve[k], "o", ms=4.5, color=colour, zorder=4)
                label += rf": max {curve[k]:.4f} at $\delta$ = {d[k]:.4g}"
            else:
                label += rf": no maximum for $\delta \leq$ {d[finite[-1]]:.4g}"
        ax.plot(d, curve, color=colour, lw=2.6 if chosen else 1.4, label=label,
                zorder=3 if chosen else 2)  # fmt: skip
    ax.axhline(chosen_limit, color="0.25", ls="--", lw=1.0, zorder=1)
    text = rf"$1/\kappa_0$ = {chosen_limit:.5g}"
    if chosen_delta is None:
        text += " (given)"
    if chosen_delta is not None:
        ax.axvline(chosen_delta, color="0.25", ls=":", lw=1.0, zorder=1)
        ax.plot(chosen_delta, chosen_limit, "D", ms=7, color=_CHOSEN, mec="black", zorder=5)
        text += rf" at $\delta$ = {chosen_delta:.4g}"
    ax.annotate(text, (chosen_delta if chosen_delta is not None else d[0], chosen_limit),
                xytext=(10, -22), textcoords="offset points", fontsize=10,
                bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "0.6"})  # fmt: skip
    ax.set_xlim(d[0], d[-1])
    ax.set_ylim(0.0, 1.0)
    ax.set_xlabel(_DELTA_LABEL, fontsize=11)
    ax.set_ylabel(r"conditioning limit $1/\kappa_0$ (eqs 17, 7)", fontsize=11)
    dimensionless(ax.xaxis, ax.yaxis)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=9,
              title="allowable pressure angle (dots: maxima)", title_fontsize=9.5,
              frameon=False)  # fmt: skip
    ax.set_title(r"1/$\kappa_0$ = 1/$\kappa$ at $(\pm e, y_0)$, $y_0$ of eq (17), isotropic "
                 r"design of eq (12)", fontsize=10, color="0.25")  # fmt: skip
    fig.suptitle(title, fontsize=13, fontweight="bold")
    return fig


def design_indices_figure(
    deltas: ArrayLike,
    area_ratio: ArrayLike,
    mean_inverse_condition: ArrayLike,
    eta: ArrayLike,
    *,
    optimum_delta: float | None,
    window: Sequence[float] | None,
    title: str,
    subtitle: str = "",
) -> Figure:
    """S/S_max, the mean 1/kappa over W_lambda and eta = (S/S_max) mean (Fig. 8).

    All arrays (n,), NaN where no rectangle was found. ``window`` = (lo, hi): the deltas
    where eta is within 0.001 of its maximum, shaded.
    """
    where = "design_indices_figure"
    d = _curve(deltas, "deltas", where)
    curves = {
        "S": _curve(area_ratio, "area_ratio", where, d.size),
        "mean": _curve(mean_inverse_condition, "mean_inverse_condition", where, d.size),
        "eta": _curve(eta, "eta", where, d.size),
    }
    labels = {
        "S": r"$\Delta_s = S / S_{\max}$",
        "mean": r"mean $1/\bar\kappa$ over $W_\lambda$ (eq 14)",
        "eta": r"$\eta = \Delta_s / \bar\kappa$ (eq 13)",
    }
    fig = Figure(figsize=(8.6, 5.6), layout="constrained")
    ax = fig.add_subplot()
    if window is not None:
        lo, hi = (float(v) for v in window)
        ax.axvspan(lo, hi, color=_WINDOW, lw=0, zorder=0,
                   label=rf"$\eta$ within 0.001 of its max: [{lo:.3g}, {hi:.3g}]")  # fmt: skip
    for key, values in curves.items():
        ax.plot(d, values, color=_INDEX_COLOURS[key], lw=2.0 if key == "eta" else 1.5,
                marker="o" if d.size < 30 else None, ms=4, label=labels[key])  # fmt: skip
    if optimum_delta is not None:
        k = int(np.argmin(np.abs(d - optimum_delta)))
        ax.axvline(optimum_delta, color="0.25", ls=":", lw=1.0)
        ax.plot(
            optimum_delta,
            curves["eta"][k],
            "D",
            ms=7,
            color=_INDEX_COLOURS["eta"],
            mec="black",
            zorder=5,
            label=rf"optimum $\delta$ = {optimum_delta:.4g}, $\eta$ = {curves['eta'][k]:.4f}",
        )
    finite = np.concatenate([v[np.isfinite(v)] for v in curves.values()])
    low = float(finite.min()) if finite.size else 0.0
    ax.set_ylim(max(0.0, min(low - 0.05, 0.6)), 1.02)
    ax.set_xlim(d[0], d[-1]) if d.size > 1 else ax.set_xlim(d[0] - 0.1, d[0] + 0.1)
    ax.set_xlabel(_DELTA_LABEL, fontsize=11)
    ax.set_ylabel("performance indices", fontsize=11)
    dimensionless(ax.xaxis, ax.yaxis)
    ax.grid(alpha=0.3)
    if subtitle:
        ax.set_title(subtitle, fontsize=10, color="0.25")
    fig.legend(loc="outside lower center", ncols=2, fontsize=9.5, frameon=False)
    fig.suptitle(title, fontsize=13, fontweight="bold")
    return fig


def _view_around(
    grid: ScalarGrid, limit: float, box: tuple[float, float, float, float] | None
) -> tuple[float, float, float, float]:
    """The grid's x range; in y, from the grid's bottom to a little above the highest node of
    W_kappa0 (and of the rectangle), so that the part of the workspace in use fills the
    figure."""
    x0, x1, y0, y1 = float(grid.x[0]), float(grid.x[-1]), float(grid.y[0]), float(grid.y[-1])
    inside = np.nan_to_num(grid.values, nan=-1.0) >= limit
    rows = np.flatnonzero(inside.any(axis=1))
    if rows.size == 0:
        return x0, x1, y0, y1
    top = float(grid.y[rows[-1]])
    if box is not None:
        top = max(top, box[1] + box[3])
    return x0, x1, y0, min(y1, top + 0.12 * (top - y0))


def rectangle_workspace_figure(
    x: ArrayLike,
    y: ArrayLike,
    inverse_condition: ArrayLike,
    *,
    inverse_condition_limit: float,
    rectangle: Sequence[float] | None,
    joints: ArrayLike | None = None,
    isotropic_point: Sequence[float] | None = None,
    title: str,
    subtitle: str = "",
) -> Figure:
    """The rectangle W_lambda inside W_kappa0 over the 1/kappa map (the paper's Fig. 6).

    ``rectangle`` = (b, h, H'): |x| <= b/2, -H' - h/2 <= y <= -H' + h/2; None when no
    rectangle was found; W_kappa0 is outlined by the map's contour at the limit.
    Lengths in units of l1.
    """
    where = "rectangle_workspace_figure"
    grid = checked_grid(x, y, inverse_condition, where)
    box = None
    if rectangle is not None:
        b, h, h_prime = (float(v) for v in rectangle)
        box = (-b / 2, -h_prime - h / 2, b, h)
    overlay = checked_overlay(
        where, outline=(grid, inverse_condition_limit),
        outline_label=rf"boundary of $W_{{\kappa 0}}$: $1/\kappa = {inverse_condition_limit:.5g}$",
        joints=joints, isotropic_point=isotropic_point, rectangle=box,
        rectangle_label=r"rectangle $W_\lambda$ (b x h, centre (0, -H'))",
    )  # fmt: skip
    view = _view_around(grid, inverse_condition_limit, box)
    fig = Figure(figsize=map_figure_size(view, axes_width=6.4), layout="compressed")
    ax = fig.add_subplot()
    contour_panel(ax, grid, INVERSE_CONDITION, overlay, x_label=r"x [$l_1$]",
                  y_label=r"y [$l_1$]", view=view)  # fmt: skip
    if subtitle:
        ax.set_title(subtitle, fontsize=10, color="0.25")
    colour_bar(ax, INVERSE_CONDITION)
    fig.suptitle(title, fontsize=13, fontweight="bold")
    overlay_legend(fig, overlay, unreachable=bool(np.isnan(grid.values).any()), ncols=2)
    return fig
