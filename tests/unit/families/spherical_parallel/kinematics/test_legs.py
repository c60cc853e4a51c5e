"""SPM kinematics (docs/methods/spherical-parallel.md): axes, inverse kinematics, Jacobian, kappa.

Closed-form checks, hypothesis properties (closure, branch, J vs central differences,
kappa >= 1) and the two kinds of singularity."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from worker.families.spherical_parallel.kinematics import (
    SpmDesign,
    condition_number,
    inverse_condition_number,
    inverse_kinematics,
    jacobian,
    rotation,
    unit_vectors,
)
from worker.families.spherical_parallel.kinematics.legs import leg_frames, solve_legs

# Random designs and poses are often out of reach: many discards (assume) are expected.
FAST = settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
angle = st.floats(0.15, math.pi - 0.15)
designs = st.builds(SpmDesign, angle, angle, angle, st.floats(0.0, 2.6))
orientations = st.tuples(
    st.floats(-math.pi, math.pi), st.floats(0.0, 1.4), st.floats(-math.pi, math.pi)
).map(np.array)
branches = st.sampled_from([-1, 1])
DEG = math.radians


def test_rotation_is_tilt_about_e_psi_after_torsion_about_z() -> None:
    rng = np.random.default_rng(7)
    psi = rng.uniform(-4.0, 4.0, size=(50, 3))
    expected = [
        Rotation.from_rotvec(p[1] * np.array([-math.sin(p[0]), math.cos(p[0]), 0.0]))
        * Rotation.from_rotvec([0.0, 0.0, p[2]])
        for p in psi
    ]
    assert rotation(psi) == pytest.approx(np.array([r.as_matrix() for r in expected]), abs=1e-12)
    # the platform axis leans by psi2 toward azimuth psi1
    axis = rotation(np.array([DEG(30.0), DEG(20.0), 1.234]))[:, 2]
    assert axis == pytest.approx(
        [math.sin(DEG(20)) * math.cos(DEG(30)), math.sin(DEG(20)) * math.sin(DEG(30)),
         math.cos(DEG(20))], abs=1e-12
    )  # fmt: skip


def test_unit_vectors_match_eqs_3_5_7_at_the_reference_orientation() -> None:
    design = SpmDesign.from_degrees(50.0, 75.0, 60.0, 20.0)
    theta = np.array([0.3, -1.1, 2.0])
    u, w, v = unit_vectors(design, theta, np.zeros(3))
    s, c = math.sin, math.cos
    a1, b, g = design.alpha1, design.beta, design.gamma
    for i in range(3):
        eta, th = 2 * math.pi * i / 3, theta[i]
        assert u[i] == pytest.approx([-s(eta) * s(g), c(eta) * s(g), -c(g)], abs=1e-12)
        assert w[i] == pytest.approx([
            -s(eta) * s(g) * c(a1) + (c(eta) * s(th) - s(eta) * c(g) * c(th)) * s(a1),
            c(eta) * s(g) * c(a1) + (s(eta) * s(th) + c(eta) * c(g) * c(th)) * s(a1),
            -c(g) * c(a1) + s(g) * c(th) * s(a1),
        ], abs=1e-12)  # fmt: skip
        assert v[i] == pytest.approx([-s(eta) * s(b), c(eta) * s(b), c(b)], abs=1e-12)
    assert np.einsum("ij,ij->i", u, w) == pytest.approx([c(a1)] * 3, abs=1e-12)


@FAST
@given(designs, orientations, branches)
def test_every_inverse_kinematics_solution_closes_on_its_branch(
    design: SpmDesign, psi: np.ndarray, branch: int
) -> None:
    theta, real = inverse_kinematics(design, psi, branch)
    assume(bool(real))
    u, w, v = unit_vectors(design, theta, psi)
    assert np.einsum("ij,ij->i", w, v) == pytest.approx([math.cos(design.alpha2)] * 3, abs=1e-9)
    b = np.einsum("ij,ij->i", np.cross(u, w), v)
    assert np.all(branch * b >= -1e-9)
    # the closed form's b_i is (u_i x w_i) . v_i itself, sign included
    frames = leg_frames(design)
    assert solve_legs(design, frames, v, branch).b == pytest.approx(b, abs=1e-9)


@FAST
@given(designs, orientations)
def test_no_real_solution_is_data_and_matches_eq_12(design: SpmDesign, psi: np.ndarray) -> None:
    theta, real = inverse_kinematics(design, psi)
    frames = leg_frames(design)
    v = rotation(psi) @ frames.v_star.T
    # eq 12 written as the spherical triangle inequality on the angle between u_i and v_i
    d = np.arccos(np.clip(np.einsum("ij,ji->i", frames.u, v), -1, 1))
    a1, a2 = design.alpha1, design.alpha2
    margin = np.minimum(d - abs(a1 - a2), np.minimum(a1 + a2, 2 * math.pi - a1 - a2) - d)
    assume(np.all(np.abs(margin) > 1e-7))
    assert bool(real) == bool(np.all(margin > 0))
    assert np.isnan(theta).any() == (not real)


def test_inverse_kinematics_is_batched_on_leading_axes() -> None:
    design = SpmDesign.from_degrees(60.0, 90.0, 90.0)
    psi = np.radians([[[0, 10, 0], [45, 30, 15]], [[90, 50, -20], [200, 59, 100]]])
    theta, real = inverse_kinematics(design, psi)
    assert theta.shape == (2, 2, 3) and real.shape == (2, 2) and real.all()
    for idx in np.ndindex(2, 2):
        one, _ = inverse_kinematics(design, psi[idx])
        assert theta[idx] == pytest.approx(one, abs=1e-14)


@FAST
@given(designs, orientations, branches, st.integers(0, 2))
def test_jacobian_matches_central_differences(
    design: SpmDesign, psi: np.ndarray, branch: int, axis: int
) -> None:
    theta, real = inverse_kinematics(design, psi, branch)
    assume(bool(real))
    a, b_mat, j = jacobian(design, theta, psi)
    assume(np.all(np.abs(np.diag(b_mat)) > 0.05))
    frames = leg_frames(design)
    omega = np.eye(3)[axis]
    step = 1e-6

    def solved(eps: float) -> np.ndarray:
        q = Rotation.from_rotvec(eps * omega).as_matrix() @ rotation(psi)
        return solve_legs(design, frames, frames.v_star @ q.T, branch).theta

    plus, minus = solved(step), solved(-step)
    rate = np.angle(np.exp(1j * (plus - minus))) / (2 * step)
    assert rate == pytest.approx(j @ omega, rel=1e-5, abs=1e-5)
    assert np.diag(b_mat) * rate == pytest.approx(a @ omega, rel=1e-5, abs=1e-5)  # eq 9


@FAST
@given(st.lists(st.floats(-5, 5), min_size=9, max_size=9).map(lambda x: np.reshape(x, (3, 3))))
def test_kappa_is_at_least_one_and_matches_the_definition(j: np.ndarray) -> None:
    kappa = condition_number(j)
    inverse = inverse_condition_number(j)
    assert 0.0 <= inverse <= 1.0 and kappa >= 1.0 - 1e-12
    det = np.linalg.det(j)
    assume(abs(det) > 1e-6 * max(1.0, np.abs(j).max()) ** 3)
    weighted = math.sqrt(np.trace(j.T @ j) / 3) * math.sqrt(
        np.trace(np.linalg.inv(j).T @ np.linalg.inv(j)) / 3
    )
    assert kappa == pytest.approx(weighted, rel=1e-9)


def test_kappa_of_isotropic_and_singular_matrices() -> None:
    rot = Rotation.from_rotvec([0.3, -0.2, 0.9]).as_matrix()
    assert condition_number(2.5 * rot) == pytest.approx(1.0, abs=1e-12)
    assert condition_number(np.diag([1.0, 1.0, 0.0])) == math.inf
    assert inverse_condition_number(np.full((3, 3), np.inf)) == 0.0
    stack = np.stack([np.eye(3), np.diag([1.0, 2.0, 0.0])])
    assert condition_number(stack).tolist() == [1.0, math.inf]


def test_type_ii_singularity_gives_exactly_zero() -> None:
    # (90, 90, 90), gamma = 0, home pose: every w_i x v_i is vertical, det A = 0, B regular
    design = SpmDesign.from_degrees(90.0, 90.0, 90.0)
    theta, real = inverse_kinematics(design, np.zeros(3))
    a, b_mat, j = jacobian(design, theta, np.zeros(3))
    assert real and abs(np.linalg.det(a)) < 1e-15
    assert np.abs(np.diag(b_mat)) == pytest.approx([1.0, 1.0, 1.0], abs=1e-12)
    assert inverse_condition_number(j) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("offset", [90.0, 210.0, 330.0, 30.0])
def test_table_1_optimum_meets_a_leg_singularity_on_the_workspace_boundary(offset: float) -> None:
    # (60, 90, 90) at tilt 60 deg, psi3 - psi1 = 90 (or 30) mod 120: a leg folds (b_i = 0,
    # type I) while det A stays ~0.80 — docs/methods/spherical-parallel.md calls it "leg-folding";
    # 1/kappa = 0.
    design = SpmDesign.from_degrees(60.0, 90.0, 90.0)
    psi = np.radians([17.0, 60.0, 17.0 + offset])
    theta, real = inverse_kinematics(design, psi)
    a, b_mat, j = jacobian(design, theta, psi)
    assert real
    assert np.min(np.abs(np.diag(b_mat))) == pytest.approx(0.0, abs=1e-7)
    assert np.linalg.det(a) == pytest.approx(0.79941, abs=1e-4)
    # b_i = sqrt(rho^2 - P^2) turns a rounding error of 1e-16 into ~1e-8: that is how
    # close to 0 a type-I singularity can come in floating point (type II: ~1e-16)
    assert inverse_condition_number(j) == pytest.approx(0.0, abs=1e-7)


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: rotation([1.0, 2.0]), r"The 'psi' parameter of rotation must be finite angles"),
        (lambda: rotation([np.nan, 0, 0]), r"'psi' parameter of rotation"),
        (lambda: inverse_kinematics(SpmDesign(1, 1, 1), np.zeros(3), branch=0),
         r"The 'branch' parameter of inverse_kinematics must be -1 or 1"),
        (lambda: inverse_kinematics((1, 1, 1, 0), np.zeros(3)),  # type: ignore[arg-type]
         r"The 'design' parameter of inverse_kinematics must be an SpmDesign"),
        (lambda: unit_vectors(SpmDesign(1, 1, 1), np.zeros((2, 3)), np.zeros((3, 3))),
         r"The 'psi' parameter of unit_vectors must be broadcastable with theta"),
        (lambda: condition_number(np.eye(2)), r"The 'J' parameter of inverse_condition_number"),
        (lambda: SpmDesign(0.0, 1.0, 1.0), r"The 'alpha1' parameter of SpmDesign must be"),
        (lambda: SpmDesign(1.0, 1.0, 1.0, -0.1), r"The 'gamma' parameter of SpmDesign"),
    ],
)  # fmt: skip
def test_bad_arguments_name_the_parameter(call: object, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        call()  # type: ignore[operator]


def test_design_records_convert_degrees() -> None:
    design = SpmDesign.from_degrees(60.0, 90.0, 90.0)
    assert design.degrees() == pytest.approx((60.0, 90.0, 90.0, 0.0))
    assert isinstance(SpmDesign(np.float64(1.0), 1, 1).alpha1, float)
