"""The planar3r-dexterity-map job's figures, as the job draws them."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from matplotlib.figure import Figure

from tests.unit.families.conftest import RecordingContext, unrendered_artifacts
from worker.families.planar_serial import DEXTERITY_MAP
from worker.families.planar_serial.examples import DEXTERITY_MAP_EXAMPLES
from worker.families.planar_serial.jobs import dexterity_map
from worker.families.planar_serial.specs import DexterityMapSpec


@pytest.fixture
def figures(monkeypatch: pytest.MonkeyPatch) -> dict[str, Figure]:
    """The figures the job hands to figure_artifacts, by stem, built and not rendered."""
    drawn: dict[str, Figure] = {}

    def capture(fig: Figure, stem: str, title: str) -> Any:
        drawn[stem] = fig
        return unrendered_artifacts(fig, stem, title)

    monkeypatch.setattr(dexterity_map, "figure_artifacts", capture)
    return drawn


def test_the_radial_section_stops_at_the_reach(figures: dict[str, Figure]) -> None:
    # Example 1, links (15, 14, 8): the ray runs on to 1.05 x 37; beyond 37 the arm cannot
    # reach and the curve must stop, not lie along d_z = 0 to the end of the view.
    inputs = dict(DEXTERITY_MAP_EXAMPLES[0].inputs)
    DEXTERITY_MAP.run(DexterityMapSpec.model_validate(inputs), RecordingContext())
    reach = math.fsum(inputs["links"])
    ax = figures["radial_section"].axes[0]
    (curve,) = [line for line in ax.lines if len(line.get_xdata()) > 100]
    d = np.asarray(curve.get_xdata(), dtype=float)
    d_z = np.asarray(curve.get_ydata(), dtype=float)
    assert d[-1] > 1.04 * reach
    assert np.isnan(d_z[d > reach]).all()
    inside = d < 0.999 * reach
    assert np.isfinite(d_z[inside]).all() and (d_z[inside] > 0.0).all()
