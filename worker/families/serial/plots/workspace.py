"""Figures of a serial arm's workspace map: slices through the voxel grid (the pixel
map of a planar arm), a 3-D view of the reached voxels and histograms of the indices."""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from numpy.typing import NDArray

from worker.common.figures import dimensionless, explained_constant, plain_text
from worker.families.serial.kinematics.workspace_map import WorkspaceMap

__all__ = ["histogram_figure", "scatter_figure", "slices_figure"]

FloatArray = NDArray[np.float64]
#: The most voxels drawn in the 3-D view (an even subsample beyond).
DRAWN_VOXELS = 20_000


def _image(fig: Figure, ax: Axes, values: FloatArray, extent: list[float],
           labels: tuple[str, str], unit: str, title: str, shrink: float) -> None:  # fmt: skip
    box = (extent[0], extent[1], extent[2], extent[3])
    image = ax.imshow(values.T, origin="lower", extent=box, vmin=0.0, vmax=1.0,
                      cmap="viridis", interpolation="nearest", aspect="equal")  # fmt: skip
    ax.set_xlabel(f"{labels[0]} [{plain_text(unit)}]")
    ax.set_ylabel(f"{labels[1]} [{plain_text(unit)}]")
    ax.set_title(title, fontsize=9)
    finite = values[np.isfinite(values)]
    if finite.size and np.ptp(finite) == 0.0:
        explained_constant(ax, None)
    bar = fig.colorbar(image, ax=ax, shrink=shrink)
    bar.set_label("reachability index [-]")
    dimensionless(bar.ax.yaxis)


def slices_figure(result: WorkspaceMap, length_unit: str) -> Figure:
    """The reachability index (NaN: not reached): a planar arm's pixel map, or a
    spatial arm's three slices through the node nearest the grid's centre (z = const,
    y = const, x = const)."""
    grid = result.grid
    index = np.where(result.reached, result.reachability_index, np.nan)
    half = grid.size / 2.0
    ext = [[float(a[0] - half), float(a[-1] + half)] for a in grid.axes]
    if len(grid.axes) == 2:
        fig = Figure(figsize=(6.5, 5.5), layout="constrained")
        _image(fig, fig.add_subplot(), index, ext[0] + ext[1], ("x", "y"), length_unit,
               "Fraction of tool-angle bins reached per pixel", 0.8)  # fmt: skip
        return fig
    fig = Figure(figsize=(15.0, 5.0), layout="constrained")
    mid = [int(np.argmin(np.abs(a - 0.5 * (a[0] + a[-1])))) for a in grid.axes]
    cuts = (
        (index[:, :, mid[2]], ext[0] + ext[1], ("x", "y"), f"z = {grid.axes[2][mid[2]]:.4g}"),
        (index[:, mid[1], :], ext[0] + ext[2], ("x", "z"), f"y = {grid.axes[1][mid[1]]:.4g}"),
        (index[mid[0], :, :], ext[1] + ext[2], ("y", "z"), f"x = {grid.axes[0][mid[0]]:.4g}"),
    )
    for k, (values, extent, labels, where) in enumerate(cuts):
        _image(fig, fig.add_subplot(1, 3, k + 1), values, extent, labels, length_unit,
               f"Tool-axis cells reached at {where} {plain_text(length_unit)}", 0.55)  # fmt: skip
    return fig


def scatter_figure(result: WorkspaceMap, length_unit: str) -> Figure:
    """Reached voxels (pixels) as points coloured by the reachability index, in 3-D (a
    planar arm's pixels at the height of their index)."""
    grid = result.grid
    nodes = np.stack(np.meshgrid(*grid.axes, indexing="ij"), axis=-1)[result.reached]
    index = result.reachability_index[result.reached]
    step = max(1, int(np.ceil(index.size / DRAWN_VOXELS)))
    nodes, index = nodes[::step], index[::step]
    fig = Figure(figsize=(7.0, 6.0), layout="constrained")
    ax = fig.add_subplot(projection="3d")
    unit = plain_text(length_unit)
    z = index if len(grid.axes) == 2 else nodes[:, 2]
    points = ax.scatter(nodes[:, 0], nodes[:, 1], z, c=index, s=3, cmap="viridis",
                        vmin=0.0, vmax=1.0, depthshade=False)  # fmt: skip
    ax.set_xlabel(f"x [{unit}]")
    ax.set_ylabel(f"y [{unit}]")
    if len(grid.axes) == 2:
        ax.set_zlabel("reachability index [-]")
        dimensionless(ax.zaxis)
    else:
        ax.set_zlabel(f"z [{unit}]")
    shown = "" if step == 1 else f" (every {step}th of {int(result.reached.sum()):,})"
    ax.set_title(f"Reached voxels{shown}", fontsize=9)
    bar = fig.colorbar(points, ax=ax, shrink=0.6, pad=0.1)
    bar.set_label("reachability index [-]")
    dimensionless(bar.ax.yaxis)
    return fig


def histogram_figure(result: WorkspaceMap) -> Figure:
    """Histograms over the reached voxels of the reachability index and of the per-voxel
    mean manipulability and mean inverse condition number."""
    reached = result.reached
    panels = (
        (result.reachability_index[reached], "reachability index [-]", True),
        (result.statistics["manipulability_mean"][reached],
         "mean manipulability per voxel [mixed units]", False),
        (result.statistics["inverse_condition_mean"][reached],
         r"mean inverse condition $1/\kappa$ per voxel [-]", True),
    )  # fmt: skip
    fig = Figure(figsize=(13.0, 4.0), layout="constrained")
    for k, (values, label, pure) in enumerate(panels):
        ax = fig.add_subplot(1, 3, k + 1)
        ax.hist(values, bins=40, color="tab:blue")
        ax.set_xlabel(label)
        ax.set_ylabel("voxels [-]")
        dimensionless(ax.yaxis)
        if pure:
            dimensionless(ax.xaxis)
    return fig
