"""The arm in its configurations with its translational manipulability ellipsoids.

Planar arms are drawn in the x-y plane, spatial ones in 3-D.  An ellipsoid is
``{J_v u : |u| = 1}`` (``J_v`` the linear rows), scaled by one factor for every
configuration so the largest fits a quarter of the arm's reach; its size between
configurations compares, its absolute size is the figure's (the legend says so).
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from numpy.typing import NDArray

from worker.families.serial.kinematics.arm import SerialArm

__all__ = ["arm_figure"]

FloatArray = NDArray[np.float64]


def _chain_points(frames: FloatArray, tool: FloatArray) -> FloatArray:
    """Joint origins then the tool point: (m, n + 1, 3)."""
    return np.concatenate([frames[..., :3, 3], tool[:, None, :3, 3]], axis=1)


def _ellipses(jac: FloatArray, planar: bool, size: float) -> tuple[FloatArray, float]:
    """Unit-sphere images under J_v: (m, k, d) points, and the common scale used."""
    rows = jac[:, :2, :] if planar else jac[:, :3, :]
    u, s, _ = np.linalg.svd(rows @ np.swapaxes(rows, -1, -2))
    radii = np.sqrt(np.maximum(s, 0.0))  # (m, d)
    scale = size / max(float(radii.max()), 1e-300)
    if planar:
        t = np.linspace(0.0, 2.0 * np.pi, 73)
        circle = np.stack([np.cos(t), np.sin(t)], axis=-1)  # (k, 2)
    else:
        a, b = np.meshgrid(np.linspace(0, 2 * np.pi, 25), np.linspace(0, np.pi, 13))
        circle = np.stack([np.cos(a) * np.sin(b), np.sin(a) * np.sin(b), np.cos(b)], -1)
        circle = circle.reshape(-1, 3)
    points = np.einsum("mij,mj,kj->mki", u, radii * scale, circle)
    return points, scale


def arm_figure(
    arm: SerialArm, frames: FloatArray, tool: FloatArray, jac: FloatArray, length_unit: str
) -> Figure:
    """The first configurations: links as lines, joints as dots, the tool as a cross,
    each with its ellipsoid at the tool point."""
    planar = arm.planar
    chains = _chain_points(frames, tool)
    reach = max(float(np.linalg.norm(chains - chains[:, :1], axis=-1).max()), 1e-9)
    shapes, _ = _ellipses(jac, planar, 0.25 * reach)
    fig = Figure(figsize=(7.0, 6.0), layout="constrained")
    colours = [f"C{k}" for k in range(chains.shape[0])]
    if planar:
        ax = fig.add_subplot()
        for k, colour in enumerate(colours):
            ax.plot(*chains[k, :, :2].T, "-o", color=colour, ms=4, label=f"configuration {k}")
            ax.plot(*(shapes[k] + chains[k, -1, :2]).T, "--", color=colour, lw=0.9)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(f"$x$ [{length_unit}]")
        ax.set_ylabel(f"$y$ [{length_unit}]")
    else:
        ax = fig.add_subplot(projection="3d")
        for k, colour in enumerate(colours):
            ax.plot(*chains[k].T, "-o", color=colour, ms=3, label=f"configuration {k}")
            cloud = shapes[k] + chains[k, -1]
            ax.scatter(*cloud.T, s=0.5, color=colour, alpha=0.35)
        ax.set_xlabel(f"$x$ [{length_unit}]")
        ax.set_ylabel(f"$y$ [{length_unit}]")
        ax.set_zlabel(f"$z$ [{length_unit}]")
        ax.set_box_aspect((1, 1, 1))
    ax.set_title(
        f"{arm.joints}-joint arm: configurations and translational manipulability "
        "ellipsoids\n(dashed/dotted at the tool point, one common scale)",
        fontsize=10,
    )
    ax.legend(fontsize=8, loc="best")
    return fig
