"""The contour-line part of the figure check (:mod:`tests.figure_check`).

A labelled contour line drawn with ``inline=True`` has a gap cut under each label. The
gaps are cut in data space for the axes' size at the time of labelling, so a layout
that moves the axes afterwards leaves gaps where no label is (the line broken into
stubs), or labels over unbroken lines. And a label placed near the end of its line (at
the edge of the field) hangs over the end, onto whatever is beside the field. Found here:

- **broken contour**: an end of a drawn contour piece that is not an end of the contour
  line (as the contour generator traces it) and has no label of that contour set
  beside it;
- **contour label**: a label whose line does not run beyond it on both sides (it hangs
  over the end of its line, or is bigger than its whole loop).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator

import numpy as np
from matplotlib.axes import Axes
from matplotlib.backend_bases import RendererBase
from matplotlib.contour import ContourSet
from matplotlib.path import Path
from matplotlib.text import Text
from numpy.typing import NDArray

__all__ = ["contour_defects"]

#: How far (points) the end of a gap may be from its label: matplotlib leaves
#: ``inline_spacing`` (5 px by default) beyond the label's width on each side.
GAP_END_PT = 6.0
#: Two ends this close (pixels) are the same point.
SAME_POINT_PX = 0.5

Points = NDArray[np.float64]


class _Label:
    """A contour label as drawn: its anchor, angle and unrotated box (pixels)."""

    def __init__(self, text: Text, renderer: RendererBase) -> None:
        self.text = text
        self.centre = np.asarray(text.get_transform().transform(text.get_position()), float)
        self.angle = math.radians(text.get_rotation())
        rotation = text.get_rotation()
        text.set_rotation(0.0)  # the unrotated box, about the same centre (ha, va centre)
        box = text.get_window_extent(renderer)
        text.set_rotation(rotation)
        self.half = np.array([box.width / 2.0, box.height / 2.0])
        self.offset = np.array([(box.x0 + box.x1) / 2.0, (box.y0 + box.y1) / 2.0]) - self.centre

    def local(self, points: Points) -> Points:
        """``points`` (n, 2) in the label's frame: centred, along and across the text."""
        c, s = math.cos(self.angle), math.sin(self.angle)
        d = points - self.centre
        along = d[:, 0] * c + d[:, 1] * s
        across = -d[:, 0] * s + d[:, 1] * c
        return np.column_stack([along, across]) - self.offset

    def distance(self, points: Points) -> Points:
        """Distance (pixels) of ``points`` (n, 2) from the label's box (0 inside)."""
        outside = np.maximum(np.abs(self.local(points)) - self.half, 0.0)
        return np.asarray(np.hypot(outside[:, 0], outside[:, 1]), dtype=float)


def _components(path: Path) -> Iterator[tuple[Points, bool]]:
    """(vertices, closed) of each connected piece of ``path``."""
    vertices = np.asarray(path.vertices, dtype=float)
    if len(vertices) == 0:
        return
    codes = path.codes
    if codes is None:
        codes = np.full(len(vertices), Path.LINETO)
        codes[0] = Path.MOVETO
    starts = [*np.flatnonzero(codes == Path.MOVETO), len(vertices)]
    for start, stop in itertools.pairwise(starts):
        if stop > start:
            yield vertices[start:stop], bool(codes[stop - 1] == Path.CLOSEPOLY)


def _traced(contours: ContourSet, level: float) -> list[tuple[Points, bool]]:
    """The lines of ``level`` as the generator traces them, before any label cut them."""
    vertices, codes = contours._contour_generator.create_contour(level)
    if not len(vertices):
        return []
    return list(_components(Path(np.concatenate(vertices), np.concatenate(codes))))


def _hangs_over(label: _Label, lines: list[tuple[Points, bool]]) -> bool:
    """Whether the label's line fails to run beyond its box on either side."""
    best: tuple[float, int, Points, bool] | None = None
    for points, closed in lines:
        if len(points) == 0:
            continue
        gaps = np.hypot(*(points - label.centre).T)
        k = int(np.argmin(gaps))
        if best is None or gaps[k] < best[0]:
            best = (float(gaps[k]), k, points, closed)
    if best is None:
        return True
    _, k, points, closed = best
    outside = label.distance(points) > 0.0
    if closed:
        return not outside.any()
    return not (outside[:k].any() and outside[k + 1 :].any())


def _set_defects(ax: Axes, contours: ContourSet, renderer: RendererBase) -> Iterator[str]:
    where = ax.get_title() or "an axes"
    trans = contours.get_transform()
    # A label keeps its level's colour value (the level itself, or its index when the
    # lines have given colours): cvalues and levels are parallel.
    level_of = {float(c): float(v) for c, v in zip(contours.cvalues, contours.levels, strict=True)}
    labels = [
        (_Label(text, renderer), level_of[float(value)])
        for text, value in zip(contours.labelTexts, contours.labelCValues, strict=False)
        if text.get_visible() and text.get_text().strip()
    ]
    tolerance = GAP_END_PT * contours.axes.figure.dpi / 72.0
    for level, path in zip(contours.levels, contours.get_paths(), strict=False):
        traced = [(trans.transform(p), closed) for p, closed in _traced(contours, level)]
        ends = [p[[0, -1]] for p, closed in traced if not closed]
        true_ends = np.concatenate(ends) if ends else np.empty((0, 2))
        for piece, closed in _components(path):
            if closed:
                continue
            for end in trans.transform(piece[[0, -1]]):
                if len(true_ends) and np.hypot(*(true_ends - end).T).min() < SAME_POINT_PX:
                    continue
                if any(lab.distance(end[None, :])[0] <= tolerance for lab, _ in labels):
                    continue
                yield (f"broken contour: the {level:g} line of {where!r} has a gap with no "
                       f"label at ({end[0]:.0f}, {end[1]:.0f}) px")  # fmt: skip
        for label, value in labels:
            if math.isclose(value, level) and _hangs_over(label, traced):
                yield (f"contour label: {label.text.get_text()!r} on {where!r} hangs over "
                       "the end of its line")  # fmt: skip


def contour_defects(ax: Axes, renderer: RendererBase) -> list[str]:
    """The defects of the labelled contour lines of ``ax`` (drawn with ``renderer``)."""
    defects: list[str] = []
    for artist in ax.collections:
        if (isinstance(artist, ContourSet) and not artist.filled and artist.get_visible()
                and getattr(artist, "_contour_generator", None) is not None):  # fmt: skip
            defects.extend(_set_defects(ax, artist, renderer))
    return defects
