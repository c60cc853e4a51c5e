"""The 2-DOF parallel robots' figures, rendered on small synthetic maps."""

from __future__ import annotations

import subprocess
import sys
import time
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest
from matplotlib.contour import ContourSet
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from tests.unit.common.test_figures import ROOT, png_pixels, svg_strings
from worker.common.figures import RASTER_DPI, figure_artifacts
from worker.families.planar_parallel.plots import conditioning as p
from worker.families.planar_parallel.plots import design as d
from worker.families.planar_parallel.plots.panels import INVERSE_CONDITION, MAX_DRAWN_NODES

POINTS = np.array([[0.0, -1.5], [1.0, -1.0]])
JOINTS = [[0.5, 0.0], [-0.5, 0.0]]
IC_LABEL = r"conditioning index $1/\kappa$ (eq 7)"
BETA_LABEL = r"minimum pressure angle $\beta_{\min}$ (eq 15) [°]"
OUTLINE_LABEL = r"boundary of $W_{\kappa 0}$: $1/\kappa = 0.5$"


def synthetic_map(n: int = 61) -> tuple[Any, Any, Any, Any]:
    """1/kappa peaking at (0, -1.5), NaN outside a disc of radius 2.5; beta_min alike."""
    x = np.linspace(-3.0, 3.0, n)
    y = np.linspace(-3.0, 1.0, n)
    xx, yy = np.meshgrid(x, y)
    r = np.hypot(xx, yy + 1.5)
    inverse = np.where(np.hypot(xx, yy) <= 2.5, np.clip(1.0 - r / 2.0, 0.0, 1.0), np.nan)
    return x, y, inverse, 90.0 * inverse


def ic_map(**overrides: Any) -> Figure:
    x, y, inverse, _ = synthetic_map()
    kwargs: dict[str, Any] = {
        "inverse_condition_limit": 0.5, "points": POINTS, "point_labels": ["A", "B"],
        "joints": JOINTS, "isotropic_point": (0.0, -1.5), "title": "Map test",
        "subtitle": "proximal-arm, l1 = 1", "length_unit": "mm",
    }  # fmt: skip
    kwargs.update(overrides)
    return p.inverse_condition_map_figure(x, y, inverse, **kwargs)


def beta_map(**overrides: Any) -> Figure:
    x, y, inverse, beta = synthetic_map()
    kwargs: dict[str, Any] = {
        "inverse_condition": inverse, "inverse_condition_limit": 0.5, "points": POINTS,
        "title": "Beta test", "length_unit": "mm",
    }  # fmt: skip
    kwargs.update(overrides)
    return p.pressure_angle_map_figure(x, y, beta, **kwargs)


def fig7(**overrides: Any) -> Figure:
    deltas = np.linspace(1.0, 2.5, 31)
    angles = np.array([25.0, 30.0, 35.0])
    limits = np.stack([0.3 + a / 100.0 - 0.1 * (deltas - 1.5 - a / 100.0) ** 2 for a in angles])
    kwargs: dict[str, Any] = {"chosen_angle_deg": 30.0, "chosen_limit": 0.6,
                              "chosen_delta": 1.8, "title": "Fig 7 test"}  # fmt: skip
    kwargs.update(overrides)
    return d.conditioning_limit_figure(deltas, angles, limits, **kwargs)


def fig8(**overrides: Any) -> Figure:
    deltas = np.linspace(1.0, 2.5, 16)
    ratio = np.exp(-((deltas - 1.7) ** 2))
    mean = 0.75 + 0.02 * (deltas - 1.7) ** 2
    ratio[0] = mean[0] = np.nan  # no rectangle at the first delta
    kwargs: dict[str, Any] = {"optimum_delta": 1.7, "window": (1.6, 1.8), "title": "Fig 8 test",
                              "subtitle": "limit 0.5"}  # fmt: skip
    kwargs.update(overrides)
    return d.design_indices_figure(deltas, ratio, mean, ratio * mean, **kwargs)


def fig9(**overrides: Any) -> Figure:
    xs = np.linspace(-0.5, 0.5, 41)
    ys = np.linspace(-0.125, 0.125, 21)
    xx, yy = np.meshgrid(xs, ys)
    inverse = 0.7 + 0.3 * (0.125 - yy) * 4 - 0.2 * xx**2
    beta = 30.0 + 200.0 * (0.125 - yy) + 20 * xx**2
    kwargs: dict[str, Any] = {"inverse_condition_limit": 0.8, "allowable_angle_deg": 35.0,
                              "title": "Fig 9 test", "subtitle": "delta = 1.7"}  # fmt: skip
    kwargs.update(overrides)
    return d.normalised_rectangle_figure(xs, ys, inverse, beta, **kwargs)


def workspace(**overrides: Any) -> Figure:
    x, y, inverse, _ = synthetic_map()
    kwargs: dict[str, Any] = {"inverse_condition_limit": 0.5, "rectangle": (1.6, 0.4, 1.5),
                              "joints": JOINTS, "isotropic_point": (0.0, -1.5),
                              "title": "Workspace test", "subtitle": "b = 1.6"}  # fmt: skip
    kwargs.update(overrides)
    return d.rectangle_workspace_figure(x, y, inverse, **kwargs)


@dataclass(frozen=True)
class Rendered:
    fig: Figure
    pixels: Any
    strings: list[str]
    svg: bytes


def rendered(fig: Figure) -> Rendered:
    png, svg = figure_artifacts(fig, "figure", "title")
    return Rendered(fig, png_pixels(png.data), svg_strings(svg.data), svg.data)


def expected_shape(fig: Figure) -> tuple[int, int]:
    w, h = fig.get_size_inches()
    return round(h * RASTER_DPI), round(w * RASTER_DPI)


def outlines(fig: Figure) -> list[ContourSet]:
    """The W_kappa0 outlines: red single-level contour sets."""
    return [
        c for ax in fig.axes for c in ax.collections
        if isinstance(c, ContourSet) and len(c.levels) == 1 and c.get_edgecolor()[0][0] > 0.8
    ]  # fmt: skip


# -- conditioning maps (Figs 4-5) -------------------------------------------------------


@pytest.fixture(scope="module")
def ic_render() -> Rendered:
    return rendered(ic_map())


def test_inverse_condition_map(ic_render: Rendered) -> None:
    fig, strings = ic_render.fig, ic_render.strings
    assert ic_render.pixels.shape[:2] == expected_shape(fig)
    assert {"Map test", "proximal-arm, l1 = 1", "x [mm]", "y [mm]", IC_LABEL, OUTLINE_LABEL,
            "A", "B", "actuated joints (±e, 0)", "isotropic point ($1/\\kappa = 1$)",
            "given points", "unreachable in this working mode"} <= set(strings)  # fmt: skip
    (outline,) = outlines(fig)
    assert list(outline.levels) == [0.5]
    assert len(fig.axes) == 2  # the map and its colour bar
    assert fig.axes[0].get_aspect() == 1.0


def test_pressure_angle_map_outlines_w_kappa0_on_the_1_kappa_grid() -> None:
    result = rendered(beta_map())
    assert {"Beta test", "x [mm]", "y [mm]", BETA_LABEL, OUTLINE_LABEL, "1", "2"} <= set(
        result.strings
    )
    (outline,) = outlines(result.fig)
    assert list(outline.levels) == [0.5]


def test_no_limit_no_outline() -> None:
    fig = ic_map(inverse_condition_limit=None, points=None, point_labels=None)
    assert outlines(fig) == []
    fig.draw_without_rendering()
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert OUTLINE_LABEL not in legend and "given points" not in legend
    assert beta_map(inverse_condition=None).legends[0].get_texts()[0].get_text() != OUTLINE_LABEL


def test_a_2001_grid_is_strided_and_rasterised() -> None:
    x, y, inverse, _ = synthetic_map(n=2001)
    start = time.perf_counter()
    fig = p.inverse_condition_map_figure(x, y, inverse, inverse_condition_limit=0.5, title="big")
    _, svg = figure_artifacts(fig, "big", "big")
    assert time.perf_counter() - start < 30.0
    filled = fig.axes[0].collections[0]
    assert filled.get_rasterized()
    assert len(svg.data) < 3_000_000
    assert MAX_DRAWN_NODES == 601


def test_identical_inputs_give_identical_svg(ic_render: Rendered) -> None:
    assert rendered(ic_map()).svg == ic_render.svg


def test_user_text_is_shown_literally() -> None:
    strings = rendered(ic_map(title="Cost $5 and $10", point_labels=["$x$", "B"])).strings
    assert "Cost $5 and $10" in strings and "$x$" in strings


@pytest.mark.parametrize(
    ("overrides", "message"),
    [
        ({"points": np.full((2, 2), np.nan)}, r"The 'points' parameter of inverse_condition_map"),
        ({"point_labels": ["A"]}, r"The 'labels' parameter .* 2 labels"),
        ({"inverse_condition_limit": 1.5}, r"The 'inverse_condition_limit' parameter .* \(0, 1\]"),
        ({"isotropic_point": (0.0, float("nan"))}, "The 'isotropic_point' parameter"),
    ],
)
def test_map_rejects_bad_parameters(overrides: dict[str, Any], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        ic_map(**overrides)


def test_map_rejects_a_grid_of_the_wrong_shape() -> None:
    x, y, inverse, _ = synthetic_map()
    with pytest.raises(ValueError, match=r"The 'values' parameter .* \(ny, nx\) = \(61, 61\)"):
        p.inverse_condition_map_figure(x, y, inverse[:-1], title="t")
    with pytest.raises(ValueError, match=r"The 'x' parameter .* strictly monotonic"):
        p.inverse_condition_map_figure(np.zeros(61), y, inverse, title="t")
    with pytest.raises(ValueError, match=r"The 'values' parameter of pressure_angle_map_figure"):
        p.pressure_angle_map_figure(x, y, inverse, inverse_condition=inverse[:, :-1],
                                    inverse_condition_limit=0.5, title="t")  # fmt: skip


# -- Fig. 7 --------------------------------------------------------------------------------


def test_conditioning_limit_figure() -> None:
    result = rendered(fig7())
    fig, strings = result.fig, result.strings
    assert result.pixels.shape[:2] == expected_shape(fig)
    assert {"Fig 7 test", r"$\delta = l_2 / l_1$", r"conditioning limit $1/\kappa_0$ (eqs 17, 7)",
            r"$1/\kappa_0$ = 0.6 at $\delta$ = 1.8"} <= set(strings)  # fmt: skip
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert labels[1].startswith(r"$[\beta]$ = 30°: max 0.6000 at $\delta$ = ")
    widths = {line.get_label(): line.get_linewidth() for line in fig.axes[0].lines}
    assert widths[labels[1]] > widths[labels[0]]  # the chosen [beta] is drawn bold


def test_conditioning_limit_given_directly() -> None:
    fig = fig7(chosen_angle_deg=None, chosen_delta=None, chosen_limit=0.55)
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert texts == [r"$1/\kappa_0$ = 0.55 (given)"]


def test_conditioning_limit_rejects_mismatched_arrays() -> None:
    with pytest.raises(ValueError, match=r"The 'limits' parameter .* \(k, n\) = \(2, 3\)"):
        d.conditioning_limit_figure([1, 2, 3], [30, 35], np.zeros((3, 3)), chosen_angle_deg=30,
                                    chosen_limit=0.5, chosen_delta=None, title="t")  # fmt: skip


# -- Fig. 8 --------------------------------------------------------------------------------


def test_design_indices_figure() -> None:
    result = rendered(fig8())
    fig, strings = result.fig, result.strings
    assert result.pixels.shape[:2] == expected_shape(fig)
    assert {"Fig 8 test", "limit 0.5", "performance indices", r"$\delta = l_2 / l_1$",
            r"$\Delta_s = S / S_{\max}$", r"$\eta = \Delta_s / \bar\kappa$ (eq 13)",
            r"$\eta$ within 0.001 of its max: [1.6, 1.8]"} <= set(strings)  # fmt: skip
    assert any(s.startswith(r"optimum $\delta$ = 1.7, $\eta$ = ") for s in strings)


def test_design_indices_of_one_delta() -> None:
    fig = d.design_indices_figure([1.7], [1.0], [0.75], [0.75], optimum_delta=1.7, window=None,
                                  title="one")  # fmt: skip
    assert fig.axes[0].get_xlim() == pytest.approx((1.6, 1.8))
    fig.draw_without_rendering()


def test_design_indices_rejects_mismatched_arrays() -> None:
    with pytest.raises(ValueError, match=r"The 'eta' parameter of design_indices_figure .* \(3,\)"):
        d.design_indices_figure([1, 2, 3], [1, 1, 1], [1, 1, 1], [1, 1], optimum_delta=None,
                                window=None, title="t")  # fmt: skip


# -- Fig. 9 --------------------------------------------------------------------------------


def test_normalised_rectangle_figure() -> None:
    result = rendered(fig9())
    fig, strings = result.fig, result.strings
    assert result.pixels.shape[:2] == expected_shape(fig)
    assert len(fig.axes) == 4  # two panels, two colour bars
    assert {r"$\bar x = x / b$", r"$\bar y = (y + H') / b$", r"$1/\kappa$ = 0.8",
            r"$\beta_{\min}$ = 35°"} <= set(strings)  # fmt: skip
    assert any(s.startswith("Fig 9 test") for s in strings)
    top, bottom = fig.axes[0], fig.axes[1]
    assert top.get_title().startswith(r"conditioning index $1/\kappa$: minimum 0.65")
    assert bottom.get_title().startswith(r"minimum pressure angle $\beta_{\min}$: minimum 30°")
    # the minima sit on the top edge, mirrored about x = 0
    markers = [line for line in top.lines if line.get_marker() == "v"]
    assert sorted(float(m.get_xdata()[0]) for m in markers) == pytest.approx([-0.5, 0.5])


def test_restricted_colour_scale_covers_the_data() -> None:
    scale = INVERSE_CONDITION.restricted(0.526, 0.97)
    assert scale.levels[0] == 0.5 and scale.levels[-1] == 1.0
    assert len(scale.levels) - 1 >= 8
    assert INVERSE_CONDITION.restricted(float("nan"), float("nan")) is INVERSE_CONDITION


# -- Fig. 6: the rectangle in W_kappa0 ------------------------------------------------------


def test_rectangle_workspace_figure() -> None:
    result = rendered(workspace())
    fig, strings = result.fig, result.strings
    assert result.pixels.shape[:2] == expected_shape(fig)
    assert {"Workspace test", "b = 1.6", r"x [$l_1$]", r"y [$l_1$]", OUTLINE_LABEL,
            r"rectangle $W_\lambda$ (b x h, centre (0, -H'))"} <= set(strings)  # fmt: skip
    ax = fig.axes[0]
    (patch,) = [a for a in ax.patches if isinstance(a, Rectangle)]
    assert (patch.get_x(), patch.get_y()) == pytest.approx((-0.8, -1.7))
    assert (patch.get_width(), patch.get_height()) == pytest.approx((1.6, 0.4))
    # the view ends a little above W_kappa0 (1/kappa >= 0.5 up to y = -0.5), not at y = 1
    assert -0.5 < ax.get_ylim()[1] < 0.0


def test_rectangle_workspace_without_a_rectangle() -> None:
    fig = workspace(rectangle=None)
    assert not [a for a in fig.axes[0].patches if isinstance(a, Rectangle)]
    with pytest.raises(ValueError, match="The 'rectangle' parameter"):
        d.rectangle_workspace_figure(*synthetic_map()[:3], inverse_condition_limit=0.5,
                                     rectangle=(1.0, -0.2, 1.5), title="t")  # fmt: skip


# -- process hygiene ------------------------------------------------------------------------


@pytest.mark.slow
def test_rendering_never_loads_pyplot_nor_changes_rc_params() -> None:
    code = """
import sys
from tests.unit.families.planar_parallel.plots import test_figures as t
from tests.unit.common.test_figures import rc_snapshot
from worker.common.figures import figure_artifacts
before = rc_snapshot()
for fig in (t.ic_map(), t.beta_map(), t.fig7(), t.fig8(), t.fig9(), t.workspace()):
    figure_artifacts(fig, "f", "t")
print("matplotlib.pyplot" in sys.modules, rc_snapshot() == before)
"""
    out = subprocess.run([sys.executable, "-W", "error", "-c", code], capture_output=True,
                         text=True, check=True, cwd=ROOT)  # fmt: skip
    assert out.stdout.split() == ["False", "True"]
