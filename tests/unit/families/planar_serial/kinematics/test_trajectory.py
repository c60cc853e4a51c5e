"""Distance ranges of task points and trajectories (step 1 of the §4 algorithm)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from worker.families.planar_serial.kinematics.trajectory import (
    DistanceRange,
    points_distance_range,
    polyline_distance_range,
    polynomial_distance_range,
    sample_polynomial,
)

EX1_CUBIC = [-0.2292, 7.625, -78.83, 252.0]  # eq (12)
EX2_TASK = [(16, 19), (18, 0), (-8, -25), (-15, 11), (-10, 16), (20, -21), (-7, 27)]


@pytest.mark.parametrize(("x_start", "x_end"), [(14.0, 8.0), (8.0, 14.0)])
def test_example1_cubic_distance_range(x_start: float, x_end: float) -> None:
    # docs/methods/planar-serial.md errata: 10.3923 at x = 10.2044 and 19.7673 at x = 14 (paper: 10
    # and 20)
    span = polynomial_distance_range(EX1_CUBIC, x_start, x_end)
    assert span.d_min == pytest.approx(10.3923, abs=5e-5)
    assert span.at_min[0] == pytest.approx(10.2044, abs=5e-5)
    assert span.d_max == pytest.approx(19.7673, abs=5e-5)
    assert span.at_max[0] == 14.0
    assert span.at_max[1] == pytest.approx(np.polyval(EX1_CUBIC, 14.0))


def test_example1_cubic_range_matches_dense_sampling() -> None:
    samples = sample_polynomial(EX1_CUBIC, 14.0, 8.0, 600_001)
    d = np.hypot(samples[:, 0], samples[:, 1])
    span = polynomial_distance_range(EX1_CUBIC, 14.0, 8.0)
    assert span.d_min <= d.min() <= span.d_min + 1e-9
    assert span.d_max == pytest.approx(d.max(), abs=1e-12)


def test_example2_task_points() -> None:
    # docs/methods/planar-serial.md errata: min 18 at B, max 29 at F (the paper swaps min and max)
    assert points_distance_range(EX2_TASK) == DistanceRange(18.0, 29.0, (18.0, 0.0), (20.0, -21.0))


def test_polyline_minimum_inside_a_segment() -> None:
    span = polyline_distance_range([[3.0, 4.0], [1.0, 1.0], [1.0, -1.0], [-2.0, -2.0]])
    assert (span.d_min, span.at_min) == (1.0, (1.0, 0.0))
    assert (span.d_max, span.at_max) == (5.0, (3.0, 4.0))
    single = polyline_distance_range([[3.0, 4.0]])
    assert (single.d_min, single.d_max) == (5.0, 5.0)


def test_sample_polynomial_is_inclusive_and_ordered() -> None:
    samples = sample_polynomial([1.0, 0.0, 0.0], 2.0, -1.0, 4)
    np.testing.assert_allclose(samples, [[2, 4], [1, 1], [0, 0], [-1, 1]])


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.floats(-3.0, 3.0), min_size=1, max_size=5),
    st.floats(-4.0, 4.0),
    st.floats(-4.0, 4.0),
)
def test_polynomial_range_bounds_dense_samples(coefficients, x_start, x_end) -> None:
    samples = sample_polynomial(coefficients, x_start, x_end, 2001)
    d = np.hypot(samples[:, 0], samples[:, 1])
    span = polynomial_distance_range(coefficients, x_start, x_end)
    scale = 1.0 + d.max()
    assert span.d_min <= d.min() + 1e-9 * scale
    assert span.d_max >= d.max() - 1e-9 * scale
    x, y = span.at_min
    assert math.hypot(x, y) == pytest.approx(span.d_min)
    assert min(x_start, x_end) <= x <= max(x_start, x_end)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(-5, 5), st.floats(-5, 5)), min_size=1, max_size=6))
def test_polyline_range_bounds_dense_samples(vertices) -> None:
    v = np.array(vertices)
    t = np.linspace(0.0, 1.0, 1001)[:, None, None]
    dense = (v[:-1] + t * (v[1:] - v[:-1])).reshape(-1, 2) if len(v) > 1 else v
    d = np.hypot(dense[:, 0], dense[:, 1])
    span = polyline_distance_range(v)
    assert span.d_min <= d.min() + 1e-12
    assert span.d_max == pytest.approx(d.max())


@pytest.mark.parametrize(
    ("call", "parameter", "function"),
    [
        (lambda: points_distance_range([[1.0, 2.0, 3.0]]), "points", "points_distance_range"),
        (lambda: points_distance_range(np.zeros((0, 2))), "points", "points_distance_range"),
        (lambda: polyline_distance_range([[np.nan, 1.0]]), "vertices", "polyline_distance_range"),
        (lambda: polynomial_distance_range([], 0.0, 1.0), "coefficients",
         "polynomial_distance_range"),
        (lambda: polynomial_distance_range([1.0], math.inf, 1.0), "x_start",
         "polynomial_distance_range"),
        (lambda: sample_polynomial([1.0], 0.0, 1.0, 1), "samples", "sample_polynomial"),
    ],
)  # fmt: skip
def test_bad_parameters_name_the_parameter(call, parameter, function) -> None:
    with pytest.raises(ValueError, match=rf"The '{parameter}' parameter of {function} must be"):
        call()
