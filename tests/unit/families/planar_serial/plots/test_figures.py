"""The three-link planar arm's figures, rendered on small synthetic maps."""

from __future__ import annotations

import itertools
import subprocess
import sys
import time
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import pytest
from matplotlib.collections import QuadMesh
from matplotlib.figure import Figure
from matplotlib.text import Annotation, Text

from tests.unit.common.test_figures import ROOT, png_pixels, svg_strings
from worker.common.figures import RASTER_DPI, figure_artifacts
from worker.families.planar_serial.plots import figures as p

# A made-up arm: links (8, 6, 4) give regions at d = 4, 10, 18 and full dexterity on
# [0, 2] and [6, 10] (docs/methods/planar-serial.md).  d_z is a simple radial formula, NaN beyond
# reach.
LINKS = (8.0, 6.0, 4.0)
RADII = (4.0, 10.0, 18.0)
BANDS = ((0.0, 2.0), (6.0, 10.0))
POINTS = np.array([[5.0, 5.0], [9.0, -3.0], [9.5, -3.6], [-7.0, 2.0]])
LABELS = ["A", "B", "C", "D"]
PATH = np.column_stack([np.linspace(5.0, 9.5, 50), np.linspace(5.0, -3.6, 50)])


def synthetic_map(n: int = 41, half: float = 20.0) -> tuple[Any, Any, Any]:
    x = np.linspace(-half, half, n)
    y = np.linspace(-half, half, n)
    r = np.hypot(*np.meshgrid(x, y))
    d_z = np.where(r <= RADII[2], np.clip(1.4 - r / RADII[2], 0.0, 1.0), np.nan)
    return x, y, d_z


def heatmap(**overrides: Any) -> Figure:
    x, y, d_z = synthetic_map()
    kwargs: dict[str, Any] = {
        "links": LINKS, "region_radii": RADII, "bands": BANDS, "task_points": POINTS,
        "task_labels": LABELS, "trajectory": PATH, "title": "Heat map test",
        "length_unit": "mm",
    }  # fmt: skip
    kwargs.update(overrides)
    return p.dexterity_heatmap_figure(x, y, d_z, **kwargs)


def section(**overrides: Any) -> Figure:
    d = np.linspace(0.0, 18.0, 181)
    kwargs: dict[str, Any] = {
        "region_radii": RADII, "bands": BANDS, "task_distances": [7.07, 9.49, 9.6, 12.0],
        "task_labels": LABELS, "title": "Section test", "length_unit": "mm", "angle_deg": 30.0,
    }  # fmt: skip
    kwargs.update(overrides)
    return p.radial_section_figure(d, np.clip(1.4 - d / 18.0, 0.0, 1.0), **kwargs)


def case_panels(count: int) -> list[p.CasePanel]:
    x, y, d_z = synthetic_map()
    specs = [("Case 1: ideal", LINKS, False), ("Case 2: swapped", (8.0, 4.0, 6.0), False),
             ("Case 3: joint limits", LINKS, True)]  # fmt: skip
    return [
        p.CasePanel(label=label, links=links, x=x, y=y, d_z=d_z * (1 - 0.2 * i), bands=BANDS,
                    region_radii=RADII, joint_limited=limited)
        for i, (label, links, limited) in enumerate(specs[:count])
    ]  # fmt: skip


def cases(count: int = 3) -> Figure:
    return p.synthesis_cases_figure(
        case_panels(count), task_points=POINTS, task_labels=LABELS, trajectory=PATH,
        title="Cases test", length_unit="mm",
    )  # fmt: skip


@dataclass(frozen=True)
class Rendered:
    fig: Figure
    pixels: Any  # (h, w, 4) floats in [0, 1]
    strings: list[str]
    svg: bytes


def rendered(fig: Figure) -> Rendered:
    png, svg = figure_artifacts(fig, "figure", "title")
    return Rendered(fig, png_pixels(png.data), svg_strings(svg.data), svg.data)


# Each figure is rendered once per module; tests that only inspect the figure objects
# skip rendering.  Rendering costs about a second per figure.
@pytest.fixture(scope="module")
def heatmap_render() -> Rendered:
    return rendered(heatmap())


@pytest.fixture(scope="module")
def section_render() -> Rendered:
    return rendered(section())


@pytest.fixture(scope="module")
def cases_render() -> Rendered:
    return rendered(cases(3))


def expected_shape(fig: Figure) -> tuple[int, int]:
    w, h = fig.get_size_inches()
    return round(h * RASTER_DPI), round(w * RASTER_DPI)


def pixel_at(fig: Figure, pixels: Any, xy: tuple[float, float]) -> Any:
    """The PNG pixel over data point ``xy`` of the first axes (layout is fixed by then)."""
    col, row = fig.axes[0].transData.transform(xy) * RASTER_DPI / fig.dpi
    return pixels[pixels.shape[0] - int(row), int(col)]


def text_boxes(fig: Figure, texts: list[Text]) -> list[Any]:
    fig.draw_without_rendering()
    renderer = fig._get_renderer()  # type: ignore[attr-defined]
    return [t.get_window_extent(renderer) for t in texts]


# -- heat map -------------------------------------------------------------------------


def test_heatmap_png_and_svg(heatmap_render: Rendered) -> None:
    strings = heatmap_render.strings
    assert heatmap_render.pixels.shape[:2] == expected_shape(heatmap_render.fig)
    assert {"Heat map test", "x [mm]", "y [mm]", *LABELS} <= set(strings)
    assert r"orientation dexterity $d_z$  ($D = d_z/3$)" in strings
    assert "unreachable" in strings and "trajectory" in strings and "base" in strings
    assert any("full dexterity" in s and "[0, 2]" in s and "[6, 10]" in s for s in strings)
    assert any("region boundaries" in s and "4, 10, 18" in s for s in strings)


def test_heatmap_colours_nan_as_background_and_full_dexterity_as_yellow() -> None:
    fig = heatmap(task_points=None, task_labels=None, trajectory=None)
    pixels = rendered(fig).pixels
    corner = pixel_at(fig, pixels, (19.0, 19.0))  # beyond reach: NaN
    centre = pixel_at(fig, pixels, (1.0, 0.5))  # d_z = 1
    np.testing.assert_allclose(corner[:3], [0xD9 / 255] * 3, atol=0.02)
    np.testing.assert_allclose(centre[:3], [0xFD / 255, 0xE7 / 255, 0x25 / 255], atol=0.03)


def test_heatmap_is_cell_centred_on_one_colour_scale() -> None:
    fig = heatmap()
    (image,) = fig.axes[0].images
    assert image.get_extent() == pytest.approx((-20.5, 20.5, -20.5, 20.5))
    assert image.get_clim() == (0.0, 1.0)
    assert image.get_cmap().name.startswith("viridis")
    assert fig.axes[0].get_aspect() == 1.0


def test_heatmap_flips_descending_axes() -> None:
    x, y, d_z = synthetic_map()
    d_z = d_z * np.linspace(0.5, 1.0, x.size)  # make left and right differ
    fig = p.dexterity_heatmap_figure(x[::-1], y, d_z[:, ::-1], links=LINKS, region_radii=RADII,
                                     bands=BANDS, title="t")  # fmt: skip
    (image,) = fig.axes[0].images
    assert image.get_extent()[0] < image.get_extent()[1]
    np.testing.assert_array_equal(image.get_array(), np.ma.masked_invalid(d_z))


def test_heatmap_on_an_irregular_grid_uses_cells_around_the_nodes() -> None:
    x = np.array([-18.0, -9.0, -3.0, 0.0, 3.0, 9.0, 18.0])
    d_z = np.ones((x.size, x.size))
    fig = p.dexterity_heatmap_figure(x, x, d_z, links=LINKS, region_radii=RADII, bands=BANDS,
                                     title="t")  # fmt: skip
    assert not fig.axes[0].images
    assert any(isinstance(c, QuadMesh) for c in fig.axes[0].collections)
    fig.draw_without_rendering()


def test_heatmap_task_labels_overlap_neither_each_other_nor_points() -> None:
    fig = heatmap()
    ax = fig.axes[0]
    labels = [t for t in ax.texts if isinstance(t, Annotation)]
    assert [t.get_text() for t in labels] == LABELS
    boxes = text_boxes(fig, list(labels))
    for a, b in itertools.combinations(boxes, 2):
        assert not a.overlaps(b)
    for box in boxes:
        for point in ax.transData.transform(POINTS):
            assert not box.contains(*point)


def test_heatmap_notes_joint_limits() -> None:
    assert "exact under joint limits" in heatmap(joint_limited=True).axes[0].get_title()
    sampled = heatmap(joint_limited=True, limited_method="orientation-sampling")
    assert "sampled under joint limits" in sampled.axes[0].get_title()
    assert "joint limits" not in heatmap().axes[0].get_title()


def test_heatmap_under_joint_limits_outlines_its_own_full_dexterity() -> None:
    legend = heatmap(joint_limited=True).legends[0]
    texts = [t.get_text() for t in legend.get_texts()]
    assert any("joint limits included" in t for t in texts)
    assert any("unlimited joints" in t for t in texts)
    plain = [t.get_text() for t in heatmap().legends[0].get_texts()]
    assert not any("joint limits included" in t for t in plain)


def test_default_task_labels_are_letters() -> None:
    texts = [t.get_text() for t in heatmap(task_labels=None).axes[0].texts]
    assert texts == ["A", "B", "C", "D"]


def test_identical_inputs_give_identical_svg(
    heatmap_render: Rendered, section_render: Rendered, cases_render: Rendered
) -> None:
    assert rendered(heatmap()).svg == heatmap_render.svg
    assert rendered(section()).svg == section_render.svg
    assert rendered(cases(3)).svg == cases_render.svg


def test_user_text_is_shown_literally() -> None:
    fig = heatmap(title="Cost $5 and $10", task_labels=["$x$", "B", "C", "D"])
    strings = rendered(fig).strings  # a "$" pair would otherwise start mathtext
    assert "Cost $5 and $10" in strings and "$x$" in strings


@pytest.mark.parametrize(
    ("overrides", "message"),
    [
        ({"links": (1.0, 2.0)}, "The 'links' parameter of dexterity_heatmap_figure must be 3"),
        ({"region_radii": (1.0, float("nan"), 3.0)}, "The 'region_radii' parameter .* 3 finite"),
        ({"bands": [(3.0, 1.0)]}, r"The 'bands' parameter .* 0 <= lo <= hi"),
        ({"task_points": np.zeros((3, 3))}, r"The 'task_points' parameter .* \(k, 2\)"),
        ({"task_labels": ["A"]}, r"The 'task_labels' parameter .* 4 labels"),
        ({"trajectory": np.zeros((1, 2))}, "The 'trajectory' parameter"),
    ],
)
def test_heatmap_rejects_bad_parameters(overrides: dict[str, Any], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        heatmap(**overrides)


def test_heatmap_rejects_a_grid_of_the_wrong_shape() -> None:
    x, y, d_z = synthetic_map()
    with pytest.raises(ValueError, match=r"The 'd_z' parameter .* \(ny, nx\) = \(41, 41\)"):
        p.dexterity_heatmap_figure(x, y, d_z[:-1], links=LINKS, region_radii=RADII,
                                   bands=BANDS, title="t")  # fmt: skip
    with pytest.raises(ValueError, match=r"The 'x' parameter .* strictly monotonic"):
        p.dexterity_heatmap_figure(np.zeros(41), y, d_z, links=LINKS, region_radii=RADII,
                                   bands=BANDS, title="t")  # fmt: skip


# -- surface --------------------------------------------------------------------------


def test_surface_png_and_svg() -> None:
    x, y, d_z = synthetic_map()
    fig = p.dexterity_surface_figure(x, y, d_z, title="Surface test", length_unit="mm")
    result = rendered(fig)
    strings = result.strings
    assert result.pixels.shape[:2] == expected_shape(fig)
    assert {"Surface test", "x [mm]", "y [mm]", "$d_z$"} <= set(strings)
    assert r"orientation dexterity $d_z$  ($D = d_z/3$)" in strings


def test_surface_of_a_2001_grid_is_downsampled_and_fast() -> None:
    x, y, d_z = synthetic_map(n=2001)
    start = time.perf_counter()
    fig = p.dexterity_surface_figure(x, y, d_z, title="Big surface")
    _, svg = figure_artifacts(fig, "surface", "Big surface")
    assert time.perf_counter() - start < 30.0  # about 2 s; unstrided it takes minutes
    (surface,) = fig.axes[0].collections
    assert len(surface.get_paths()) <= 200 * 200
    assert len(svg.data) < 2_000_000


# -- radial section -------------------------------------------------------------------


def test_section_png_and_svg(section_render: Rendered) -> None:
    fig, strings = section_render.fig, section_render.strings
    assert section_render.pixels.shape[:2] == expected_shape(fig)
    assert {"Section test", "region 1", "region 2", "region 3", "4", *LABELS} <= set(strings)
    assert "distance from the base d along the ray at 30° [mm]" in strings
    assert r"dexterity index $D = d_z/3$" in strings
    assert fig.axes[0].get_ylim() == (0.0, 1.05)


def test_section_stacks_close_task_labels() -> None:
    fig = section()
    labels = [t for t in fig.axes[0].texts if t.get_text() in LABELS]
    assert len(labels) == 4
    for a, b in itertools.combinations(text_boxes(fig, labels), 2):
        assert not a.overlaps(b)


def test_section_skips_empty_regions() -> None:
    # Swapped links (8, 4, 6): region 2 (6 < d <= 6) is empty, as in the paper's Case 2.
    fig = section(region_radii=(6.0, 6.0, 18.0), task_distances=None, task_labels=None)
    strings = [t.get_text() for t in fig.axes[0].texts]
    assert "region 1" in strings and "region 3" in strings and "region 2" not in strings


def test_section_stops_where_the_arm_cannot_reach() -> None:
    # The job passes d_z = 0 beyond the reach (18 here), and NaN may come too: the curve
    # ends at the reach instead of running along the floor to the end of the view.
    d = np.linspace(0.0, 20.0, 201)
    d_z = np.where(d < 18.0, np.clip(1.4 - d / 18.0, 0.0, 1.0), 0.0)
    d_z[d > 19.5] = np.nan
    fig = p.radial_section_figure(d, d_z, region_radii=RADII, bands=BANDS, title="t")
    (curve,) = [line for line in fig.axes[0].lines if len(line.get_xdata()) == d.size]
    shown = np.asarray(curve.get_ydata(), dtype=float)
    assert np.isnan(shown[d >= 18.0]).all()
    np.testing.assert_array_equal(shown[d < 18.0], d_z[d < 18.0])


def test_section_rejects_mismatched_arrays() -> None:
    with pytest.raises(ValueError, match=r"The 'd_z' parameter of radial_section_figure"):
        p.radial_section_figure(np.linspace(0, 1, 5), np.zeros(4), region_radii=RADII,
                                bands=BANDS, title="t")  # fmt: skip


# -- synthesis cases ------------------------------------------------------------------


@pytest.mark.parametrize("count", [1, 2, 3])
def test_cases_panels_share_one_colour_bar(count: int, cases_render: Rendered) -> None:
    result = cases_render if count == 3 else rendered(cases(count))
    fig, strings = result.fig, result.strings
    assert result.pixels.shape[:2] == expected_shape(fig)
    assert len(fig.axes) == count + 1  # the panels and one colour bar
    for ax in fig.axes[:count]:
        (image,) = ax.images
        assert image.get_clim() == (0.0, 1.0)
    assert "Cases test" in strings
    for label in LABELS:
        assert strings.count(label) == count
    titles = [ax.get_title() for ax in fig.axes[:count]]
    assert titles[0] == "Case 1: ideal\n$l_1, l_2, l_3$ = 8, 6, 4 mm"
    if count == 3:
        assert titles[2].endswith("· joint-limited")


def test_cases_titles_give_lengths_to_four_significant_digits_and_their_unit() -> None:
    # An optimum's links as the search returns them (planar3r-design's example 0).
    panel = replace(case_panels(1)[0], label="Optimum", links=(14.5846, 5.27883, 0.0370962))
    fig = p.synthesis_cases_figure([panel], task_points=None, task_labels=None,
                                   trajectory=None, title="t", length_unit="mm")  # fmt: skip
    assert fig.axes[0].get_title() == "Optimum\n$l_1, l_2, l_3$ = 14.58, 5.279, 0.0371 mm"


@pytest.mark.parametrize("count", [0, 4])
def test_cases_needs_one_to_three_panels(count: int) -> None:
    panels = case_panels(3) + case_panels(1)
    with pytest.raises(ValueError, match=r"The 'cases' parameter .* 1 to 3"):
        p.synthesis_cases_figure(panels[:count], task_points=None, task_labels=None,
                                 trajectory=None, title="t")  # fmt: skip


# -- process hygiene ------------------------------------------------------------------


@pytest.mark.slow
def test_rendering_never_loads_pyplot_nor_changes_rc_params() -> None:
    code = """
import sys
from tests.unit.families.planar_serial.plots import test_figures as t
from tests.unit.common.test_figures import rc_snapshot
from worker.common.figures import figure_artifacts
before = rc_snapshot()
x, y, d_z = t.synthetic_map()
figures = [t.heatmap(), t.section(), t.cases(),
           t.p.dexterity_surface_figure(x, y, d_z, title="s")]
for fig in figures:
    figure_artifacts(fig, "f", "t")
print("matplotlib.pyplot" in sys.modules, rc_snapshot() == before)
"""
    out = subprocess.run([sys.executable, "-W", "error", "-c", code], capture_output=True,
                         text=True, check=True, cwd=ROOT)  # fmt: skip
    assert out.stdout.split() == ["False", "True"]


def test_a_negative_region_radius_draws_no_circle() -> None:
    # Links (1, 1, 3): l1 + l2 - l3 = -1, so region 2 is empty and there is no band.
    x, y, d_z = synthetic_map()
    fig = p.dexterity_heatmap_figure(x, y, d_z, links=(1.0, 1.0, 3.0), region_radii=(3, -1, 5),
                                     bands=(), title="t")  # fmt: skip
    circles = [line for line in fig.axes[0].lines if np.size(line.get_xdata()) > 1]
    assert len(circles) == 2
    fig.draw_without_rendering()
