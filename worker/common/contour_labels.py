"""Contour labels that sit on their lines, in gaps cut where they are drawn.

``Axes.clabel(inline=True)`` cuts a gap under each label in data space, sized for the
axes as they are at that moment. Two things spoil that, and both are handled here:

* a layout engine that moves or resizes the axes afterwards (a colour bar, a title or a
  legend added later) leaves the gaps where the labels no longer are: the line is
  broken into stubs. :func:`freeze_layout` lays the finished figure out once and keeps
  that layout, so labels placed after it stay in their gaps;
* a label placed near the end of a line (at the edge of the field) or on a loop smaller
  than itself hangs over the end, onto whatever lies beside the field (white text on a
  white margin reads as a clipped number). :func:`contour_labels` keeps only labels
  whose line runs on beyond them on both sides.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
from matplotlib.figure import Figure
from matplotlib.path import Path
from matplotlib.transforms import Bbox
from numpy.typing import NDArray

__all__ = ["contour_labels", "freeze_layout"]

#: Line left beyond each end of a label (points), besides the gap clabel cuts.
_CLEARANCE_PT = 3.0


def freeze_layout(fig: Figure) -> None:
    """Lay ``fig`` out with its layout engine once, then keep that layout.

    Call it when the figure is otherwise complete and before :func:`contour_labels`:
    nothing added afterwards is laid out.
    """
    engine = fig.get_layout_engine()
    if engine is None:
        return
    engine.execute(fig)
    fig.set_layout_engine("none")


def _pieces(path: Path) -> Iterator[tuple[NDArray[np.float64], bool]]:
    """(vertices (n, 2), closed) of each connected piece of ``path``."""
    vertices = np.asarray(path.vertices, dtype=np.float64)
    codes = None if path.codes is None else np.asarray(path.codes)
    if len(vertices) == 0:
        return
    if codes is None:
        yield vertices, False
        return
    starts = [*np.flatnonzero(codes == Path.MOVETO), len(vertices)]
    for start, stop in itertools.pairwise(starts):
        if stop > start:
            yield vertices[start:stop], bool(codes[stop - 1] == Path.CLOSEPOLY)


def _room_on_line(lines: Any, level_index: int, anchor: NDArray[np.float64]) -> float:
    """Line length (pixels) on the shorter side of ``anchor`` (pixels) along the piece of
    the level's line nearest to it; for a closed loop, half its length."""
    transform = lines.get_transform()
    best: tuple[float, float] | None = None
    for vertices, closed in _pieces(lines.get_paths()[level_index]):
        shown = transform.transform(vertices)
        steps = np.hypot(*np.diff(shown, axis=0).T)
        along = np.concatenate([[0.0], np.cumsum(steps)])
        gaps = np.hypot(*(shown - anchor).T)
        k = int(np.argmin(gaps))
        room = along[-1] / 2.0 if closed else min(along[k], along[-1] - along[k])
        if best is None or gaps[k] < best[0]:
            best = (float(gaps[k]), float(room))
    return 0.0 if best is None else best[1]


def _on_its_line(text: Any, lines: Any, level_index: int, spacing_px: float) -> bool:
    """Whether the line of ``text`` (a label placed without a gap) runs beyond it by
    ``spacing_px`` on both sides."""
    anchor = np.asarray(text.get_transform().transform(text.get_position()), dtype=np.float64)
    text.set_rotation(0.0)  # a probe, removed after: its unrotated width
    width = float(text.get_window_extent().width)
    return _room_on_line(lines, level_index, anchor) >= width / 2.0 + spacing_px


def contour_labels(
    ax: Any,
    lines: Any,
    *,
    margin: float = 0.05,
    keep: Callable[[float, float], bool] | None = None,
    **kwargs: Any,
) -> list[Any]:
    """``ax.clabel(lines, **kwargs)``, keeping only readable labels: none within
    ``margin`` (a fraction of the view) of the axes' edge, where it would be clipped or
    run into a title, none where ``keep(x, y)`` (data coordinates) is false, none over
    a label kept before it, none whose line does not run on beyond it on both sides (at
    the edge of the field, or on a loop smaller than the label), and every label upright
    (rotations in [-90°, 90°]).  Labels are placed once to find where they would go, then
    again at the places kept, so no contour line keeps a gap for a label that was
    dropped.

    The gaps are cut for the axes' size now: in a figure with a layout engine, label
    last, after :func:`freeze_layout`.
    """
    inline = kwargs.pop("inline", True)
    # clabel's inline_spacing is in pixels (5 by default).
    spacing_px = float(kwargs.get("inline_spacing", 5)) + _CLEARANCE_PT * ax.figure.dpi / 72.0
    probe = list(ax.clabel(lines, inline=False, **kwargs))
    index_of = {float(c): i for i, c in enumerate(lines.cvalues)}
    values = [index_of[float(c)] for c in lines.labelCValues]
    (x0, x1), (y0, y1) = sorted(ax.get_xlim()), sorted(ax.get_ylim())
    dx, dy = margin * (x1 - x0), margin * (y1 - y0)
    places: list[tuple[float, float]] = []
    taken: list[Bbox] = []
    for text, level_index in zip(probe, values, strict=True):
        x, y = (float(v) for v in text.get_position())
        box = text.get_window_extent()
        inside = x0 + dx <= x <= x1 - dx and y0 + dy <= y <= y1 - dy
        if (inside and (keep is None or keep(x, y))
                and not any(box.overlaps(other) for other in taken)
                and _on_its_line(text, lines, level_index, spacing_px)):  # fmt: skip
            places.append((x, y))
            taken.append(box)
        text.remove()
    for attribute in ("labelTexts", "labelCValues", "labelXYs"):
        getattr(lines, attribute, []).clear()
    if not places:
        return []
    kwargs.pop("levels", None)
    texts = list(ax.clabel(lines, manual=places, inline=inline, **kwargs))
    for text in texts:
        angle = text.get_rotation() % 360.0
        if 90.0 < angle < 270.0:
            text.set_rotation(angle - 180.0)
    return texts
