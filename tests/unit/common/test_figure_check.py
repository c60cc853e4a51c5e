"""The figure check finds what a reader would see: a deliberately broken figure fails
it on every count, a clean one passes."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure
from matplotlib.path import Path

from tests.figure_check import figure_defects
from worker.common.figures import dimensionless, explained_constant


def clean() -> Figure:
    fig = Figure(figsize=(6.0, 4.0), layout="compressed")
    ax = fig.add_subplot()
    image = ax.imshow(np.arange(12.0).reshape(3, 4), extent=(0, 4, 0, 3))
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(r"A map of $1/\kappa$")
    bar = fig.colorbar(image, ax=ax)
    bar.set_label(r"$1/\kappa$")
    dimensionless(bar.ax.yaxis)
    return fig


def test_a_clean_figure_passes() -> None:
    assert figure_defects(clean()) == []


def test_a_broken_figure_fails_on_every_count() -> None:
    fig = Figure(figsize=(4.0, 3.0))
    ax = fig.add_subplot()
    ax.imshow(np.full((3, 4), 7.0), extent=(0, 4, 0, 3))  # a constant field
    ax.set_xlabel("x")  # no unit
    ax.text(1.0, 1.0, "label one", fontsize=12)
    ax.text(1.1, 1.05, "label two", fontsize=12)  # on top of the first
    fig.suptitle("A title far too long to fit in this narrow figure, clipped at both ends",
                 fontsize=16)  # fmt: skip
    ax.set_title("1/κ and beta_min, P_norm")  # Greek, a Greek name, a subscript as text
    other = fig.add_axes((0.1, 0.1, 0.3, 0.2))
    mesh = other.pcolormesh(np.random.default_rng(1).random((3, 3)))
    cax = fig.add_axes((0.9, 0.05, 0.03, 0.9))  # far taller than the axes it belongs to
    fig.colorbar(mesh, cax=cax, label="weights")
    kinds = {line.split(":")[0] for line in figure_defects(fig)}
    assert kinds == {"overlap", "clipped", "symbol", "axis label", "constant field", "colour bar"}
    lines = "\n".join(figure_defects(fig))
    assert "'label one' and 'label two'" in lines
    assert "Greek letter outside mathtext" in lines and "('beta')" in lines
    assert "('P_norm')" in lines and "'x' names no unit" in lines


def test_a_constant_field_may_say_why() -> None:
    fig = clean()
    ax = fig.axes[0]
    ax.images[0].set_data(np.full((3, 4), 90.0))
    assert any(line.startswith("constant field") for line in figure_defects(fig))
    explained_constant(ax, "90° everywhere: the legs push along themselves")
    assert not any(line.startswith("constant field") for line in figure_defects(fig))


def test_a_filled_contour_of_one_band_is_a_constant_field() -> None:
    fig = Figure()
    ax = fig.add_subplot()
    ax.contourf(np.full((5, 5), 90.0), levels=[0, 30, 60, 89, 91])
    assert any(line.startswith("constant field") for line in figure_defects(fig))


def test_mathtext_and_escaped_dollars_are_not_symbols() -> None:
    fig = clean()
    fig.axes[0].set_title(r"$\beta_{\min}$ and $d_z$ cost \$5 (a user's text)")
    assert figure_defects(fig) == []


def framed() -> tuple[Figure, Any]:
    """A figure with one labelled axes and room for its labels, laid out by hand."""
    fig = Figure(figsize=(5.0, 5.0))
    fig.subplots_adjust(left=0.16, bottom=0.14)
    ax = fig.add_subplot()
    ax.set(xlabel="x [mm]", ylabel="y [mm]")
    return fig, ax


def ring_field(ax: Any, n: int = 61) -> Any:
    """White contour rings of r^2 on a filled field, the kind the maps draw."""
    x = np.linspace(-1.0, 1.0, n)
    field = np.add.outer(x**2, x**2)
    ax.contourf(x, x, field, levels=8)
    return ax.contour(x, x, field, levels=[0.2, 0.5, 0.8], colors="white")


def test_contour_lines_broken_only_under_their_labels_pass() -> None:
    fig, ax = framed()
    ax.clabel(ring_field(ax), inline=True, fmt="%.1f")
    assert figure_defects(fig) == []


def test_axes_grown_after_labelling_leave_gaps_without_labels() -> None:
    # As when a layout engine moves the axes after clabel: the gaps, cut in data space,
    # grow with the axes; the labels keep their size.
    fig, ax = framed()
    ax.clabel(ring_field(ax), inline=True, fmt="%.1f")
    fig.set_size_inches(10.0, 10.0)
    broken = [line for line in figure_defects(fig) if line.startswith("broken contour")]
    assert broken and all("has a gap with no label" in line for line in broken)


def test_a_gap_cut_by_hand_is_a_broken_contour() -> None:
    fig, ax = framed()
    lines = ring_field(ax)
    path = lines.get_paths()[1]
    keep = np.ones(len(path.vertices), dtype=bool)
    keep[10:20] = False  # a piece of the 0.5 ring gone, no label there
    codes = path.codes[keep].copy()
    codes[10] = Path.MOVETO
    lines.get_paths()[1] = Path(path.vertices[keep], codes)
    lines.set_paths(lines.get_paths())
    defects = figure_defects(fig)
    assert len(defects) == 2 and all(d.startswith("broken contour: the 0.5 line") for d in defects)


def test_a_label_over_the_end_of_its_line_is_found() -> None:
    # The 0.5 level of x + y over this square is a short line across a corner: its label
    # hangs over both ends, as "0.100" did over the edge of the design space. The label
    # of the -0.5 line, in the middle of it, is fine.
    fig, ax = framed()
    x = np.linspace(-1.0, 0.3, 40)
    lines = ax.contour(x, x, np.add.outer(x, x), levels=[-0.5, 0.5], colors="k")
    ax.clabel(lines, inline=False, fmt="%.2f", fontsize=14,
              manual=[(0.25, 0.25), (-0.25, -0.25)])  # fmt: skip
    labels = [line for line in figure_defects(fig) if line.startswith("contour label")]
    assert labels == ["contour label: '0.50' on 'an axes' hangs over the end of its line"]


def test_a_contour_label_cut_off_at_its_axes_edge_is_clipped() -> None:
    fig, ax = framed()
    lines = ring_field(ax)
    (label,) = ax.clabel(lines, levels=[0.8], inline=False, fmt="%.1f", manual=[(0.0, 0.9)])
    label.set_position((0.99, 0.0))  # its box now runs past the axes
    assert "clipped: '0.8' reaches beyond the box it is clipped to" in figure_defects(fig)
