"""Target poses coloured by whether the arm reaches them, with the arm drawn at a few
of its solutions (planar arms in the x-y plane, spatial ones in 3-D)."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from numpy.typing import NDArray

from worker.families.serial.kinematics.arm import SerialArm

__all__ = ["reach_figure"]

FloatArray = NDArray[np.float64]


def reach_figure(
    arm: SerialArm,
    positions: FloatArray,
    reached: NDArray[np.bool_],
    frames: FloatArray,
    tool: FloatArray,
    length_unit: str,
) -> Figure:
    """Targets (t, 3) as dots (reached) and crosses (not), the arm at solutions whose
    joint frames (m, n, 4, 4) and tool frames (m, 4, 4) are given."""
    planar = arm.planar
    dims = 2 if planar else 3
    chains = np.concatenate([frames[..., :3, 3], tool[:, None, :3, 3]], axis=1)[..., :dims]
    fig = Figure(figsize=(7.0, 6.0), layout="constrained")
    ax = fig.add_subplot() if planar else fig.add_subplot(projection="3d")
    for k in range(chains.shape[0]):
        ax.plot(*chains[k].T, "-o", color="0.45", ms=3, lw=1.2,
                label="the arm at reached targets" if k == 0 else None)  # fmt: skip
    for mask, marker, colour, label in ((reached, "o", "tab:green", "reached"),
                                        (~reached, "x", "tab:red", "not reached")):  # fmt: skip
        if mask.any():
            x, y, z = positions[mask].T
            text = f"{label} ({int(mask.sum())})"
            if planar:
                ax.scatter(x, y, s=22, marker=marker, color=colour, label=text)
            else:
                ax.scatter(x, y, z, s=22, marker=marker, color=colour, label=text)  # type: ignore[misc]
    ax.set_xlabel(f"$x$ [{length_unit}]")
    ax.set_ylabel(f"$y$ [{length_unit}]")
    if planar:
        ax.set_aspect("equal", adjustable="datalim")
    else:
        ax.set_zlabel(f"$z$ [{length_unit}]")  # type: ignore[union-attr]
        # one scale on every axis: a cube around the targets and the drawn arms
        points = np.concatenate([positions, chains.reshape(-1, 3)])
        centre = 0.5 * (points.max(axis=0) + points.min(axis=0))
        half = max(0.5 * float(np.ptp(points, axis=0).max()), 1e-9)
        ax.set_xlim(centre[0] - half, centre[0] + half)
        ax.set_ylim(centre[1] - half, centre[1] + half)
        ax.set_zlim(centre[2] - half, centre[2] + half)  # type: ignore[union-attr]
        ax.set_box_aspect((1, 1, 1))  # type: ignore[arg-type]
    share = float(reached.mean()) if reached.size else 0.0
    ax.set_title(f"{arm.joints}-joint arm: {int(reached.sum())} of {reached.size} targets "
                 f"reached ({100.0 * share:.1f} %)", fontsize=10)  # fmt: skip
    ax.legend(fontsize=8, loc="best")
    return fig
