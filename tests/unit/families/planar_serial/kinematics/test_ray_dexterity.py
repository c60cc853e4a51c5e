"""Exact joint-limited d_z along a ray: its range per interval and its d_z = 1 radii,
against dense sampling of the exact events, the independent reference sampler, the
closed form for unlimited joints, and the paper's Example 1 under its limits."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from tests.unit.families.planar_serial.kinematics.strategies import angles, designs, limits
from worker.families.planar_serial.kinematics import (
    exact_orientation_dexterity,
    full_dexterity_bands,
    sampled_orientation_dexterity,
)
from worker.families.planar_serial.kinematics.limited_exact import (
    exact_limited_orientation_dexterity,
    feasible_arcs,
)
from worker.families.planar_serial.kinematics.ray import dexterity as ray_module
from worker.families.planar_serial.kinematics.ray.bounds import dexterity_bounds
from worker.families.planar_serial.kinematics.ray.dexterity import (
    RANGE_TOL,
    RayDexterity,
    ray_dexterity,
)

PAPER_LIMITS = np.radians([[-150.0, 150.0], [-150.0, 150.0], [-175.0, 175.0]])
FREE = np.array([[-math.pi, math.pi]] * 3)
EX1_LINKS = (15.0, 14.0, 8.0)
EX1_REGIONS = [0.0, 8.0, 21.0, 37.0]
#: sqrt(1e-16): d_z near a tangency, where it moves like a square root of the distance.
ROUNDED = 1e-7
PROPERTY = settings(max_examples=60, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])  # fmt: skip


@st.composite
def edges(draw: st.DrawFn, links: tuple[float, float, float]) -> list[float]:
    """0 or a random start, then 1 to 3 more distances up to 1.05 (l1 + l2 + l3)."""
    reach = 1.05 * sum(links)
    cuts = draw(st.lists(st.floats(0.0, 1.0), min_size=2, max_size=4))
    ends = sorted(reach * c for c in cuts)
    return [0.0, *ends[1:]] if draw(st.booleans()) else ends


def along(links, limits_rad, angle: float, radii: np.ndarray) -> np.ndarray:
    points = np.stack([radii * math.cos(angle), radii * math.sin(angle)], axis=-1)
    return exact_limited_orientation_dexterity(links, points, limits_rad)


def check_against_samples(links, limits_rad, angle: float, ends: list[float]) -> RayDexterity:
    """The range of every interval holds every sample (to RANGE_TOL), is a value d_z
    takes, and is certified; the bands are where the samples have d_z = 1."""
    profile = ray_dexterity(links, limits_rad, angle, ends)
    for (lo, hi), span in zip(itertools.pairwise(ends), profile.ranges, strict=True):
        radii = np.linspace(lo, hi, 2001)
        values = along(links, limits_rad, angle, radii)
        assert span.d_z_min <= values.min() + RANGE_TOL
        assert span.d_z_max >= values.max() - RANGE_TOL
        assert lo <= span.d_z_min_at <= hi and lo <= span.d_z_max_at <= hi
        found = along(links, limits_rad, angle, np.array([span.d_z_min_at, span.d_z_max_at]))
        assert found.tolist() == [span.d_z_min, span.d_z_max]
        # certified to RANGE_TOL, or where d_z moves like a square root (at a tangency)
        # to what a distance rounded to 1e-16 allows
        assert span.d_z_min - ROUNDED <= span.d_z_min_bound <= span.d_z_min
        assert span.d_z_max <= span.d_z_max_bound <= span.d_z_max + ROUNDED
    if ends[-1] - ends[0] < 1e-6:  # no room for a band of positive width
        return profile
    radii = np.linspace(ends[0], ends[-1], 4001)
    full = along(links, limits_rad, angle, radii) >= 1.0 - 1e-12
    inside = np.zeros_like(full)
    for lo, hi in profile.bands:
        assert ends[0] <= lo <= hi <= ends[-1]
        inside |= (radii >= lo) & (radii <= hi)
    near_edge = np.zeros_like(full)  # and the ends: breakpoints, where d_z may touch 1 alone
    near_edge[[0, -1]] = True
    for lo, hi in profile.bands:
        near_edge |= (np.abs(radii - lo) < 1e-9) | (np.abs(radii - hi) < 1e-9)
    np.testing.assert_array_equal(full[~near_edge], inside[~near_edge])
    return profile


# -- the paper's Example 1 under its joint limits (issue 26, finding 2) --------------


def test_example_1_under_the_papers_limits_along_the_ray_at_0_deg() -> None:
    profile = check_against_samples(EX1_LINKS, PAPER_LIMITS, 0.0, EX1_REGIONS)
    region_1, region_2, region_3 = profile.ranges
    assert region_1.d_z_min == pytest.approx(0.605127, abs=1e-6)
    assert region_1.d_z_min_at == pytest.approx(2.5944, abs=1e-4)
    assert region_2.d_z_min == pytest.approx(0.686358, abs=1e-6)  # not 0.960 (unlimited)
    assert region_2.d_z_min_at == 8.0 and region_2.d_z_max == 1.0
    assert region_3.d_z_max == pytest.approx(0.976595, abs=1e-6) and region_3.d_z_min == 0.0
    np.testing.assert_allclose(profile.bands, [[0.0, 0.432350], [15.567650, 20.897015]],
                               atol=1e-6)  # fmt: skip
    # task point B (12, 8), d = 14.42 in region 2, has d_z = 0.8807: inside the range
    b = float(exact_limited_orientation_dexterity(EX1_LINKS, [12.0, 8.0], PAPER_LIMITS))
    assert region_2.d_z_min < b < region_2.d_z_max


def test_each_interval_is_searched_on_its_own() -> None:
    whole = ray_dexterity(EX1_LINKS, PAPER_LIMITS, 0.0, [0.0, 37.0])
    split = ray_dexterity(EX1_LINKS, PAPER_LIMITS, 0.0, EX1_REGIONS)
    assert whole.bands == split.bands
    assert whole.ranges[0].d_z_min == min(r.d_z_min for r in split.ranges)
    empty = ray_dexterity(EX1_LINKS, PAPER_LIMITS, 0.0, [0.0, 8.0, 8.0, 21.0]).ranges[1]
    (at_8,) = along(EX1_LINKS, PAPER_LIMITS, 0.0, np.array([8.0]))
    assert empty.d_z_min == empty.d_z_max == at_8
    assert empty.d_z_min_at == empty.d_z_max_at == 8.0


# -- properties ----------------------------------------------------------------------


@PROPERTY
@given(st.data(), designs, limits(), angles)
@example(None, (1.0, 1.0, 1.0), np.radians([[0, 90], [-180, 180], [-180, 180]]), 0.0)
def test_range_and_bands_against_dense_sampling(
    data: st.DataObject | None, links, limits_rad, angle: float
) -> None:
    ends = [0.0, sum(links) / 3, sum(links)] if data is None else data.draw(edges(links))
    check_against_samples(links, limits_rad, angle, ends)


@settings(max_examples=20, deadline=None, derandomize=True)
@given(designs, limits(), angles)
def test_range_holds_the_reference_sampler(links, limits_rad, angle: float) -> None:
    """The plain per-point sampler (independent code) never falls outside the range by
    more than its own error: one sample per feasible arc."""
    step = math.radians(0.5)
    n = round(2 * math.pi / step)
    reach = sum(links)
    (span,) = ray_dexterity(links, limits_rad, angle, [0.0, reach]).ranges
    for radius in np.linspace(0.0, reach, 24):
        point = (radius * math.cos(angle), radius * math.sin(angle))
        sampled = sampled_orientation_dexterity(links, point, step, limits_rad.tolist())
        error = max(len(feasible_arcs(links, point, limits_rad)), 1) / n + 1e-9
        assert span.d_z_min - error <= sampled <= span.d_z_max + error


@PROPERTY
@given(designs, angles)
def test_free_joints_give_the_closed_form(links, angle: float) -> None:
    """The same d_z by another formula: near a tangency, where d_z grows like a square
    root of the distance, rounding alone moves it by up to ~1e-6 (C sqrt(1e-16))."""
    reach = sum(links)
    profile = ray_dexterity(links, FREE, angle, [0.0, reach / 2, reach])
    radii = np.linspace(0.0, reach, 4001)
    points = np.stack([radii * math.cos(angle), radii * math.sin(angle)], axis=-1)
    closed = exact_orientation_dexterity(links, points)
    for span, part in zip(profile.ranges, (radii <= reach / 2, radii >= reach / 2), strict=True):
        assert span.d_z_min <= closed[part].min() + 1e-6
        assert span.d_z_max >= closed[part].max() - 1e-6
    # bands of positive width (a touch of d_z = 1 at one distance is rounding's to call)
    expected = [(a, b) for a, b in full_dexterity_bands(links) if a <= reach and b - a > 1e-9]
    found = [(a, b) for a, b in profile.bands if b - a > 1e-9]
    assert len(found) == len(expected)
    for (lo, hi), (a, b) in zip(found, expected, strict=True):
        assert lo == pytest.approx(a, abs=1e-9) and hi == pytest.approx(min(b, reach), abs=1e-9)


@PROPERTY
@given(st.data(), designs, limits(), angles)
def test_on_a_piece_d_z_follows_its_roots(data: st.DataObject, links, limits_rad, angle) -> None:
    """The bounds of an interval hold d_z at points inside it: the arrangement (c of
    each root) read at a piece's middle holds across the piece."""
    ray = ray_module._ray(links, limits_rad, angle, [0.0, 1.05 * sum(links)])
    pieces = ray_module._pieces(ray, np.array([0.0, 1.05 * sum(links)]))
    index = data.draw(st.integers(0, pieces.edges.size - 2))
    lo, hi = pieces.edges[index], pieces.edges[index + 1]
    x, y = sorted(data.draw(st.floats(lo, hi)) for _ in range(2))
    inside = np.linspace(x, y, 9)
    values = ray.d_z(inside * ray.total)
    anchor = ray.d_z(np.array([x]) * ray.total)
    lower, upper = dexterity_bounds(
        ray.conditions, ray.polynomials, pieces.coefficient[[index]], np.array([x]),
        np.array([y]), anchor, np.array([True]),
    )  # fmt: skip
    # Beside a double root (where two roots meet at a piece's edge) rounding of order eps
    # in the discriminant moves the roots by sqrt(eps) ~ 1.5e-8: an arc of that length
    # may open or close there, so d_z may stray from the bounds by about that much.
    slack = 1e-7
    if x > lo:  # at a breakpoint d_z need not continue the piece
        assert lower[0] <= values.min() + slack and values.max() <= upper[0] + slack


# -- hard cases ----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("links", "limits_deg", "angle"),
    [
        ((1.0, 1.0, 1.0), [[0, 90], [-180, 180], [-180, 180]], 0.0),  # elbow over the ray
        ((1.0, 1.0, 2.0), [[-180, 180], [-90, 90], [-180, 180]], 0.0),  # l3 = l1 + l2
        ((2.0, 1.0, 1.0), [[-90, 0], [-150, 150], [180, 180]], math.pi / 2),  # th3 locked
        ((1.0, 2.0, 2.0), [[-180, 180], [-180, 180], [180, 180]], 0.0),  # l2 = l3, th3 = 180
        ((15.0, 14.0, 8.0), [[0, 0], [0, 0], [-180, 180]], 0.0),  # th1, th2 locked
        ((1.0, 1e-6, 1.0), [[-150, 150], [-150, 150], [-175, 175]], 0.0),
        ((1e6, 1.0, 1.0), [[0, 90], [-45, 45], [-180, 180]], 0.0),
    ],
)
def test_degenerate_arms(links, limits_deg, angle: float) -> None:
    reach = sum(links)
    check_against_samples(links, np.radians(limits_deg), angle, [0.0, reach / 3, reach])


def test_a_plateau_is_certified_quickly(monkeypatch: pytest.MonkeyPatch) -> None:
    """Limited in th3 only, d_z is constant on a piece while its roots turn: a pair of
    roots turning rigidly moves nothing, so the search ends at once."""
    links = (3.429, 1.4945, 1.1191)
    limits_rad = np.array([[-math.pi, math.pi], [-math.pi, math.pi], [-1.8152, -0.4969]])
    monkeypatch.setattr(ray_module, "MAX_EVALUATIONS", 400)
    (span,) = ray_dexterity(links, limits_rad, 1.6402, [2.0145, 3.8486]).ranges
    assert span.d_z_min - span.d_z_min_bound <= RANGE_TOL
    assert span.d_z_max_bound - span.d_z_max <= RANGE_TOL
    assert span.d_z_min == pytest.approx(0.256096, abs=1e-6)


def test_out_of_budget_the_bounds_stay_true(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(ray_module, "MAX_EVALUATIONS", 40)
    (span,) = ray_dexterity(EX1_LINKS, PAPER_LIMITS, 1.0, [0.0, 37.0]).ranges
    values = along(EX1_LINKS, PAPER_LIMITS, 1.0, np.linspace(0.0, 37.0, 4001))
    assert span.d_z_min_bound <= values.min() and span.d_z_max_bound >= values.max()


@pytest.mark.parametrize(
    ("kwargs", "parameter"),
    [
        ({"links": (1.0, -1.0, 1.0)}, "links"),
        ({"joint_limits": np.radians([[-150, 150], [-150, 150]])}, "joint_limits"),
        ({"angle": math.inf}, "angle"),
        ({"edges": [1.0]}, "edges"),
        ({"edges": [2.0, 1.0]}, "edges"),
        ({"edges": [-1.0, 1.0]}, "edges"),
    ],
)
def test_bad_parameters_name_the_parameter(kwargs: dict, parameter: str) -> None:
    arguments = {"links": EX1_LINKS, "joint_limits": PAPER_LIMITS, "angle": 0.0,
                 "edges": [0.0, 37.0], **kwargs}  # fmt: skip
    with pytest.raises(ValueError, match=f"'{parameter}' parameter of ray_dexterity"):
        ray_dexterity(**arguments)
