"""The link graph of a kinematic chain, with its loops (the chain-parallelism job).

Every figure function of :mod:`worker.families.chains.plots` takes plain data and
returns a :class:`matplotlib.figure.Figure`;
:func:`worker.common.figures.figure_artifacts` turns it into PNG/SVG bytes.

The link graph follows the paper (Fig 1b): every link is a vertex (a circle for a
binary link, a shaded polygon marker for a ternary or larger link), every joint an
edge.  The peripheral loop is drawn as the outer polygon; links off it sit at the
average of their neighbours (Tutte's barycentric layout), which keeps a planar chain's
drawing planar.  Inner loops are shaded and numbered as in the paper's Fig 4, and
each loop shows, next to every link it passes, the length of the side it uses there,
so the adjacent products of eq (3) can be read off the drawing.  User-supplied text is
shown literally, ``$`` included.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.layout_engine import ConstrainedLayoutEngine
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Polygon
from matplotlib.path import Path
from numpy.typing import NDArray

from worker.common.figures import plain_text

__all__ = ["ChainGraph", "FloatArray", "bad_argument", "chain_graphs_figure", "graph_layout"]

FloatArray = NDArray[np.float64]
_LOOP_COLOURS = (
    "#4c78a8",
    "#f58518",
    "#54a24b",
    "#b279a2",
    "#e45756",
    "#72b7b2",
    "#9d755d",
    "#eeca3b",
)
_PERIPHERAL_COLOUR = "0.35"
_EDGE_COLOUR = "0.2"
_POLYGON_MARKERS = {3: "^", 4: "s", 5: "p", 6: "h"}
_MAX_COLUMNS = 3


@dataclass(frozen=True)
class ChainGraph:
    """One chain to draw.

    ``links``: link names; ``polygonal``: the names of ternary and larger links;
    ``joints``: pairs of jointed links; ``loops``: each loop's sides in order (``"2"``,
    ``"1.a"``), the peripheral loop last (a single loop is its own peripheral loop);
    ``loop_lengths``: the side lengths of each loop, in the same order.
    """

    name: str
    links: tuple[str, ...]
    polygonal: frozenset[str]
    joints: tuple[tuple[str, str], ...]
    loops: tuple[tuple[str, ...], ...]
    loop_lengths: tuple[tuple[float, ...], ...]
    #: A line under the panel, built by the job: mathtext, any user text in it (the length
    #: unit) escaped with :func:`worker.common.figures.plain_text`.
    caption: str = ""


def bad_argument(parameter: str, where: str, expected: str, got: object) -> ValueError:
    """The ValueError of a bad argument of the chain figures (``got`` shown by repr)."""
    return ValueError(
        f"The '{parameter}' parameter of {where} must be {expected}. Got {got!r} instead."
    )


def _link(side: str) -> str:
    return side.partition(".")[0]


def graph_layout(graph: ChainGraph) -> dict[str, tuple[float, float]]:
    """Vertex positions: the peripheral loop on a unit regular polygon, clockwise from the
    top; every other link at the mean of its neighbours (solved as one linear system)."""
    rim = [_link(side) for side in graph.loops[-1]]
    positions: dict[str, tuple[float, float]] = {}
    for k, link in enumerate(rim):
        angle = math.pi / 2 - 2 * math.pi * k / len(rim)
        positions[link] = (math.cos(angle), math.sin(angle))
    inner = [link for link in graph.links if link not in positions]
    if inner:
        neighbours: dict[str, list[str]] = {link: [] for link in graph.links}
        for a, b in graph.joints:
            neighbours[a].append(b)
            neighbours[b].append(a)
        index = {link: i for i, link in enumerate(inner)}
        system = np.zeros((len(inner), len(inner)))
        rhs = np.zeros((len(inner), 2))
        for link, i in index.items():
            system[i, i] = max(len(neighbours[link]), 1)
            for other in neighbours[link]:
                if other in index:
                    system[i, index[other]] -= 1.0
                else:
                    rhs[i] += positions[other]
        solved = np.linalg.lstsq(system, rhs, rcond=None)[0]
        positions.update(
            {link: (float(solved[i, 0]), float(solved[i, 1])) for link, i in index.items()}
        )
    return positions


def _unit(vector: FloatArray) -> FloatArray:
    norm = float(np.hypot(*vector))
    return vector / norm if norm > 1e-12 else np.array([0.0, 1.0])


def _segment_distance(points: FloatArray, a: FloatArray, b: FloatArray) -> FloatArray:
    """Distance of ``points`` (k, 2) from the segment a-b."""
    ab = b - a
    t = np.clip(((points - a) @ ab) / max(float(ab @ ab), 1e-12), 0.0, 1.0)
    return np.asarray(np.hypot(*(points - (a + t[:, None] * ab)).T), dtype=float)


def _clear_spot(corners: FloatArray, taken: FloatArray) -> FloatArray:
    """The point inside the polygon ``corners`` (m, 2) farthest from its edges and from the
    ``taken`` spots (k, 2): where a loop's number reads clearly."""
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    gx, gy = np.meshgrid(np.linspace(lo[0], hi[0], 41), np.linspace(lo[1], hi[1], 41))
    grid = np.column_stack([gx.ravel(), gy.ravel()])
    inside = grid[Path(corners).contains_points(grid)]
    if inside.size == 0:
        return np.asarray(corners.mean(axis=0), dtype=float)
    clearance = np.full(len(inside), np.inf)
    for a, b in zip(corners, np.roll(corners, -1, axis=0), strict=True):
        clearance = np.minimum(clearance, _segment_distance(inside, a, b))
    for spot in taken:
        clearance = np.minimum(clearance, np.hypot(*(inside - spot).T))
    return np.asarray(inside[int(np.argmax(clearance))], dtype=float)


def _draw_loop(
    ax: Axes, graph: ChainGraph, k: int, xy: dict[str, FloatArray], centre: FloatArray
) -> None:
    """Shade and number an inner loop; write each side's length next to its link."""
    loop = graph.loops[k]
    corners = np.array([xy[_link(side)] for side in loop])
    peripheral = k == len(graph.loops) - 1 and len(graph.loops) > 1
    colour = _PERIPHERAL_COLOUR if peripheral else _LOOP_COLOURS[k % len(_LOOP_COLOURS)]
    spots = []
    for side, length, vertex in zip(loop, graph.loop_lengths[k], corners, strict=True):
        away = vertex - centre if peripheral else corners.mean(axis=0) - vertex
        spot = vertex + 0.27 * _unit(away)
        spots.append(spot)
        name = side.partition(".")[2]
        text = f"{name} {length:g}" if name else f"{length:g}"
        ax.text(
            float(spot[0]),
            float(spot[1]),
            text,
            ha="center",
            va="center",
            fontsize=8,
            color=colour,
            zorder=5,
        )
    if peripheral:
        ax.text(
            0.02,
            0.02,
            f"loop {k + 1}: peripheral (lengths outside)",
            fontsize=8.5,
            transform=ax.transAxes,
            color=colour,
            ha="left",
            va="bottom",
        )
        return
    if len(graph.loops) == 1:
        ax.text(
            0.02,
            0.02,
            "loop 1: the single loop, also the peripheral one",
            fontsize=8.5,
            transform=ax.transAxes,
            color=colour,
            ha="left",
            va="bottom",
        )
    ax.add_patch(Polygon(corners, closed=True, facecolor=colour, alpha=0.16, lw=0, zorder=0))
    label = _clear_spot(corners, np.vstack([corners, np.array(spots)]))
    ax.text(
        float(label[0]),
        float(label[1]),
        str(k + 1),
        ha="center",
        va="center",
        fontsize=10,
        fontweight="bold",
        color=colour,
        zorder=4,
        bbox={"boxstyle": "circle,pad=0.25", "fc": "white", "ec": colour, "lw": 1.3},
    )


def _degrees(graph: ChainGraph) -> dict[str, int]:
    """Each link -> its number of joints (3 for a ternary link)."""
    degree = {link: 0 for link in graph.links}
    for a, b in graph.joints:
        degree[a] += 1
        degree[b] += 1
    return degree


_POLYGON_NAMES = {3: "ternary", 4: "quaternary", 5: "pentagonal", 6: "hexagonal"}


def _graph_legend(
    fig: Figure, graphs: Sequence[ChainGraph], length_unit: str, columns: int
) -> None:
    """One legend under the panels: the vertex kinds drawn, joints, loops, side lengths."""
    sizes = sorted({_degrees(g)[link] for g in graphs for link in g.links if link in g.polygonal})
    handles: list[Artist] = [
        Line2D([], [], ls="none", marker="o", ms=11, mfc="white", mec=_EDGE_COLOUR,
               label="binary link"),
    ]  # fmt: skip
    for size in sizes:
        name = _POLYGON_NAMES.get(size, f"{size}-joint")
        handles.append(
            Line2D([], [], ls="none", marker=_POLYGON_MARKERS.get(size, "o"), ms=12,
                   mfc="#d9d9d9", mec=_EDGE_COLOUR, label=f"{name} link")
        )  # fmt: skip
    handles += [
        Line2D([], [], color=_EDGE_COLOUR, lw=1.8, label="joint"),
        Patch(facecolor=_LOOP_COLOURS[0], alpha=0.3, label="loop (numbered)"),
        Line2D([], [], ls="none", marker="$9$", ms=8, color=_PERIPHERAL_COLOUR,
               label=f"side length used by a loop [{plain_text(length_unit)}]"),
    ]  # fmt: skip
    if sizes:  # a polygonal link has one length per side; each loop uses one side
        handles.append(
            Line2D([], [], ls="none", marker="$a$", ms=8, color=_PERIPHERAL_COLOUR,
                   label="next to a polygonal link: the length of the side (a, b, ...) "
                   "the loop passes")
        )  # fmt: skip
    ncols = min(len(handles), 3 * columns if not sizes else max(1, 2 * columns - 1))
    fig.legend(handles=handles, loc="outside lower center", ncols=ncols, fontsize=9,
               frameon=False, columnspacing=1.4)  # fmt: skip


def _draw_graph(ax: Axes, graph: ChainGraph) -> None:
    xy = {link: np.array(p) for link, p in graph_layout(graph).items()}
    centre = np.mean(list(xy.values()), axis=0)
    for k in range(len(graph.loops)):
        _draw_loop(ax, graph, k, xy, centre)
    for a, b in graph.joints:
        (x0, y0), (x1, y1) = xy[a], xy[b]
        ax.plot([x0, x1], [y0, y1], color=_EDGE_COLOUR, lw=1.8, zorder=2, solid_capstyle="round")
    degree = _degrees(graph)
    for link in graph.links:
        x, y = xy[link]
        if link in graph.polygonal:
            marker = _POLYGON_MARKERS.get(degree[link], "o")
            ax.scatter(
                [x],
                [y],
                s=430,
                marker=marker,
                facecolor="#d9d9d9",
                edgecolor=_EDGE_COLOUR,
                lw=1.4,
                zorder=3,
            )
        else:
            ax.scatter(
                [x],
                [y],
                s=300,
                marker="o",
                facecolor="white",
                edgecolor=_EDGE_COLOUR,
                lw=1.4,
                zorder=3,
            )
        ax.text(
            x,
            y,
            plain_text(link),
            ha="center",
            va="center",
            fontsize=8.5,
            zorder=6,
            fontweight="bold",
        )
    ax.set_xlim(-1.5, 1.5)
    ax.set_ylim(-1.5, 1.45)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    for spine in ax.spines.values():
        spine.set_color("0.85")
    ax.set_title(plain_text(graph.name), fontsize=11, fontweight="bold")
    if graph.caption:  # built by the job: mathtext, user text escaped
        ax.set_xlabel(graph.caption, fontsize=8, color="0.3")


def chain_graphs_figure(
    graphs: Sequence[ChainGraph], *, title: str, length_unit: str = "units"
) -> Figure:
    """One panel per chain: its link graph, loops shaded and numbered, side lengths."""
    where = "chain_graphs_figure"
    if not graphs:
        raise bad_argument("graphs", where, "at least one ChainGraph", graphs)
    for graph in graphs:
        if len(graph.loop_lengths) != len(graph.loops) or any(
            len(lengths) != len(loop)
            for lengths, loop in zip(graph.loop_lengths, graph.loops, strict=False)
        ):
            raise bad_argument(
                "graphs", where, "ChainGraphs with one length per loop side", graph.name
            )
    columns = min(len(graphs), _MAX_COLUMNS)
    rows = math.ceil(len(graphs) / columns)
    # The extra space between rows keeps each caption off the next row's titles.
    layout = ConstrainedLayoutEngine(h_pad=0.1, hspace=0.07)
    fig = Figure(figsize=(4.1 * columns, 4.4 * rows + 0.6), layout=layout)
    for index, graph in enumerate(graphs):
        _draw_graph(fig.add_subplot(rows, columns, index + 1), graph)
    fig.suptitle(plain_text(title), fontsize=13, fontweight="bold")
    _graph_legend(fig, graphs, length_unit, columns)
    return fig
