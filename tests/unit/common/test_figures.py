"""figure_artifacts: PNG + SVG bytes, reproducible, no global state."""

from __future__ import annotations

import io
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import matplotlib as mpl
import pytest
from matplotlib.figure import Figure
from matplotlib.image import imread

from worker.common.figures import RASTER_DPI, figure_artifacts

ROOT = Path(__file__).resolve().parents[3]
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
SVG_NS = "{http://www.w3.org/2000/svg}"


def svg_strings(data: bytes) -> list[str]:
    """Every string in an SVG: <title>/<text> contents and the per-text comments.

    Matplotlib draws text as glyph paths and keeps each string in a comment beside
    them; parsing (not substring search) also proves the file is well-formed XML.
    """
    root = ET.fromstring(data, parser=ET.XMLParser(target=ET.TreeBuilder(insert_comments=True)))
    assert root.tag == f"{SVG_NS}svg"
    return [(el.text or "").strip() for el in root.iter() if el.text and el.text.strip()]


def png_pixels(data: bytes) -> object:
    assert data.startswith(PNG_SIGNATURE)
    return imread(io.BytesIO(data), format="png")


def rc_snapshot() -> dict[str, object]:
    """rcParams without "backend": reading that one can resolve it, importing pyplot."""
    return {key: mpl.rcParams[key] for key in mpl.rcParams if key != "backend"}


def small_figure(title: str = "A line") -> Figure:
    fig = Figure(figsize=(4, 3), layout="constrained")
    ax = fig.add_subplot()
    ax.plot([0, 1, 2], [0, 1, 4])
    ax.set_xlabel("x [mm]")
    fig.suptitle(title)
    return fig


def test_names_media_types_and_titles() -> None:
    png, svg = figure_artifacts(small_figure(), "curve", "A curve")
    assert (png.name, png.media_type, png.title) == ("curve.png", "image/png", "A curve")
    assert (svg.name, svg.media_type, svg.title) == ("curve.svg", "image/svg+xml", "A curve")


def test_png_is_decodable_at_150_dpi() -> None:
    png, _ = figure_artifacts(small_figure(), "curve", "A curve")
    pixels = png_pixels(png.data)
    assert RASTER_DPI == 150
    assert pixels.shape[:2] == (3 * 150, 4 * 150)  # type: ignore[attr-defined]


def test_svg_parses_and_carries_title_and_labels() -> None:
    _, svg = figure_artifacts(small_figure("Curve plot"), "curve", "Artifact title")
    strings = svg_strings(svg.data)
    assert "Artifact title" in strings  # the <title> element and dc:title metadata
    assert "Curve plot" in strings
    assert "x [mm]" in strings
    assert b"<dc:date>" not in svg.data


def test_identical_figures_give_identical_bytes() -> None:
    first = figure_artifacts(small_figure(), "curve", "A curve")
    second = figure_artifacts(small_figure(), "curve", "A curve")
    assert first[1].data == second[1].data
    assert first[0].data == second[0].data


def test_rc_params_are_left_untouched() -> None:
    before = rc_snapshot()
    figure_artifacts(small_figure(), "curve", "A curve")
    assert rc_snapshot() == before


@pytest.mark.parametrize("stem", ["", "a/b", "..\\x"])
def test_stem_must_be_a_plain_file_name(stem: str) -> None:
    with pytest.raises(ValueError, match="The 'stem' parameter of figure_artifacts must be"):
        figure_artifacts(small_figure(), stem, "t")


def test_importing_the_plots_packages_loads_no_matplotlib() -> None:
    families = ("chains", "planar_parallel", "planar_serial", "spherical_parallel")
    imports = "; ".join(f"import worker.families.{f}.plots" for f in families)
    code = f"import sys; {imports}; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         cwd=ROOT)  # fmt: skip
    assert out.stdout.strip() == "False"
