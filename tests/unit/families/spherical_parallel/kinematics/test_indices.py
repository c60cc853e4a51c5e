"""SPM conditioning indices: the paper's numbers as corrected by
docs/methods/spherical-parallel.md, the exact symmetries as properties, and vectorised
vs the per-orientation reference loop."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from worker.families.spherical_parallel.kinematics import (
    SpmDesign,
    Workspace,
    orientation_samples,
    per_orientation_reference,
    rotation,
    workspace_indices,
    workspace_minimum,
)
from worker.families.spherical_parallel.kinematics.legs import leg_frames

# Random designs and poses are often out of reach: many discards (assume) are expected.
FAST = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
DEG = math.radians
CONE_120 = Workspace(DEG(60.0))
CONE_90 = Workspace(DEG(45.0))
CONE_90_TORSION_30 = Workspace(DEG(45.0), (DEG(-15.0), DEG(15.0)), False)
SAMPLES_120, _ = orientation_samples(CONE_120)
SAMPLES_90, _ = orientation_samples(CONE_90)
SAMPLES_T3, _ = orientation_samples(CONE_90_TORSION_30)

angle = st.floats(0.2, math.pi - 0.2)
designs = st.builds(SpmDesign, angle, angle, angle, st.floats(0.0, 2.5))
coaxial = st.builds(SpmDesign, angle, angle, angle)
branches = st.sampled_from([-1, 1])
sample_sets = st.integers(0, 2**32 - 1).map(
    lambda seed: np.random.default_rng(seed).uniform([-4, 0, -4], [4, 1.3, 4], size=(12, 3))
)


def closure_margin(design: SpmDesign, samples: np.ndarray) -> np.ndarray:
    """Least slack (rad) over the legs of eq 12 as the spherical triangle inequality:
    |a1 - a2| <= angle(u_i, v_i) <= min(a1 + a2, 2 pi - a1 - a2)."""
    frames = leg_frames(design)
    v = np.einsum("njk,ik->nij", rotation(samples), frames.v_star)
    d = np.arccos(np.clip(np.einsum("nij,ij->ni", v, frames.u), -1.0, 1.0))
    a1, a2 = design.alpha1, design.alpha2
    upper = min(a1 + a2, 2 * math.pi - a1 - a2)
    return np.min(np.minimum(d - abs(a1 - a2), upper - d), axis=-1)


def inverse_condition(design: SpmDesign, samples: np.ndarray, branch: int = -1) -> np.ndarray:
    return workspace_indices(design, samples, branch).inverse_condition


# --- the paper's designs on the default 144 samples ------------------------------------


@pytest.mark.parametrize(
    ("degrees", "branch", "samples", "mean_square", "rms", "gci"),
    [
        ((60, 90, 90), -1, SAMPLES_120, 0.2974, 0.5453, None),  # Table 1
        ((120, 90, 90), 1, SAMPLES_120, 0.2974, 0.5453, None),  # its supplementary twin
        ((48, 90, 90), -1, SAMPLES_90, 0.7021, 0.8379, 0.8357),  # Table 2 numerical
        ((50, 105, 75), -1, SAMPLES_90, 0.6157, 0.7847, None),  # Table 2 graphic (errata 0.616)
    ],
)
def test_paper_designs_match_methods_on_the_default_samples(
    degrees: tuple[float, float, float],
    branch: int,
    samples: np.ndarray,
    mean_square: float,
    rms: float,
    gci: float | None,
) -> None:
    design = SpmDesign.from_degrees(*degrees)
    fast = workspace_indices(design, samples, branch)
    loop = per_orientation_reference(design, samples, branch)
    assert fast.all_real and loop.all_real
    for name in ("mean_square_inverse_condition", "rms_inverse_condition", "gci",
                 "min_inverse_condition", "max_inverse_condition", "min_abs_det_a"):  # fmt: skip
        assert getattr(fast, name) == pytest.approx(getattr(loop, name), abs=1e-4)
    assert fast.mean_square_inverse_condition == pytest.approx(mean_square, abs=1e-4)
    assert fast.rms_inverse_condition == pytest.approx(rms, abs=1e-4)
    assert fast.rms_inverse_condition**2 == pytest.approx(fast.mean_square_inverse_condition)
    if gci is not None:
        assert fast.gci == pytest.approx(gci, abs=1e-4)


@pytest.mark.parametrize(
    ("degrees", "samples", "printed"),
    [((60, 90, 90), SAMPLES_120, 0.28), ((48, 90, 90), SAMPLES_90, 0.72),
     ((54.9, 115.4, 33.3, 33.3), SAMPLES_T3, 0.585)],
)  # fmt: skip
def test_printed_c_n_is_the_mean_square_within_the_sampling_spread(
    degrees: tuple[float, ...], samples: np.ndarray, printed: float
) -> None:
    indices = workspace_indices(SpmDesign.from_degrees(*degrees), samples)
    assert indices.mean_square_inverse_condition == pytest.approx(printed, abs=0.04)
    # the root mean square of eq 25 is far from the printed value: the erratum
    assert abs(indices.rms_inverse_condition - printed) > 0.1


def test_graphic_design_value_is_an_erratum() -> None:
    indices = workspace_indices(SpmDesign.from_degrees(50, 105, 75), SAMPLES_90)
    assert indices.mean_square_inverse_condition != pytest.approx(0.67, abs=0.04)
    assert 0.606 <= indices.mean_square_inverse_condition <= 0.675  # METHODS' spread


def test_table_3_design_and_its_twins() -> None:
    printed = SpmDesign.from_degrees(54.9, 115.4, 33.3, 33.3)
    dense, _ = orientation_samples(CONE_90_TORSION_30, azimuth=24, tilt=24, torsion=13)
    assert workspace_indices(printed, dense).mean_square_inverse_condition == pytest.approx(
        0.585, abs=0.005
    )
    default = workspace_indices(printed, SAMPLES_T3).mean_square_inverse_condition
    true_twin = SpmDesign.from_degrees(125.1, 64.6, 33.3, 33.3)
    assert workspace_indices(true_twin, SAMPLES_T3, 1).mean_square_inverse_condition == (
        pytest.approx(default, abs=1e-12)
    )
    printed_twin = SpmDesign.from_degrees(115.4, 54.9, 33.3, 33.3)
    for branch in (-1, 1):
        value = workspace_indices(printed_twin, SAMPLES_T3, branch).mean_square_inverse_condition
        assert value == pytest.approx(0.50, abs=0.01)


FIG_7 = {  # (design, psi2) -> printed range of 1/kappa over a torsion turn at psi1 = 35
    ((48, 90, 90), 15): (0.895, 0.899), ((48, 90, 90), 30): (0.846, 0.863),
    ((48, 90, 90), 45): (0.584, 0.800), ((50, 105, 75), 15): (0.862, 0.867),
    ((50, 105, 75), 30): (0.773, 0.797), ((50, 105, 75), 45): (0.558, 0.758),
}  # fmt: skip


@pytest.mark.parametrize(("key", "printed"), FIG_7.items(), ids=str)
def test_fig_7_ranges_over_a_torsion_turn(
    key: tuple[tuple[float, float, float], float], printed: tuple[float, float]
) -> None:
    degrees, tilt = key
    psi3 = np.radians(np.arange(0.0, 360.0, 0.25))
    psi = np.stack([np.full_like(psi3, DEG(35)), np.full_like(psi3, DEG(tilt)), psi3], axis=-1)
    q = inverse_condition(SpmDesign.from_degrees(*degrees), psi)
    assert (q.min(), q.max()) == pytest.approx(printed, abs=6e-4)
    period = len(psi3) // 3  # 120 deg
    assert q[:period] == pytest.approx(q[period : 2 * period], abs=1e-12)


def test_corner_design_reaches_zero_on_the_workspace_boundary_only() -> None:
    design = SpmDesign.from_degrees(60, 90, 90)
    least = workspace_minimum(design, CONE_120)
    assert least.all_real and least.inverse_condition == pytest.approx(0.0, abs=1e-7)
    assert np.degrees(least.psi[1]) == pytest.approx(60.0)
    assert math.remainder(np.degrees(least.psi[2] - least.psi[0]) - 30.0, 60.0) == (
        pytest.approx(0.0, abs=1e-9)
    )
    assert workspace_indices(design, SAMPLES_120).min_inverse_condition > 0.29
    assert workspace_minimum(SpmDesign.from_degrees(48, 90, 90), CONE_90).inverse_condition > 0.5


def test_a_design_missing_part_of_the_samples_is_not_scored() -> None:
    # METHODS' (50, 120, 48) fails eq 19 in the 120-deg cone: 18 of the 144 samples miss
    design = SpmDesign.from_degrees(50, 120, 48)
    indices = workspace_indices(design, SAMPLES_120)
    assert not indices.all_real and indices.real.sum() == 126
    assert math.isnan(indices.mean_square_inverse_condition) and math.isnan(indices.gci)
    assert np.isnan(indices.inverse_condition[~indices.real]).all()
    loop = per_orientation_reference(design, SAMPLES_120)
    assert np.array_equal(loop.real, indices.real)
    with pytest.raises(ValueError, match="read-only"):
        indices.inverse_condition[0] = 1.0


# --- properties ---------------------------------------------------------------------------


@FAST
@given(designs, sample_sets, branches)
def test_vectorised_matches_the_per_orientation_loop(
    design: SpmDesign, samples: np.ndarray, branch: int
) -> None:
    fast = workspace_indices(design, samples, branch)
    loop = per_orientation_reference(design, samples, branch)
    margin = closure_margin(design, samples)
    clear = np.abs(margin) > 1e-7  # away from the edge of eq 12 both must say the same
    assert np.array_equal(fast.real[clear], margin[clear] > 0)
    assert np.array_equal(loop.real[clear], margin[clear] > 0)
    both = fast.real & loop.real
    assert fast.inverse_condition[both] == pytest.approx(loop.inverse_condition[both], abs=1e-9)
    assert fast.det_a[both] == pytest.approx(loop.det_a[both], abs=1e-9)
    turn = np.angle(np.exp(1j * (fast.theta[both] - loop.theta[both])))
    assert np.abs(turn).max(initial=0.0) < 1e-7


@FAST
@given(designs, sample_sets, branches)
def test_supplementary_twin_is_the_same_mechanism(
    design: SpmDesign, samples: np.ndarray, branch: int
) -> None:
    twin = SpmDesign(math.pi - design.alpha1, math.pi - design.alpha2, design.beta, design.gamma)
    original = workspace_indices(design, samples, branch)
    other = workspace_indices(twin, samples, -branch)
    assert np.array_equal(original.real, other.real)
    assert other.inverse_condition[other.real] == pytest.approx(
        original.inverse_condition[original.real], abs=1e-9
    )


@FAST
@given(designs, sample_sets, branches)
def test_full_turn_twin_scores_the_same_with_the_torsion_origin_moved(
    design: SpmDesign, samples: np.ndarray, branch: int
) -> None:
    twin = SpmDesign(design.alpha1, math.pi - design.alpha2, math.pi - design.beta, design.gamma)
    q = inverse_condition(design, samples, branch)
    moved = inverse_condition(twin, samples + np.array([0.0, 0.0, math.pi]), -branch)
    assert np.array_equal(np.isnan(q), np.isnan(moved))
    assert moved[~np.isnan(q)] == pytest.approx(q[~np.isnan(q)], abs=1e-9)


@FAST
@given(designs, sample_sets, branches)
def test_flipped_pyramids_score_the_same_with_the_azimuth_origin_moved(
    design: SpmDesign, samples: np.ndarray, branch: int
) -> None:
    assume(design.gamma > 1e-9)
    twin = SpmDesign(design.alpha1, design.alpha2, math.pi - design.beta, math.pi - design.gamma)
    q = inverse_condition(design, samples, branch)
    moved = inverse_condition(twin, samples + np.array([math.pi, 0.0, 0.0]), -branch)
    assert np.array_equal(np.isnan(q), np.isnan(moved))
    assert moved[~np.isnan(q)] == pytest.approx(q[~np.isnan(q)], abs=1e-9)


@FAST
@given(designs, sample_sets, branches)
def test_kappa_has_period_120_degrees_in_psi1(
    design: SpmDesign, samples: np.ndarray, branch: int
) -> None:
    q = inverse_condition(design, samples, branch)
    shifted = inverse_condition(design, samples + np.array([2 * math.pi / 3, 0.0, 0.0]), branch)
    assert np.array_equal(np.isnan(q), np.isnan(shifted))
    assert shifted[~np.isnan(q)] == pytest.approx(q[~np.isnan(q)], abs=1e-9)


@FAST
@given(coaxial, sample_sets, st.floats(-4.0, 4.0), branches)
def test_coaxial_kappa_depends_on_psi2_and_psi3_minus_psi1_only(
    design: SpmDesign, samples: np.ndarray, turn: float, branch: int
) -> None:
    q = inverse_condition(design, samples, branch)
    turned = inverse_condition(design, samples + np.array([turn, 0.0, turn]), branch)
    assert np.array_equal(np.isnan(q), np.isnan(turned))
    assert turned[~np.isnan(q)] == pytest.approx(q[~np.isnan(q)], abs=1e-9)


@FAST
@given(designs, sample_sets, branches)
def test_mirror_image_flips_the_branch(design: SpmDesign, samples: np.ndarray, branch: int) -> None:
    mirrored = np.stack([math.pi - samples[:, 0], samples[:, 1], -samples[:, 2]], axis=-1)
    q = inverse_condition(design, samples, branch)
    other = inverse_condition(design, mirrored, -branch)
    assert np.array_equal(np.isnan(q), np.isnan(other))
    assert other[~np.isnan(q)] == pytest.approx(q[~np.isnan(q)], abs=1e-9)


@FAST
@given(designs, sample_sets)
def test_indices_are_means_of_the_per_sample_values(design: SpmDesign, samples: np.ndarray) -> None:
    indices = workspace_indices(design, samples[:, :] * [1.0, 0.3, 1.0])
    q = indices.inverse_condition
    if not indices.all_real:
        assert math.isnan(indices.gci) and math.isnan(indices.min_abs_det_a)
        return
    assert 0.0 <= indices.min_inverse_condition <= indices.gci <= indices.max_inverse_condition <= 1
    assert indices.gci <= indices.rms_inverse_condition + 1e-15  # power-mean inequality
    assert indices.mean_square_inverse_condition == pytest.approx(np.mean(q**2), abs=1e-15)


def test_bad_samples_name_the_parameter() -> None:
    design = SpmDesign(1.0, 1.0, 1.0)
    with pytest.raises(ValueError, match=r"The 'samples' parameter of workspace_indices"):
        workspace_indices(design, np.zeros((0, 3)))
    with pytest.raises(ValueError, match=r"'samples' parameter of per_orientation_reference"):
        per_orientation_reference(design, np.zeros(3))
    with pytest.raises(ValueError, match=r"The 'branch' parameter of workspace_indices"):
        workspace_indices(design, SAMPLES_120, branch=2)
