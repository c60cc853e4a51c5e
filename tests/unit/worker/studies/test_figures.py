"""A study's figures, read off the Figure objects: the first varied input on x (alpha1,
as every SPM figure has it), objectives labelled with their symbol and unit, the
non-dominated designs drawn over the paper's markers."""

from __future__ import annotations

import numpy as np
from matplotlib.collections import QuadMesh
from matplotlib.lines import Line2D

from tests.figure_check import figure_defects
from worker.studies.figures import (
    Marker,
    objective_label,
    objective_maps_figure,
    objective_slices_figure,
    pareto_figure,
)

ALPHA1 = np.array([30.0, 60.0, 90.0])
ALPHA2 = np.array([60.0, 80.0, 100.0, 120.0])
LABELS = [r"$\mathtt{alpha1\_deg}$ [deg]", r"$\mathtt{alpha2\_deg}$ [deg]"]
TABLE_1 = Marker("Table 1", (60.0, 100.0), (0.55, 0.30))


def test_the_first_varied_input_is_on_x() -> None:
    values = np.add.outer(ALPHA1, ALPHA2 / 1000)  # (alpha1, alpha2): the designs' order
    label = objective_label("indices.rms_inverse_condition", "$C_n$", "-")
    fig = objective_maps_figure([ALPHA1, ALPHA2], LABELS, [values], [label], "t", [TABLE_1])
    ax = fig.axes[0]
    assert "alpha1" in ax.get_xlabel() and "alpha2" in ax.get_ylabel()
    (mesh,) = [c for c in ax.collections if isinstance(c, QuadMesh)]
    coordinates = mesh.get_coordinates()  # (rows = y, columns = x, 2)
    assert coordinates.shape[:2] == (len(ALPHA2) + 1, len(ALPHA1) + 1)
    drawn = np.asarray(mesh.get_array()).reshape(len(ALPHA2), len(ALPHA1))
    np.testing.assert_array_equal(drawn, values.T)  # the value at (alpha1, alpha2) is there
    (marker,) = [line for line in ax.get_lines() if line.get_label() == "Table 1"]
    assert (marker.get_xdata()[0], marker.get_ydata()[0]) == (60.0, 100.0)
    assert not figure_defects(fig)


def test_small_multiples_keep_the_order_of_the_other_two() -> None:
    beta = np.array([80.0, 90.0])
    values = np.zeros((3, 4, 2))
    labels = [*LABELS, r"$\mathtt{beta\_deg}$ [deg]"]
    fig = objective_slices_figure([ALPHA1, ALPHA2, beta], labels, [values], ["v [-]"], "t")
    first = fig.axes[0]
    assert "alpha1" in first.get_xlabel() and "alpha2" in first.get_ylabel()
    assert "beta" in first.get_title()


def test_objectives_are_labelled_with_symbol_and_unit() -> None:
    assert objective_label("task_points[].d_z|min", "$d_z$", "-") == (
        r"$\mathtt{task\_points[].\!d\_z|min}$" "\nmin $d_z$ [-]"
    )
    assert objective_label("areas.reachable", "", "cm^2").endswith(" [cm$^2$]")
    assert objective_label("optimum.eta", r"$\eta$", "-").endswith("\n" r"$\eta$ [-]")


def test_the_front_is_drawn_over_the_papers_designs() -> None:
    objectives = np.array([[0.55, 0.30], [0.50, 0.35], [0.40, 0.20], [0.30, 0.10]])
    front = np.array([0, 1])
    fig = pareto_figure(objectives, front, ["a [-]", "b [-]"], ["max", "max"], "t",
                        [TABLE_1, Marker("twin", (120.0, 100.0), (0.55, 0.30))])  # fmt: skip
    ax = fig.axes[0]
    lines = {line.get_label(): line for line in ax.get_lines()}
    front_line = lines["non-dominated (2)"]
    papers = [line for label, line in lines.items() if label.startswith("the paper's")]
    assert len(papers) == 2
    assert all(front_line.get_zorder() > paper.get_zorder() for paper in papers)
    # distinguishable: filled red dots against hollow dark shapes
    assert front_line.get_marker() == "o" and front_line.get_markerfacecolor() != "none"
    assert all(isinstance(p, Line2D) and p.get_markerfacecolor() == "none" for p in papers)
    assert {p.get_marker() for p in papers}.isdisjoint({"o", "."})
    assert not figure_defects(fig)


def test_a_large_cloud_is_an_image_in_the_svg() -> None:
    """200,000 designs in the objective space: the cloud and a long front are drawn as
    images inside the SVG, which stays small (vector markers made ~40 MB)."""
    from worker.common.figures import figure_artifacts

    rng = np.random.default_rng(2)
    values = rng.random((200_000, 2))
    front = np.flatnonzero(values.sum(axis=1) < 0.1)
    labels = [objective_label("a", "", "-"), objective_label("b", "", "-")]
    fig = pareto_figure(values, front, labels, ["min", "min"], "t")
    _, svg = figure_artifacts(fig, "pareto", "t")
    assert len(svg.data) < 3_000_000
    assert b"<image" in svg.data
