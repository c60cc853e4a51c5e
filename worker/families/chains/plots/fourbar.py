"""A four-bar's motion and its full-turn table (the four-bar classification job)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib import colormaps
from matplotlib.axes import Axes
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.patches import Patch
from numpy.typing import NDArray

from worker.common.figures import categorical, explained_constant, plain_text
from worker.families.chains.plots.graphs import FloatArray, bad_argument

__all__ = ["fourbar_figure"]

_ROLE_COLOURS = {"ground": "0.25", "input": "#4c78a8", "coupler": "#f58518", "output": "#54a24b"}
#: Colour scale of the full-turn table (1: turns fully, 0: rocks) on the "Blues" map.
_TURNS_VMIN, _TURNS_VMAX = -0.35, 1.25


def _motion_panel(
    ax: Axes, poses: FloatArray, lengths: Sequence[float], roles: Sequence[str], unit: str
) -> None:
    """The ground fixed, the paths of the two moving joints, ghosted and one drawn pose."""
    ground = roles.index("ground")
    link_of = {role: roles.index(role) for role in roles}
    tip, joint = (ground + 2) % 4, (ground + 3) % 4  # joints J_{g+2}, J_{g+3}
    ok = np.isfinite(poses[..., 0, 0])
    for branch, style in enumerate(("-", "--")):
        ax.plot(
            poses[branch, :, tip, 0],
            poses[branch, :, tip, 1],
            color=_ROLE_COLOURS["input"],
            lw=2.6,
            alpha=0.55,
            zorder=1,
            label="path of the input-coupler joint" if branch == 0 else None,
        )
        ax.plot(
            poses[branch, :, joint, 0],
            poses[branch, :, joint, 1],
            style,
            color=_ROLE_COLOURS["output"],
            lw=2.6,
            alpha=0.55,
            zorder=1,
            label=f"path of the coupler-output joint, assembly branch {branch + 1}",
        )
    feasible = np.flatnonzero(ok[0])
    for n, k in enumerate(feasible[:: max(1, feasible.size // 10)]):
        pose = poses[0, k]
        for role in ("input", "coupler", "output"):
            a, b = pose[link_of[role]], pose[(link_of[role] + 1) % 4]
            ax.plot(
                [a[0], b[0]],
                [a[1], b[1]],
                color=_ROLE_COLOURS[role],
                lw=1.0,
                alpha=0.22,
                label="poses along branch 1" if n == 0 and role == "coupler" else None,
            )
    if feasible.size:
        angles = np.linspace(0.0, 2.0 * np.pi, poses.shape[1])
        shown = feasible[np.argmin(np.abs(np.angle(np.exp(1j * (angles[feasible] - 1.1)))))]
        pose = poses[0, shown]
        for role in ("ground", "input", "coupler", "output"):
            k = link_of[role]
            a, b = pose[k], pose[(k + 1) % 4]
            ax.plot(
                [a[0], b[0]],
                [a[1], b[1]],
                color=_ROLE_COLOURS[role],
                lw=4.0,
                solid_capstyle="round",
                zorder=3,
            )
            middle = (a + b) / 2.0
            ax.annotate(
                f"{k}: {role} {lengths[k]:g}",
                middle,
                xytext=(0, 9),
                textcoords="offset points",
                ha="center",
                fontsize=9,
                color=_ROLE_COLOURS[role],
                fontweight="bold",
                zorder=5,
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.8},
            )
        ax.scatter(pose[:, 0], pose[:, 1], s=36, color="white", edgecolor="0.15", zorder=4)
    pivots = (
        poses[0, 0, [(ground + 1) % 4, ground]]
        if ok[0, 0]
        else np.array([[0.0, 0.0], [lengths[ground], 0.0]])
    )
    ax.scatter(
        pivots[:, 0],
        pivots[:, 1] - 0.04 * max(lengths),
        marker="^",
        s=120,
        color="0.25",
        zorder=4,
        label="ground pivots",
    )
    ax.set_aspect("equal")
    ax.grid(color="0.92")
    ax.set_xlabel(f"x [{plain_text(unit)}]")
    ax.set_ylabel(f"y [{plain_text(unit)}]")
    ax.set_title("range of motion with the ground fixed (one pose drawn bold)", fontsize=9.5)


def _turns_panel(
    ax: Axes, full_turns: NDArray[np.bool_], lengths: Sequence[float], roles: Sequence[str]
) -> None:
    """A 4 x 4 table: which links turn fully relative to which."""
    colours = np.where(full_turns, 1.0, 0.0)
    np.fill_diagonal(colours, np.nan)
    ax.imshow(colours, cmap="Blues", vmin=_TURNS_VMIN, vmax=_TURNS_VMAX)
    labels = [f"{k}: {roles[k]}\n{lengths[k]:g}" for k in range(4)]
    ax.set_xticks(range(4), labels, fontsize=8.5)
    ax.set_yticks(range(4), labels, fontsize=8.5)
    for i in range(4):
        for j in range(4):
            text = "" if i == j else ("full turn" if full_turns[i, j] else "rocks")
            ax.text(
                j,
                i,
                text,
                ha="center",
                va="center",
                fontsize=8.5,
                color="white" if full_turns[i, j] else "0.3",
            )
    ax.set_title("does link (column) turn fully\nrelative to link (row)?", fontsize=9.5)
    ax.set_xlabel("link that moves")
    ax.set_ylabel("link held fixed")
    categorical(ax.xaxis, ax.yaxis)
    explained_constant(ax)  # a table: every cell says "full turn" or "rocks"
    ax.tick_params(length=0)


def fourbar_figure(
    poses: FloatArray,
    *,
    lengths: Sequence[float],
    roles: Sequence[str],
    full_turns: NDArray[np.bool_],
    title: str,
    length_unit: str = "units",
) -> Figure:
    """A four-bar's range of motion (poses from :func:`worker.families.chains.kinematics.fourbar.
    four_bar_poses`, (2, k, 4, 2)) beside the 4 x 4 table of fully turning pairs."""
    where = "fourbar_figure"
    arr = np.asarray(poses, dtype=float)
    if arr.ndim != 4 or arr.shape[0] != 2 or arr.shape[2:] != (4, 2):
        raise bad_argument("poses", where, "an array of shape (2, k, 4, 2)", arr.shape)
    if sorted(roles) != sorted(_ROLE_COLOURS) or len(lengths) != 4:
        raise bad_argument("roles", where, "the four roles, one per link, with four lengths", roles)
    turns = np.asarray(full_turns, dtype=bool)
    if turns.shape != (4, 4):
        raise bad_argument("full_turns", where, "a (4, 4) boolean array", turns.shape)
    fig = Figure(figsize=(11.0, 6.2), layout="constrained")
    grid = fig.add_gridspec(1, 2, width_ratios=(1.75, 1.0))
    motion = fig.add_subplot(grid[0, 0])
    _motion_panel(motion, arr, lengths, roles, length_unit)
    _turns_panel(fig.add_subplot(grid[0, 1]), turns, lengths, roles)
    shade = colormaps["Blues"]
    scale = Normalize(vmin=_TURNS_VMIN, vmax=_TURNS_VMAX)
    handles, _ = motion.get_legend_handles_labels()
    handles += [
        Patch(color=shade(scale(1.0)), label="turns fully"),
        Patch(color=shade(scale(0.0)), label="rocks (cannot turn fully)"),
    ]
    fig.legend(handles=handles, loc="outside lower center", ncols=3, fontsize=8.5,
               frameon=False)  # fmt: skip
    fig.suptitle(plain_text(title), fontsize=12.5, fontweight="bold")
    return fig
