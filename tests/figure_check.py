"""A figure check: the defects a reader sees, found on a drawn ``Figure``.

:func:`figure_defects` draws the figure with the Agg renderer and returns one line per
defect (empty: none):

- **overlap**: two visible text artists (titles, axis labels, tick labels, contour
  labels, legend entries, annotations) whose boxes intersect;
- **clipped**: a text artist reaching beyond the figure's edge, or beyond the box it is
  clipped to (a contour label cut off at its axes' edge);
- **colour bar**: a colour bar longer than the axes it belongs to, or not beside them;
- **axis label**: an axis with ticks but no label, or a label without a unit in
  brackets (``[mm]``, ``[°]``, ``[-]``) unless the axis declares itself dimensionless
  (:func:`worker.common.figures.dimensionless`);
- **symbol**: a Greek letter, a subscript (``d_z``) or a Greek letter's name
  (``kappa``) written as plain text instead of mathtext (``$\\kappa$``);
- **constant field**: an image, mesh or filled contour whose finite values are all
  equal, unless the axes say why (:func:`worker.common.figures.explained_constant`);
- **broken contour** and **contour label**: a contour line with a gap where no label is,
  a label hanging over the end of its line (:mod:`tests.figure_contours`).
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Iterator

import numpy as np
from matplotlib.axes import Axes
from matplotlib.backend_bases import RendererBase
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.cm import ScalarMappable
from matplotlib.figure import Figure
from matplotlib.text import Text
from matplotlib.transforms import Bbox

from tests.figure_contours import contour_defects

__all__ = ["figure_defects"]

#: Boxes may touch; they overlap when they share more than this many pixels each way.
OVERLAP_PX = 1.0
#: A text may reach this far beyond the figure's edge (antialiasing) before it is clipped.
EDGE_PX = 1.0
#: A colour bar may exceed its axes by this fraction of their length.
COLOURBAR_SLACK = 0.02
_GREEK = "αβγδεζηθικλμνξπρστυφχψωΓΔΘΛΞΠΣΦΨΩ"
_GREEK_NAMES = (
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "kappa",
    "lambda", "mu", "sigma", "phi", "psi", "omega",
)  # fmt: skip
_SUBSCRIPT = re.compile(r"\b[A-Za-z]{1,3}_[A-Za-z0-9]{1,4}\b")
_GREEK_WORD = re.compile(r"\b(" + "|".join(_GREEK_NAMES) + r")(?=\b|_|\d)", re.IGNORECASE)
_UNIT = re.compile(r"\[[^\[\]]+\]\s*$")


def _tick_labels(fig: Figure) -> tuple[set[int], set[int]]:
    """(every tick label, the tick labels drawn): matplotlib keeps labels of ticks
    outside the view limits, which are never drawn."""
    every: set[int] = set()
    drawn: set[int] = set()
    for ax in fig.axes:
        axes = [ax.xaxis, ax.yaxis, *([ax.zaxis] if hasattr(ax, "zaxis") else [])]
        for axis in axes:
            for tick in [*axis.get_major_ticks(), *axis.get_minor_ticks()]:
                every.update({id(tick.label1), id(tick.label2)})
            if not (ax.get_visible() and ax.axison and axis.get_visible()):
                continue
            for tick in axis._update_ticks():
                for label in (tick.label1, tick.label2):
                    if label.get_visible():
                        drawn.add(id(label))
    return every, drawn


def _visible_texts(fig: Figure) -> Iterator[Text]:
    every, drawn = _tick_labels(fig)
    for text in fig.findobj(Text):
        if not text.get_visible() or not text.get_text().strip():
            continue
        if id(text) in every and id(text) not in drawn:
            continue
        if text.axes is not None and not text.axes.get_visible():
            continue
        yield text


def _plain_parts(text: str) -> str:
    """The text outside $...$ (mathtext), escaped dollars kept as text."""
    parts = re.split(r"(?<!\\)\$", text)
    return " ".join(parts[0::2])


def _symbol_defects(text: str) -> list[str]:
    plain = _plain_parts(text.replace(r"\$", ""))
    found = []
    if any(ch in plain for ch in _GREEK):
        found.append("a Greek letter outside mathtext")
    if _SUBSCRIPT.search(plain):
        found.append(f"a subscript as plain text ({_SUBSCRIPT.search(plain).group(0)!r})")  # type: ignore[union-attr]
    if _GREEK_WORD.search(plain):
        found.append(f"a Greek letter's name ({_GREEK_WORD.search(plain).group(0)!r})")  # type: ignore[union-attr]
    return found


def _label(text: Text) -> str:
    shown = text.get_text().replace("\n", " ")
    return shown if len(shown) <= 50 else shown[:47] + "..."


def _extent(text: Text, renderer: RendererBase) -> Bbox | None:
    try:
        box = text.get_window_extent(renderer)
    except (RuntimeError, ValueError):
        return None
    if not np.all(np.isfinite(box.get_points())) or box.width <= 0 or box.height <= 0:
        return None
    return box


def _overlap(a: Bbox, b: Bbox) -> bool:
    dx = min(a.x1, b.x1) - max(a.x0, b.x0)
    dy = min(a.y1, b.y1) - max(a.y0, b.y0)
    return dx > OVERLAP_PX and dy > OVERLAP_PX


def _colourbar_axes(fig: Figure) -> dict[Axes, list[Axes]]:
    """Colour bar axes -> the axes they stand beside (those they were made for, else
    the mappable's)."""
    pairs = {}
    for ax in fig.axes:
        colorbar = getattr(ax, "_colorbar", None)
        if colorbar is None:
            continue
        parents = list(getattr(ax, "_colorbar_info", {}).get("parents", []) or [])
        if not parents and getattr(colorbar.mappable, "axes", None) is not None:
            parents = [colorbar.mappable.axes]
        pairs[ax] = parents
    return pairs


def _constant_fields(ax: Axes) -> Iterator[str]:
    if getattr(ax, "dexlab_constant_explained", False):
        return
    for artist in [*ax.images, *ax.collections]:
        if not isinstance(artist, ScalarMappable) or artist.get_array() is None:
            continue
        if getattr(artist, "filled", False):  # a filled contour set: one band drawn?
            bands = sum(len(path.vertices) > 0 for path in artist.get_paths())
            if bands == 1:
                yield f"constant field: {ax.get_title() or 'an axes'} shows one band everywhere"
            continue
        values = np.asarray(np.ma.filled(np.ma.asarray(artist.get_array(), dtype=float), np.nan))
        finite = values[np.isfinite(values)]
        if finite.size > 1 and np.ptp(finite) == 0.0:
            yield f"constant field: {ax.get_title() or 'an axes'} shows {finite[0]:g} everywhere"


def _cut_off(text: Text, box: Bbox) -> bool:
    """Whether ``text`` is clipped to a box (a contour label to its axes) it overruns."""
    clip = text.get_clip_box() if text.get_clip_on() else None
    if clip is None:
        return False
    return bool(box.x0 < clip.x0 - EDGE_PX or box.y0 < clip.y0 - EDGE_PX
                or box.x1 > clip.x1 + EDGE_PX or box.y1 > clip.y1 + EDGE_PX)  # fmt: skip


def _text_defects(fig: Figure, renderer: RendererBase) -> list[str]:
    defects: list[str] = []
    boxes: list[tuple[Text, Bbox]] = []
    edge = fig.bbox
    for text in _visible_texts(fig):
        box = _extent(text, renderer)
        if box is None:
            continue
        boxes.append((text, box))
        if (box.x0 < edge.x0 - EDGE_PX or box.y0 < edge.y0 - EDGE_PX
                or box.x1 > edge.x1 + EDGE_PX or box.y1 > edge.y1 + EDGE_PX):  # fmt: skip
            defects.append(f"clipped: {_label(text)!r} reaches beyond the figure's edge")
        elif _cut_off(text, box):
            defects.append(f"clipped: {_label(text)!r} reaches beyond the box it is clipped to")
        for problem in _symbol_defects(text.get_text()):
            defects.append(f"symbol: {_label(text)!r} has {problem}")
    for (a, box_a), (b, box_b) in itertools.combinations(boxes, 2):
        if _overlap(box_a, box_b):
            defects.append(f"overlap: {_label(a)!r} and {_label(b)!r}")
    return defects


def _colourbar_defects(bars: dict[Axes, list[Axes]], renderer: RendererBase) -> list[str]:
    defects = []
    for bar, owners in bars.items():
        label = bar.yaxis.label.get_text() or bar.xaxis.label.get_text()
        declared = _declared(bar.yaxis) or _declared(bar.xaxis)
        if not label:
            defects.append("axis label: a colour bar has no label")
        elif not declared and not _UNIT.search(label):
            defects.append(f"axis label: colour bar {label!r} names no unit in brackets")
        if not owners:
            continue
        outer = bar.get_window_extent(renderer)
        inner = Bbox.union([o.get_window_extent(renderer) for o in owners])
        vertical = outer.height >= outer.width
        lo, hi, a_lo, a_hi = (
            (outer.y0, outer.y1, inner.y0, inner.y1) if vertical
            else (outer.x0, outer.x1, inner.x0, inner.x1)
        )  # fmt: skip
        slack = COLOURBAR_SLACK * (a_hi - a_lo)
        if lo < a_lo - slack or hi > a_hi + slack:
            defects.append(f"colour bar: the bar of {owners[0].get_title() or 'an axes'!r} "
                           "runs beyond its axes")  # fmt: skip
    return defects


def _declared(axis: object) -> bool:
    return bool(getattr(axis, "dexlab_dimensionless", False))


def _axis_defects(ax: Axes) -> list[str]:
    defects = []
    axes_to_check = [("x", ax.xaxis), ("y", ax.yaxis)]
    if hasattr(ax, "zaxis"):
        axes_to_check.append(("z", ax.zaxis))
    for name, axis in axes_to_check:
        if not axis.get_visible() or not any(t.get_text() for t in axis.get_ticklabels()):
            continue
        label = axis.label.get_text()
        if not label:
            defects.append(f"axis label: the {name} axis of {ax.get_title()!r} has none")
        elif not _UNIT.search(label) and not _declared(axis):
            defects.append(f"axis label: {label!r} names no unit in brackets")
    return defects


def figure_defects(fig: Figure) -> list[str]:
    """The defects of ``fig`` (see the module doc), one line each."""
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    defects = _text_defects(fig, renderer)
    bars = _colourbar_axes(fig)
    defects += _colourbar_defects(bars, renderer)
    for ax in fig.axes:
        if ax in bars or not ax.get_visible() or not ax.axison:
            continue
        defects += _axis_defects(ax)
        defects.extend(_constant_fields(ax))
        defects += contour_defects(ax, renderer)
    return defects
