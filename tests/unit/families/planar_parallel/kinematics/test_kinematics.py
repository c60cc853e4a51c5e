"""2-DOF planar parallel robots, point kinematics: the paper's closed forms and numbers as
corrected by docs/methods/planar-parallel.md, and properties (eq 7 vs SVD, J vs finite
differences, IK closure) over all three actuation types of Fig. 1."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from worker.families.planar_parallel.kinematics import (
    Architecture,
    condition_limit_from_pressure_angle,
    conditioning_map,
    inverse_condition,
    inverse_kinematics,
    isotropic_architecture,
    isotropic_point,
    jacobian,
    max_condition_limit,
    pressure_angles,
    reference_jacobian,
    sampled_inverse_condition,
    workspace_area,
)
from worker.families.planar_parallel.kinematics.model import chain_terms

ACTUATIONS = ("proximal-arm", "telescopic-leg", "linear-drive")
MODES = ((1, -1), (1, 1), (-1, 1), (-1, -1))
PAPER_MODE = (1, -1)
FAST = settings(max_examples=150, deadline=None)

architectures = st.builds(
    Architecture,
    actuation=st.sampled_from(ACTUATIONS),
    l1=st.floats(0.5, 2.0),
    l2=st.floats(0.5, 3.0),
    e=st.floats(0.0, 1.5),
)
points = st.tuples(st.floats(-4.0, 4.0), st.floats(-4.0, 4.0))
modes = st.sampled_from(MODES)


def near_a_pivot(arch: Architecture, point: tuple[float, float]) -> bool:
    """On a pivot the IK is degenerate (any arm angle when l1 = l2; |r| is not smooth)."""
    return min(math.dist(point, (arch.e, 0.0)), math.dist(point, (-arch.e, 0.0))) < 1e-3


# --- the isotropic design, eqs (11)-(12) ----------------------------------------------


@pytest.mark.parametrize("delta", np.linspace(1.0, 2.5, 16))
def test_isotropic_point_for_every_delta(delta: float) -> None:
    arch = isotropic_architecture(delta)
    x, y = isotropic_point(arch)
    assert (x, y) == (0.0, pytest.approx(-math.sqrt(0.5) * (1.0 + delta), abs=1e-12))
    joints, reachable = inverse_kinematics(arch, (x, y))
    assert bool(reachable)
    np.testing.assert_allclose(np.degrees(joints), [-45.0, -135.0], atol=1e-6)
    assert float(inverse_condition(arch, (x, y))) == pytest.approx(1.0, abs=1e-6)
    # sigma_1 = sigma_2 = 1 (eq 11): J is orthogonal
    j = jacobian(arch, (x, y))
    np.testing.assert_allclose(j @ j.T, np.eye(2), atol=1e-12)
    np.testing.assert_allclose(np.degrees(pressure_angles(arch, (x, y))), [90.0, 90.0], atol=1e-6)


def test_eq12_offsets() -> None:
    # docs/methods/planar-parallel.md: the paper prints e = 0.6001 for delta = 1.85; eq (12) gives
    # 0.6010
    assert isotropic_architecture(1.7).e == pytest.approx(0.4950, abs=5e-5)
    assert isotropic_architecture(1.85).e == pytest.approx(0.6010, abs=5e-5)
    assert abs(isotropic_architecture(1.85).e - 0.6001) > 5e-4
    assert isotropic_architecture(1.0).e == 0.0


def test_only_the_papers_working_mode_gives_the_isotropic_optimum() -> None:
    arch = isotropic_architecture(1.7)
    point = isotropic_point(arch)
    others = [float(inverse_condition(arch, point, mode)) for mode in MODES[1:]]
    assert max(others) < 0.9


@pytest.mark.parametrize(
    ("arch", "expected"),
    [
        (Architecture("telescopic-leg", 1.0, 1.0, 0.4), (0.0, -0.4)),
        (Architecture("linear-drive", 1.0, 1.5, 0.0), (0.0, -1.5 / math.sqrt(2.0))),
    ],
)
def test_isotropic_points_of_the_other_types(
    arch: Architecture, expected: tuple[float, float]
) -> None:
    assert isotropic_point(arch) == pytest.approx(expected, abs=1e-12)
    assert float(inverse_condition(arch, expected)) == pytest.approx(1.0, abs=1e-12)


def test_isotropic_point_of_a_non_eq12_proximal_arm_is_searched() -> None:
    arch = Architecture("proximal-arm", 1.0, 1.6, 0.4)
    x, y = isotropic_point(arch)
    on_axis = inverse_condition(arch, np.stack([np.zeros(2001), np.linspace(-3.0, 0.0, 2001)], 1))
    assert x == 0.0 and -3.0 < y < 0.0
    assert float(inverse_condition(arch, (x, y))) >= np.nanmax(on_axis) - 1e-12


# --- eq (17) then eq (7): the conditioning limit from [beta] ---------------------------


@pytest.mark.parametrize(
    ("beta", "limit", "delta"), [(30.0, 0.52555, 1.7445), (35.0, 0.57672, 1.9185)]
)
def test_max_condition_limit(beta: float, limit: float, delta: float) -> None:
    got_limit, got_delta = max_condition_limit(beta)
    assert got_limit == pytest.approx(limit, abs=1e-4)
    assert got_delta == pytest.approx(delta, abs=1e-4)


def test_the_papers_printed_limits() -> None:
    # 0.526 for 30 deg rounds 0.52555 up; 0.581 for 35 deg needs [beta] ~ 35.3-35.4 deg
    assert round(max_condition_limit(30.0)[0], 3) == 0.526
    assert max_condition_limit(35.0)[0] < 0.581 - 4e-3
    assert max_condition_limit(35.3)[0] < 0.581 < max_condition_limit(35.4)[0]


def test_condition_limit_is_beta_on_the_top_edge() -> None:
    # eq (17): at (e, y0) chain 1's pressure angle (eq 15) is exactly [beta]
    delta = 1.7
    arch = isotropic_architecture(delta)
    y0 = -math.sqrt(1.0 + delta**2 - 2.0 * delta * math.cos(math.radians(30.0)))
    assert math.degrees(float(pressure_angles(arch, (arch.e, y0))[0])) == pytest.approx(30.0)
    limit = condition_limit_from_pressure_angle(30.0, delta)
    assert isinstance(limit, float)
    assert limit == pytest.approx(float(inverse_condition(arch, (arch.e, y0))), abs=1e-15)


def test_condition_limit_is_batched() -> None:
    deltas = np.array([[1.0, 1.5], [2.0, 2.5]])
    limits = condition_limit_from_pressure_angle(30.0, deltas)
    assert isinstance(limits, np.ndarray) and limits.shape == (2, 2)
    expected = [condition_limit_from_pressure_angle(30.0, float(d)) for d in deltas.ravel()]
    np.testing.assert_allclose(limits.ravel(), expected, atol=1e-15)


# --- eq (7) against the SVD, J against finite differences, IK closure ------------------


@FAST
@given(architectures, points, modes)
def test_eq7_equals_the_svd_ratio(arch: Architecture, point: tuple[float, float], mode) -> None:
    assume(not near_a_pivot(arch, point))
    terms = chain_terms(arch, mode, np.array(point))
    # Where A is (nearly) singular J does not exist, and near a double singularity
    # (eq 9) 1/kappa hangs on v1 / v2, itself a square root of a rounding-level number.
    scale = arch.l1 if arch.actuation == "proximal-arm" else 1.0
    assume(bool(terms.reachable) and float(np.min(np.abs(terms.a))) > 1e-2 * scale)
    ours = float(inverse_condition(arch, point, mode))
    reference = sampled_inverse_condition(arch, point, mode)
    assert ours == pytest.approx(reference, abs=1e-9)


def test_reachability_agrees_with_the_reference() -> None:
    rng = np.random.default_rng(2004)
    for actuation in ACTUATIONS:
        arch = Architecture(actuation, 1.0, 1.6, 0.4)
        for mode in MODES:
            pts = rng.uniform(-3.0, 3.0, (600, 2))
            ours = inverse_condition(arch, pts, mode)
            reference = np.array([sampled_inverse_condition(arch, p, mode) for p in pts])
            np.testing.assert_array_equal(np.isnan(ours), np.isnan(reference))
            np.testing.assert_allclose(ours, reference, atol=1e-12)


@FAST
@given(architectures, points, modes)
def test_inverse_condition_in_unit_interval(
    arch: Architecture, point: tuple[float, float], mode
) -> None:
    value = float(inverse_condition(arch, point, mode))
    assert math.isnan(value) or 0.0 <= value <= 1.0


@FAST
@given(architectures, points, modes)
def test_jacobian_matches_finite_differences(
    arch: Architecture, point: tuple[float, float], mode
) -> None:
    assume(not near_a_pivot(arch, point))
    step = 1e-6
    p = np.array(point)
    j = jacobian(arch, p, mode)
    assume(np.all(np.isfinite(j)) and np.abs(j).max() < 20.0)
    shifted = p + np.array([[step, 0.0], [-step, 0.0], [0.0, step], [0.0, -step]])
    q, reachable = inverse_kinematics(arch, shifted, mode)
    assume(bool(np.all(reachable)))
    diff = np.stack([q[0] - q[1], q[2] - q[3]], axis=-1)  # (chain, axis)
    if arch.actuation == "proximal-arm":
        diff = np.angle(np.exp(1j * diff))  # unwrap across +-pi
    np.testing.assert_allclose(diff / (2.0 * step), j, atol=2e-5 * max(1.0, np.abs(j).max()))


def test_jacobian_matches_the_reference_solve() -> None:
    rng = np.random.default_rng(7)
    for actuation in ACTUATIONS:
        arch = Architecture(actuation, 1.2, 1.7, 0.5)
        for p in rng.uniform(-2.5, 2.5, (200, 2)):
            ours, reference = jacobian(arch, p), reference_jacobian(arch, p)
            if reference is None:
                continue
            np.testing.assert_allclose(ours, reference, rtol=1e-9, atol=1e-12)


@FAST
@given(points, st.floats(0.5, 2.0), st.floats(0.5, 3.0), st.floats(0.0, 1.5), modes)
def test_proximal_ik_is_eq2_and_closes_the_loop(
    point: tuple[float, float], l1: float, l2: float, e: float, mode
) -> None:
    arch = Architecture("proximal-arm", l1, l2, e)
    joints, reachable = inverse_kinematics(arch, point, mode)
    assume(bool(reachable) and not near_a_pivot(arch, point))
    # on a reach boundary (A_ii = 0) eq (2)'s root is sqrt(rounding): both forms are 0/0
    assume(float(np.min(np.abs(chain_terms(arch, mode, np.array(point)).a))) > 1e-6 * l1)
    x, y = point
    for i, (sign, m) in enumerate(zip((1.0, -1.0), mode, strict=True)):
        a, b = -2.0 * l1 * y, -2.0 * l1 * (x - sign * e)
        c = (x - sign * e) ** 2 + y * y + l1 * l1 - l2 * l2  # = x^2 + y^2 + e^2 + ... - 2 sgn e x
        root = m * math.sqrt(max(a * a - c * c + b * b, 0.0))
        # eq (2): tan(th/2) = (-a + root) / (c - b) = (c + b) / (-a - root); take the form
        # whose numerator does not cancel (the larger one if a = 0)
        primary, twin = (-a + root, c - b), (c + b, -a - root)
        if -a * m < 0 or (-a * m == 0 and math.hypot(*twin) > math.hypot(*primary)):
            primary = twin
        half = math.atan2(*primary)
        assert math.cos(2.0 * half - joints[i]) == pytest.approx(1.0, abs=1e-9)  # eq (2)
        elbow = (sign * e + l1 * math.cos(joints[i]), l1 * math.sin(joints[i]))
        assert math.dist(point, elbow) == pytest.approx(l2, rel=1e-9, abs=1e-9)  # eq (1)
    assert np.all((-np.pi < joints) & (joints <= np.pi))


@FAST
@given(architectures, points, modes)
def test_ik_closes_the_loop_for_legs_and_drives(
    arch: Architecture, point: tuple[float, float], mode
) -> None:
    assume(arch.actuation != "proximal-arm")
    joints, reachable = inverse_kinematics(arch, point, mode)
    assume(bool(reachable))
    for i, sign in enumerate((1.0, -1.0)):
        if arch.actuation == "telescopic-leg":
            assert joints[i] == pytest.approx(math.dist(point, (sign * arch.e, 0.0)))
        else:
            assert math.dist(point, (joints[i], 0.0)) == pytest.approx(arch.l2, abs=1e-12)
            assert (joints[i] - point[0]) * mode[i] >= 0.0


@FAST
@given(architectures, points, modes)
def test_pressure_angle_definitions(arch: Architecture, point: tuple[float, float], mode) -> None:
    terms = chain_terms(arch, mode, np.array(point))
    assume(bool(terms.reachable))
    beta = pressure_angles(arch, point, mode)
    scale = arch.l1 if arch.actuation == "proximal-arm" else 1.0
    # eq (8): A_ii^2 = sin^2(beta_i), A normalised as in eq (7) (squares: at a reach
    # boundary |A_ii| = sqrt(rounding) ~ 1e-8)
    np.testing.assert_allclose(np.sin(beta) ** 2, (terms.a / scale) ** 2, atol=1e-12)
    if arch.actuation == "proximal-arm":  # eq (15) = acute angle between the links
        cosines = np.abs(np.sum(terms.w * terms.u, axis=-1))
        np.testing.assert_allclose(np.cos(beta), cosines, atol=1e-9)


# --- the map and the area ---------------------------------------------------------------


@pytest.mark.parametrize("actuation", ACTUATIONS)
def test_conditioning_map_matches_the_point_functions(actuation: str) -> None:
    arch = Architecture(actuation, 1.0, 1.7, 0.495)  # type: ignore[arg-type]
    x, y = np.linspace(-3.0, 3.0, 41), np.linspace(-3.2, 1.0, 37)
    cmap = conditioning_map(arch, x, y)
    grid = np.stack(np.meshgrid(x, y), axis=-1)
    assert cmap.inverse_condition.shape == (37, 41) and cmap.joints.shape == (37, 41, 2)
    np.testing.assert_allclose(cmap.inverse_condition, inverse_condition(arch, grid), atol=1e-14)
    np.testing.assert_array_equal(cmap.reachable, np.isfinite(cmap.inverse_condition))
    np.testing.assert_allclose(cmap.pressure_angles, pressure_angles(arch, grid), atol=1e-14)
    np.testing.assert_allclose(cmap.joints, inverse_kinematics(arch, grid)[0], atol=1e-14)
    expected_min = np.min(pressure_angles(arch, grid), axis=-1)
    np.testing.assert_allclose(cmap.min_pressure_angle, expected_min, atol=1e-14)


def test_workspace_area_counts_cells() -> None:
    x, y = np.linspace(-2.0, 2.0, 801), np.linspace(-2.0, 2.0, 801)
    mask = np.hypot(x[None, :], y[:, None]) <= 1.5
    assert workspace_area(mask, x, y) == pytest.approx(math.pi * 1.5**2, rel=2e-3)


# --- bad parameters ---------------------------------------------------------------------


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (
            lambda: Architecture("proximal-arm", 1.0, -1.0, 0.0),
            "The 'l2' parameter of Architecture",
        ),
        (lambda: Architecture("scissor", 1.0, 1.0, 0.0), "The 'actuation' parameter of"),  # type: ignore[arg-type]
        (lambda: Architecture("proximal-arm", 1.0, 1.0, -0.1), "The 'e' parameter"),
        (lambda: isotropic_architecture(0.5), "The 'l2' parameter of isotropic_architecture"),
        (lambda: inverse_condition(isotropic_architecture(2.0), [1.0, 2.0, 3.0]), "'points'"),
        (lambda: jacobian(isotropic_architecture(2.0), [0.0, -1.0], (1, 0)), "'working_mode'"),
        (lambda: condition_limit_from_pressure_angle(95.0, 1.5), "'allowable_deg'"),
        (lambda: condition_limit_from_pressure_angle(30.0, 0.9), "'delta'"),
        (lambda: max_condition_limit(30.0, (2.0, 1.0)), "'delta_range'"),
        (lambda: workspace_area(np.ones((3, 2), bool), [0, 1, 2], [0, 1]), "'mask'"),
    ],
)
def test_bad_parameters(call, message: str) -> None:
    with pytest.raises(ValueError, match=message) as info:
        call()
    assert "must be" in str(info.value) and "instead." in str(info.value)
