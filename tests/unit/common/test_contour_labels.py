"""Contour labels sit on their lines, in gaps cut where they are drawn."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from tests.figure_check import figure_defects
from worker.common.contour_labels import contour_labels, freeze_layout


def rings() -> tuple[Figure, object, object]:
    """A constrained figure of r^2 rings with a colour bar and a title: the layout moves
    the axes once all of it is there."""
    fig = Figure(figsize=(6.0, 5.0), layout="constrained")
    ax = fig.add_subplot()
    x = np.linspace(-1.0, 1.0, 81)
    field = np.add.outer(x**2, x**2)
    filled = ax.contourf(x, x, field, levels=10)
    lines = ax.contour(x, x, field, levels=[0.1, 0.3, 0.5, 0.7, 0.9], colors="white")
    ax.set(xlabel="x [mm]", ylabel="y [mm]", aspect="equal")
    fig.colorbar(filled, ax=ax).set_label(r"$r^2$ [mm$^2$]")
    fig.suptitle("Rings\nof a paraboloid")
    return fig, ax, lines


def test_labels_placed_after_freeze_layout_sit_in_their_gaps() -> None:
    fig, ax, lines = rings()
    freeze_layout(fig)
    texts = contour_labels(ax, lines, fmt="%.1f", fontsize=8)
    assert texts and figure_defects(fig) == []


def test_freeze_layout_keeps_the_laid_out_positions() -> None:
    fig, ax, _ = rings()
    freeze_layout(fig)
    laid_out = ax.get_position().bounds
    fig.suptitle("A longer title\nover\nthree lines")  # would move the axes if laid out
    fig.draw_without_rendering()
    assert ax.get_position().bounds == laid_out


def test_labels_whose_line_ends_under_them_are_dropped() -> None:
    # x + y = 0.55 crosses the square's corner in a line shorter than its label; the
    # line x + y = -0.5 runs across the whole square.
    fig = Figure(figsize=(5.0, 5.0))
    ax = fig.add_subplot()
    x = np.linspace(-1.0, 0.3, 40)
    lines = ax.contour(x, x, np.add.outer(x, x), levels=[-0.5, 0.55], colors="k")
    texts = contour_labels(ax, lines, fmt="%.2f", fontsize=14, margin=0.0)
    assert [t.get_text() for t in texts] == ["-0.50"]


def test_labels_do_not_overlap() -> None:
    fig = Figure(figsize=(4.0, 4.0))
    ax = fig.add_subplot()
    x = np.linspace(-1.0, 1.0, 81)
    lines = ax.contour(x, x, np.add.outer(x, 0.0 * x), levels=np.linspace(-0.9, 0.9, 37))
    texts = contour_labels(ax, lines, fmt="%.3f", fontsize=9)
    fig.draw_without_rendering()
    boxes = [t.get_window_extent() for t in texts]
    assert len(texts) >= 2
    assert not any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1 :])
