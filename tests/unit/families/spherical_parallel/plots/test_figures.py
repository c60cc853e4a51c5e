"""The spherical parallel manipulator's figures, on small synthetic data."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from matplotlib.figure import Figure

from tests.figure_check import figure_defects
from tests.unit.common.test_figures import png_pixels, svg_strings
from worker.common.figures import figure_artifacts
from worker.families.spherical_parallel.plots import conditioning as p
from worker.families.spherical_parallel.plots import design_space as d
from worker.families.spherical_parallel.plots import starts as st
from worker.families.spherical_parallel.plots.cone_panel import disk_image

AZIMUTH = np.linspace(0.0, 360.0, 37)
TILT = np.linspace(0.0, 45.0, 10)


def synthetic_map(torsions: int = 2, hole: bool = False) -> np.ndarray:
    """1/kappa falling from 0.9 at the centre to 0.3 on the rim, rippled in azimuth."""
    tt, aa = np.meshgrid(TILT, np.radians(AZIMUTH), indexing="ij")
    one = 0.9 - 0.6 * (tt / 45.0) ** 2 * (0.8 + 0.2 * np.cos(3 * aa))
    maps = np.stack([one] * torsions)
    if hole:
        maps[:, -2:, :5] = np.nan  # no real solution on part of the rim
    return maps


def map_figure(**overrides: Any) -> Figure:
    kwargs: dict[str, Any] = {"title": "Map test", "subtitle": "cone of 90°",
                              "samples_deg": [[0.0, 20.0, 0.0], [90.0, 40.0, 0.0],
                                              [0.0, 20.0, 120.0]]}  # fmt: skip
    kwargs.update(overrides)
    return p.inverse_condition_map_figure(AZIMUTH, TILT, synthetic_map(hole=True), [0.0, 30.0],
                                          **kwargs)  # fmt: skip


def sweep_figure(**overrides: Any) -> Figure:
    psi3 = np.linspace(0.0, 360.0, 361)
    values = np.stack([0.9 - 0.02 * np.cos(np.radians(3 * psi3)),
                       0.7 - 0.1 * np.cos(np.radians(6 * psi3))])  # fmt: skip
    kwargs: dict[str, Any] = {"title": "Sweep test", "tilt_max_deg": 30.0}
    kwargs.update(overrides)
    return p.torsion_sweep_figure(
        psi3, [[35.0, 15.0], [35.0, 45.0]],
        [p.SweepSeries("optimum", values), p.SweepSeries("paper", values - 0.05)], **kwargs,
    )  # fmt: skip


# -- the workspace figures -------------------------------------------------------------


def test_map_panels_colour_bar_and_legend() -> None:
    fig = map_figure()
    panels = [ax for ax in fig.axes if ax.get_title().startswith("torsion")]
    assert [ax.get_title() for ax in panels] == [r"torsion $\psi_3$ = 0°",
                                                 r"torsion $\psi_3$ = 30°"]  # fmt: skip
    bar = next(ax for ax in fig.axes if ax not in panels)
    assert "1/\\kappa" in bar.get_ylabel()
    strings = svg_strings(figure_artifacts(fig, "map", "Map")[1].data)
    for text in (
        "Map test",
        "no real inverse kinematics",
        "workspace samples at this torsion",
        "90°",
        "270°",
        "20°",
    ):
        assert any(text in s for s in strings), text


def test_map_marks_only_the_samples_at_each_torsion() -> None:
    fig = map_figure()
    first, second = (ax for ax in fig.axes if ax.get_title().startswith("torsion"))
    marked = [line for line in first.get_lines() if line.get_marker() == "o"]
    x, y = np.asarray(marked[0].get_xdata()), np.asarray(marked[0].get_ydata())
    assert len(marked) == 1 and len(x) == 2
    assert not [line for line in second.get_lines() if line.get_marker() == "o"]
    assert (x[1], y[1]) == pytest.approx((0.0, 40.0), abs=1e-9)  # azimuth 90, tilt 40


def test_disk_image_resamples_the_grid() -> None:
    values = synthetic_map(torsions=1)[0]
    image = disk_image(AZIMUTH, TILT, values, pixels=91)
    assert image.shape == (91, 91)
    assert image[45, 45] == pytest.approx(0.9)  # the centre
    assert np.isnan(image[0, 0]) and np.isnan(image[90, 90])  # outside the disk
    # on the +x axis (azimuth 0) at tilt 22.5: the grid's value there
    expected = np.interp(22.5, TILT, values[:, 0])
    assert image[45, 45 + 45 // 2] == pytest.approx(expected, abs=1e-2)


def test_map_renders_as_png() -> None:
    png, _ = figure_artifacts(map_figure(), "map", "Map")
    pixels = np.asarray(png_pixels(png.data))
    assert pixels.ndim == 3 and pixels.shape[2] in (3, 4)


def test_sweep_panels_and_legend() -> None:
    fig = sweep_figure(torsion_range_deg=(-15.0, 15.0))
    axes = fig.axes
    assert len(axes) == 2
    assert axes[1].get_title(loc="left").endswith("(outside the prescribed cone)")
    assert axes[0].get_ylim() == axes[1].get_ylim()  # one scale for every panel
    assert axes[1].get_xlabel() == r"torsion $\psi_3$ [°]"
    strings = svg_strings(figure_artifacts(fig, "sweep", "Sweep")[1].data)
    for text in ("Sweep test", "optimum", "paper", "prescribed torsion range"):
        assert text in strings, text


def test_sweep_panels_give_1_over_kappa_as_a_pure_number() -> None:
    assert [ax.get_ylabel() for ax in sweep_figure().axes] == [r"$1/\kappa$ [-]"] * 2


def test_index_map_labels_sit_on_their_lines_in_their_gaps() -> None:
    # Contours reaching the edge of the rotated rectangle (the design space): no label
    # hangs over a line's end (off the field), no line is broken where no label is.
    s, t = np.meshgrid(np.linspace(-1, 1, 41), np.linspace(-1, 1, 41))
    a1, a2 = 90 + 0.5 * (45 * s + 15 * t), 90 + 0.5 * (15 * t - 45 * s)
    values = 0.08 + 0.15 * s * s + 0.03 * t
    fig = d.index_distribution_figure(a1, a2, values, title="Index", subtitle=r"$\beta$ = 75°")
    (lines,) = [c for c in fig.axes[0].collections if hasattr(c, "labelTexts")]
    assert lines.labelTexts and figure_defects(fig) == []


def test_sweep_with_gaps() -> None:
    psi3 = np.linspace(0.0, 360.0, 13)
    values = np.full((1, 13), 0.5)
    values[0, 3] = np.nan
    fig = p.torsion_sweep_figure(psi3, [[0.0, 10.0]], [p.SweepSeries("x", values)], title="g")
    assert "gaps: no real inverse kinematics" in svg_strings(
        figure_artifacts(fig, "g", "g")[1].data
    )


# -- the design-space figures ----------------------------------------------------------


def test_design_space_rectangles_lines_and_points() -> None:
    spaces = [d.SubDesignSpace(60.0, 0.0, 60.0, 0.0), d.SubDesignSpace(75.0, 0.0, 45.0, 15.0),
              d.SubDesignSpace(90.0, 0.0, 0.0, 0.0)]  # fmt: skip
    fig = d.design_space_figure(spaces, title="Fig 5", subtitle="cone",
                                markers=[d.DesignMarker(60, 105, "optimum")])  # fmt: skip
    ax = fig.axes[0]
    assert ax.get_xlabel().startswith("base-side link angle") and "[°]" in ax.get_xlabel()
    assert len(ax.patches) == 1  # only beta = 75 has an interior
    strings = svg_strings(figure_artifacts(fig, "space", "Space")[1].data)
    for text in ("Fig 5", "(degenerate: a line)", "(empty: only (90, 90))", "optimum"):
        assert any(text in s for s in strings), text
    lo, hi = ax.get_xlim()
    assert lo <= 60.0 and hi >= 120.0


def test_rectangle_corners() -> None:
    np.testing.assert_allclose(d.rectangle_corners(45.0, 15.0),
                               [[60, 105], [105, 60], [120, 75], [75, 120]])  # fmt: skip


def test_many_betas_get_a_colour_bar_and_the_half_widths() -> None:
    spaces = [d.SubDesignSpace(b, 0.0, 135.0 - b, max(0.0, b - 60.0)) for b in range(50, 91, 2)]
    fig = d.design_space_figure(spaces, title="many")
    plane = fig.axes[0]
    widths = next(ax for ax in fig.axes if ax.get_xlabel().startswith("mobile pyramid"))
    bar = next(ax for ax in fig.axes if ax.get_label() == "<colorbar>")
    assert not plane.patches[0].get_facecolor()[3]  # outlines only
    assert widths.get_xlabel().startswith("mobile pyramid half-angle")
    assert "beta" in bar.get_ylabel()
    d1 = widths.get_lines()[0]
    np.testing.assert_allclose(np.asarray(d1.get_ydata()), [135.0 - b for b in range(50, 91, 2)])
    assert [t.get_text() for t in widths.get_legend().get_texts()][-1] == (
        "degenerate (no interior)"
    )


def test_index_distribution() -> None:
    s, t = np.meshgrid(np.linspace(-1, 1, 9), np.linspace(-1, 1, 9))
    a1, a2 = 90 + 0.5 * (45 * s + 15 * t), 90 + 0.5 * (15 * t - 45 * s)
    values = 0.1 + 0.15 * (s * s)
    values[0, 0] = np.nan
    fig = d.index_distribution_figure(
        a1, a2, values, title="Fig 6", subtitle="beta = 75°",
        markers=[d.DesignMarker(60, 105, "best", "grid best"),
                 d.DesignMarker(120, 75, "best", "grid best"),
                 d.DesignMarker(70, 100, "Table 1", "paper")],
    )  # fmt: skip
    strings = svg_strings(figure_artifacts(fig, "index", "Index")[1].data)
    for text in (
        "Fig 6",
        "best",
        "Table 1",
        "misses part of the workspace",
        "edge of the design space (eq 19)",
    ):
        assert any(text in s for s in strings), text
    assert sum(1 for s in strings if s == "best") == 1  # one legend entry per label


def test_starts_figure() -> None:
    bars = [st.StartBar(0.29, True, "(60, 90, 90)"), st.StartBar(math.nan, False, ""),
            st.StartBar(0.16, False, "(70, 100, 80)")]  # fmt: skip
    fig = st.optimisation_starts_figure(bars, best_index=0, title="Starts",
                                       references=[("printed 0.28", 0.28)])  # fmt: skip
    strings = svg_strings(figure_artifacts(fig, "starts", "Starts")[1].data)
    for text in (
        "Starts",
        "infeasible",
        "(60, 90, 90)",
        "printed 0.28",
        "converged",
        "stopped by the evaluation budget",
        "optimum",
    ):
        assert text in strings, text


# -- input checks ----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("call", "parameter", "function"),
    [
        (lambda: p.inverse_condition_map_figure(AZIMUTH, TILT, np.zeros((2, 3, 4)), [0, 1],
                                                title="x"),
         "values", "inverse_condition_map_figure"),
        (lambda: p.inverse_condition_map_figure(AZIMUTH, [0.0], np.zeros((1, 1, 37)), [0],
                                                title="x"),
         "tilt_deg", "inverse_condition_map_figure"),
        (lambda: p.inverse_condition_map_figure(AZIMUTH, TILT, synthetic_map(7), list(range(7)),
                                                title="x"),
         "values", "inverse_condition_map_figure"),
        (lambda: p.torsion_sweep_figure([0, 1], [[0, 1]], [], title="x"),
         "series", "torsion_sweep_figure"),
        (lambda: p.torsion_sweep_figure([0, 1], [[0, 1]], [p.SweepSeries("a", np.zeros((2, 2)))],
                                        title="x"),
         "series", "torsion_sweep_figure"),
        (lambda: p.torsion_sweep_figure([0, math.nan], [[0, 1]], [], title="x"),
         "psi3_deg", "torsion_sweep_figure"),
        (lambda: d.design_space_figure([], title="x"), "spaces", "design_space_figure"),
        (lambda: d.design_space_figure([d.SubDesignSpace(75, 0, -1, 2)], title="x"),
         "spaces", "design_space_figure"),
        (lambda: d.index_distribution_figure(np.zeros((3, 3)), np.zeros((3, 2)), np.zeros((3, 3)),
                                             title="x"),
         "values", "index_distribution_figure"),
        (lambda: st.optimisation_starts_figure([], best_index=None, title="x"),
         "starts", "optimisation_starts_figure"),
    ],
)  # fmt: skip
def test_bad_parameters_name_the_parameter(call: Any, parameter: str, function: str) -> None:
    with pytest.raises(ValueError, match=rf"The '{parameter}' parameter of {function} must be"):
        call()


def test_user_text_is_shown_literally() -> None:
    fig = sweep_figure(title="$x$ cost")
    assert "$x$ cost" in svg_strings(figure_artifacts(fig, "t", "t")[1].data)
