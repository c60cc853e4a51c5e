"""The figure check finds what a reader would see: a deliberately broken figure fails
it on every count, a clean one passes."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

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
