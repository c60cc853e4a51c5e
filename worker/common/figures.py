"""Turn a finished :class:`matplotlib.figure.Figure` into PNG and SVG artifacts, and the
two helpers every family's figures share (literal text, argument errors).

No pyplot and no global state: figures are plain ``Figure`` objects, rendered through
the format's own canvas by ``Figure.savefig``.  The only rcParams touched is
``svg.hashsalt``, and only inside an ``rc_context`` around the SVG export (the worker
runs jobs in processes, one job per process at a time, so the context cannot leak into
another job's figure).
"""

from __future__ import annotations

import io
from typing import Any

import numpy as np
from matplotlib import rc_context
from matplotlib.figure import Figure

from worker.common.contour_labels import contour_labels, freeze_layout
from worker.contract import Artifact

__all__ = [
    "RASTER_DPI",
    "bad_figure_argument",
    "categorical",
    "contour_labels",
    "dimensionless",
    "explained_constant",
    "figure_artifacts",
    "freeze_layout",
    "plain_text",
]

#: Resolution of the PNG, and of any rasterised layer (heat-map images) inside the SVG.
RASTER_DPI = 150


def figure_artifacts(fig: Figure, stem: str, title: str) -> tuple[Artifact, Artifact]:
    """Render ``fig`` as ``(png, svg)`` artifacts named ``{stem}.png`` and ``{stem}.svg``.

    Both carry ``title`` (as the artifact title and in the file's own metadata).  The SVG
    is reproducible: no date, and element ids salted with the stem instead of a random
    value, so identical figures give identical bytes.  Text in the SVG is drawn as
    paths, so it looks the same in every viewer; each string is also kept in an XML
    comment next to its glyphs, which keeps the file searchable.
    """
    if not stem or "/" in stem or "\\" in stem:
        raise ValueError(
            "The 'stem' parameter of figure_artifacts must be a non-empty file name "
            f"without path separators. Got {stem!r} instead."
        )
    png = io.BytesIO()
    svg = io.BytesIO()
    # Matplotlib's 3-D projection multiplies the unused padding of its face arrays
    # (uninitialised memory) by the view matrix; at small length scales that overflows
    # now and then, warning about values that are never drawn.
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        fig.savefig(png, format="png", dpi=RASTER_DPI, metadata={"Title": title})
        with rc_context({"svg.hashsalt": f"dexlab:{stem}"}):
            fig.savefig(svg, format="svg", dpi=RASTER_DPI, metadata={"Date": None, "Title": title})
    return (
        Artifact(name=f"{stem}.png", media_type="image/png", data=png.getvalue(), title=title),
        Artifact(name=f"{stem}.svg", media_type="image/svg+xml", data=svg.getvalue(), title=title),
    )


def bad_figure_argument(name: str, where: str, expected: str, got: str) -> ValueError:
    """The ValueError for argument ``name`` of figure function ``where``: it must be
    ``expected`` and was ``got`` (already worded, e.g. ``"shape (3,)"``)."""
    return ValueError(f"The '{name}' parameter of {where} must be {expected}. Got {got} instead.")


def plain_text(text: str) -> str:
    """Text shown literally: a user's ``$`` must not start mathtext."""
    return text.replace("$", r"\$")


def dimensionless(*axes: Any) -> None:
    """Declare axes (``ax.xaxis``, a colour bar's ``cbar.ax.yaxis``) whose quantity is a
    pure number (1/kappa, an index, a fraction): their labels need no unit.  The figure
    check (tests/figure_check.py) reads the declaration."""
    for axis in axes:
        axis.dexlab_dimensionless = True


def categorical(*axes: Any) -> None:
    """Declare axes whose ticks are names (chains, links, starts): no unit."""
    dimensionless(*axes)


def explained_constant(ax: Any, why: str | None = None) -> None:
    """Say on ``ax`` why the field it shows may be the same everywhere (the figure check
    refuses a constant field otherwise): ``why`` is drawn on it; None when the field's
    cells are labelled already (a table)."""
    ax.dexlab_constant_explained = True
    if why is None:
        return
    ax.text(
        0.5, 0.5, why, transform=ax.transAxes, ha="center", va="center", fontsize=9,
        wrap=True, bbox={"boxstyle": "round", "facecolor": "white", "alpha": 0.85},
    )  # fmt: skip
