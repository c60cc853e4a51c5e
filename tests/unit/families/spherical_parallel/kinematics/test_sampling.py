"""SPM workspaces and their samples (docs/methods/spherical-parallel.md, "Default sampling")."""

from __future__ import annotations

import math

import numpy as np
import pytest

from worker.families.spherical_parallel.kinematics import (
    DEFAULT_COUNTS,
    Workspace,
    boundary_grid,
    orientation_samples,
)

CONE_120 = Workspace(math.radians(60.0))
WRIST_TORSION = Workspace(math.radians(45.0), (math.radians(-15.0), math.radians(15.0)), False)


def test_default_layout_is_the_papers_4_x_12_x_3() -> None:
    samples, layout = orientation_samples(CONE_120)
    assert samples.shape == (144, 3) and layout["n"] == 144
    assert layout["counts"] == DEFAULT_COUNTS == (4, 12, 3)
    assert np.degrees(layout["psi1"]) == pytest.approx([0, 90, 180, 270])
    assert np.degrees(layout["psi3"]) == pytest.approx([0, 120, 240])
    k = np.arange(1, 13)
    expected = np.arccos(1 - (1 - math.cos(math.radians(60))) * (k - 0.5) / 12)
    assert layout["psi2"] == pytest.approx(expected, abs=1e-15)
    assert layout["equal_weights"] is True
    # psi1 slowest, psi3 fastest
    assert samples[:3, 2] == pytest.approx(np.radians([0, 120, 240]))
    assert samples[:36, 0] == pytest.approx(np.zeros(36))


def test_tilt_samples_split_the_cone_into_equal_volumes() -> None:
    _, layout = orientation_samples(CONE_120, tilt=7)
    psi2 = np.array(layout["psi2"])
    # Haar measure ~ sin(psi2) dpsi2: the mid-points split 1 - cos T into equal cells
    volume = 1 - np.cos(psi2)
    assert np.diff(volume) == pytest.approx(np.full(6, (1 - math.cos(math.radians(60))) / 7))
    assert psi2[0] > 0 and psi2[-1] < math.radians(60)


def test_limited_torsion_includes_both_ends() -> None:
    _, layout = orientation_samples(WRIST_TORSION)
    assert np.degrees(layout["psi3"]) == pytest.approx([-15, 0, 15])
    assert "both ends" in layout["psi3_rule"]
    _, one = orientation_samples(WRIST_TORSION, torsion=1)
    assert one["psi3"] == (0.0,)


def test_denser_grids_and_torsion_origin() -> None:
    origin = Workspace(math.radians(30.0), (1.0, 1.0 + 2 * math.pi))
    samples, layout = orientation_samples(origin, azimuth=8, tilt=5, torsion=6)
    assert samples.shape == (240, 3)
    assert layout["psi3"][0] == 1.0
    assert np.diff(layout["psi1"]) == pytest.approx(np.full(7, math.pi / 4))


def test_boundary_grid_reaches_the_cone_edge_over_one_period() -> None:
    grid = boundary_grid(CONE_120)
    assert grid[:, 1].max() == pytest.approx(math.radians(60))
    assert grid[:, 0].max() < 2 * math.pi / 3
    limited = boundary_grid(WRIST_TORSION, 3, 3, 3)
    assert sorted(set(np.round(np.degrees(limited[:, 2]), 9))) == [-15.0, 0.0, 15.0]


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (lambda: Workspace(0.0), r"The 'tilt_max' parameter of Workspace must be"),
        (lambda: Workspace(math.pi), r"'tilt_max'"),
        (lambda: Workspace(0.5, (0.0, 1.0)), r"\(lo, lo \+ 2 pi\) when full_turn is True"),
        (lambda: Workspace(0.5, (0.0, 7.0), False), r"shorter than a full turn"),
        (lambda: Workspace(0.5, (1.0, 0.0), False), r"lo <= hi"),
        (lambda: orientation_samples(CONE_120, tilt=0), r"'tilt' parameter of orientation_samples"),
        (lambda: orientation_samples("cone"), r"'ws' parameter of orientation_samples"),  # type: ignore[arg-type]
    ],
)  # fmt: skip
def test_bad_workspaces_and_counts(make: object, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        make()  # type: ignore[operator]
