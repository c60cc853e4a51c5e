"""What the example notebook's figures show, recorded from inside its kernel.

tests/integration/test_notebook.py runs a cell calling :func:`record_figures` before the
notebook's own cells: every ``plt.show()`` then first writes one JSON line per open
figure to a file, with

- ``defects``: the figure check's findings (tests/figure_check.py); an axis whose tick
  labels are all names (chains, not numbers) is declared categorical first, as the
  service's own figures declare theirs;
- ``finite_cells``: how many cells of its colour meshes and images show a value (not
  masked, not NaN), to compare with how many nodes can be reached;
- ``w_kappa0``: the vertices (data coordinates) of every artist whose label names
  W_kappa0, so the test can compare them with the set's boundary.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.axis import Axis
from matplotlib.collections import Collection
from matplotlib.figure import Figure
from matplotlib.image import AxesImage
from matplotlib.lines import Line2D

from tests.figure_check import figure_defects
from worker.common.figures import categorical

__all__ = ["figure_record", "record_figures"]


def _is_number(text: str) -> bool:
    try:
        float(text.replace("\N{MINUS SIGN}", "-").rstrip("°"))
    except ValueError:
        return False
    return True


def _names_only(axis: Axis) -> bool:
    labels = [t.get_text() for t in axis.get_ticklabels() if t.get_text()]
    return bool(labels) and not any(_is_number(text) for text in labels)


def _finite_cells(fig: Figure) -> int:
    count = 0
    for ax in fig.axes:
        if getattr(ax, "_colorbar", None) is not None:  # a colour bar's own mesh
            continue
        for artist in [*ax.images, *ax.collections]:
            if not isinstance(artist, AxesImage | Collection) or artist.get_array() is None:
                continue
            if getattr(artist, "levels", None) is not None:  # a contour set: lines, not cells
                continue
            values = np.ma.filled(np.ma.asarray(artist.get_array(), dtype=float), np.nan)
            count += int(np.isfinite(values).sum())
    return count


def _w_kappa0(fig: Figure) -> list[list[float]]:
    vertices: list[list[float]] = []
    for ax in fig.axes:
        for artist in [*ax.lines, *ax.collections]:
            if "W_" not in str(artist.get_label()):
                continue
            if isinstance(artist, Line2D):
                vertices += np.asarray(artist.get_xydata(), dtype=float).tolist()
            elif isinstance(artist, Collection):
                for path in artist.get_paths():
                    vertices += np.asarray(path.vertices, dtype=float).tolist()
    return vertices


def figure_record(fig: Figure) -> dict[str, Any]:
    """One figure's record (see the module doc)."""
    canvas = fig.canvas
    fig.draw_without_rendering()  # tick labels are set at draw time
    for ax in fig.axes:
        categorical(*(axis for axis in (ax.xaxis, ax.yaxis) if _names_only(axis)))
    defects = figure_defects(fig)
    fig.set_canvas(canvas)  # figure_defects drew it on a canvas of its own
    title = fig.get_suptitle() or (fig.axes[0].get_title() if fig.axes else "")
    return {
        "title": title,
        "defects": defects,
        "finite_cells": _finite_cells(fig),
        "w_kappa0": _w_kappa0(fig),
    }


def record_figures(path: str) -> None:
    """Make ``plt.show()`` append each open figure's record to ``path`` first."""
    import matplotlib.pyplot as plt

    show = plt.show
    target = Path(path)

    def recorded_show(*args: Any, **kwargs: Any) -> Any:
        with target.open("a", encoding="utf-8") as out:
            for number in plt.get_fignums():
                out.write(json.dumps(figure_record(plt.figure(number))) + "\n")
        return show(*args, **kwargs)

    plt.show = recorded_show
