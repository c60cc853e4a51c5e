"""Three-link planar arms: the paper's numbers as corrected by docs/methods/planar-serial.md, closed
forms, and properties (exact vs brute force, vectorised vs per-point reference)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from worker.families.planar_serial.kinematics import (
    band_area,
    exact_orientation_dexterity,
    forward_kinematics,
    full_dexterity_bands,
    limited_orientation_dexterity,
    orientation_samples,
    paper_regions,
    reach_radii,
    region_radii,
    sampled_orientation_dexterity,
    synthesise_links,
)
from worker.families.planar_serial.kinematics.trajectory import (
    points_distance_range,
    polynomial_distance_range,
)

EX1_CUBIC = [-0.2292, 7.625, -78.83, 252.0]  # eq (12)
EX1_LINKS = (15.0, 14.0, 8.0)
EX1_SWAPPED = (15.0, 8.0, 14.0)
EX1_TASK = {"A": (14, 14), "B": (12, 8), "C": (10, -3), "D": (9, -7), "E": (8, -8)}
EX2_TASK = {
    "A": (16, 19), "B": (18, 0), "C": (-8, -25), "D": (-15, 11),
    "E": (-10, 16), "F": (20, -21), "G": (-7, 27),
}  # fmt: skip
PAPER_LIMITS = np.radians([[-150.0, 150.0], [-150.0, 150.0], [-175.0, 175.0]])
ONE_DEGREE = math.radians(1.0)
FAST = settings(max_examples=60, deadline=None)


def radial(distances: np.ndarray) -> np.ndarray:
    """Points (..., 2) on the positive x axis at the given distances."""
    return np.stack([distances, np.zeros_like(distances)], axis=-1)


# --- Example 1 (trajectory, eq 12) ----------------------------------------------------


def test_example1_links_from_the_exact_distance_range() -> None:
    span = polynomial_distance_range(EX1_CUBIC, 14.0, 8.0)
    l1, l2, l3 = synthesise_links(span.d_min, span.d_max, 8.0)
    assert (l1, l2, l3) == pytest.approx((14.8837, 13.8837, 8.0), abs=5e-5)


def test_example1_paper_links_from_distances_rounded_outward() -> None:
    span = polynomial_distance_range(EX1_CUBIC, 14.0, 8.0)
    rounded = (math.floor(span.d_min), math.ceil(span.d_max))
    assert rounded == (10, 20)
    assert synthesise_links(*rounded, 8.0) == EX1_LINKS


@pytest.mark.parametrize(
    ("links", "bands"),
    [
        (EX1_LINKS, ((0.0, 7.0), (9.0, 21.0))),
        (EX1_SWAPPED, ((0.0, 7.0),)),
        ((1.0, 1.5, 2.0), ((0.0, 0.5),)),
        ((1.0, 1.0, 3.0), ()),
        ((2.0, 2.0, 1.0), ((0.0, 3.0),)),  # l1 = l2: [0, 1] and [1, 3] merge
    ],
)
def test_full_dexterity_bands(
    links: tuple[float, float, float], bands: tuple[tuple[float, float], ...]
) -> None:
    assert full_dexterity_bands(links) == bands


def test_example1_dexterity_is_full_on_the_bands_only() -> None:
    d = np.linspace(0.0, 38.0, 38_001)
    dz = exact_orientation_dexterity(EX1_LINKS, radial(d))
    in_bands = (d <= 7.0) | ((d >= 9.0) & (d <= 21.0))
    assert np.all(dz[in_bands] == 1.0)
    assert np.all(dz[~in_bands] < 1.0)


def test_example1_dexterity_rises_from_8_to_9() -> None:
    d = np.linspace(8.0, 9.0, 1001)
    dz = exact_orientation_dexterity(EX1_LINKS, radial(d))
    assert dz[0] == pytest.approx(0.9602, abs=5e-5)
    assert dz[-1] == 1.0
    assert np.all(np.diff(dz) >= 0.0)


def test_example1_minimum_dexterity_on_0_to_21() -> None:
    d = np.linspace(0.0, 21.0, 2_100_001)
    dz = exact_orientation_dexterity(EX1_LINKS, radial(d))
    assert dz.min() == pytest.approx(0.960107, abs=5e-7)
    assert d[np.argmin(dz)] == pytest.approx(7.937, abs=5e-4)


def test_example1_case2_full_dexterity_only_on_the_central_disk() -> None:
    d = np.linspace(0.0, 38.0, 38_001)
    dz = exact_orientation_dexterity(EX1_SWAPPED, radial(d))
    assert np.all(dz[d <= 7.0] == 1.0)
    assert np.all(dz[d > 7.0] < 1.0)


def test_fully_dexterous_area_fractions_are_of_the_reachable_annulus() -> None:
    # docs/methods/planar-serial.md quotes 0.298758 (Case 1) and 0.035793 (Case 2) without a
    # denominator.
    # They are fractions of the reachable annulus (here the disk r <= 37, inner radius 0).
    fractions = []
    for links in (EX1_LINKS, EX1_SWAPPED):
        inner, outer = reach_radii(links)
        assert (inner, outer) == (0.0, 37.0)
        reachable = band_area([(inner, outer)])
        fractions.append(band_area(full_dexterity_bands(links)) / reachable)
    assert fractions == pytest.approx([0.298758, 0.035793], abs=5e-7)


def test_example1_paper_regions() -> None:
    assert region_radii(EX1_LINKS) == (8.0, 21.0, 37.0)
    d = np.array([[0.0, 8.0, 8.5, 21.0], [21.5, 37.0, 37.5, 100.0]])
    expected = np.array([[1, 1, 2, 2], [3, 3, 4, 4]], dtype=np.int8)
    np.testing.assert_array_equal(paper_regions(EX1_LINKS, d), expected)
    # Case 2: region 2 (eq 13) is empty, l3 = 14 > l1 + l2 - l3 = 9
    np.testing.assert_array_equal(paper_regions(EX1_SWAPPED, [9.5, 14.5]), [1, 3])


@pytest.mark.parametrize(
    ("name", "expected"), [("A", 1.0), ("B", 0.8807), ("C", 0.7436), ("D", 0.7697), ("E", 0.7273)]
)
def test_example1_case3_task_points(name: str, expected: float) -> None:
    dz = limited_orientation_dexterity(
        EX1_LINKS, EX1_TASK[name], PAPER_LIMITS, ONE_DEGREE, refine_tol=1e-10
    )
    assert dz == pytest.approx(expected, abs=6e-5)


def test_theta2_limit_raises_the_wrist_inner_radius() -> None:
    # docs/methods/planar-serial.md: |th2| <= 150 deg moves the wrist's inner radius from |l1 - l2|
    # = 1 to
    # 7.5677, so with only th2 limited d_z is the closed form with that inner radius.
    l1, l2, l3 = EX1_LINKS
    inner = math.sqrt(l1 * l1 + l2 * l2 + 2 * l1 * l2 * math.cos(math.radians(150)))
    assert inner == pytest.approx(7.5677, abs=5e-5)
    d = np.array([2.0, 8.0, 12.0, 15.5, 20.0, 30.0, 36.0])
    c_lo = np.clip((d * d + l3 * l3 - (l1 + l2) ** 2) / (2 * d * l3), -1, 1)
    c_hi = np.clip((d * d + l3 * l3 - inner**2) / (2 * d * l3), -1, 1)
    expected = (np.arccos(c_lo) - np.arccos(c_hi)) / np.pi
    only_th2 = np.array([[-np.pi, np.pi], PAPER_LIMITS[1], [-np.pi, np.pi]])
    got = limited_orientation_dexterity(
        EX1_LINKS, radial(d), only_th2, ONE_DEGREE, refine_tol=1e-11
    )
    np.testing.assert_allclose(got, expected, atol=1e-9)


# --- Example 2 (independent task points) ----------------------------------------------


def test_example2_synthesis() -> None:
    span = points_distance_range(list(EX2_TASK.values()))
    assert (span.d_min, span.at_min) == (18.0, EX2_TASK["B"])
    assert (span.d_max, span.at_max) == (29.0, EX2_TASK["F"])
    assert synthesise_links(span.d_min, span.d_max, 15.0) == (23.0, 22.0, 15.0)


def test_example2_case1_all_task_points_fully_dexterous() -> None:
    dz = exact_orientation_dexterity((23.0, 22.0, 15.0), list(EX2_TASK.values()))
    np.testing.assert_array_equal(dz, 1.0)


def test_example2_case2_no_task_point_fully_dexterous() -> None:
    dz = exact_orientation_dexterity((23.0, 15.0, 22.0), list(EX2_TASK.values()))
    assert np.all(dz < 1.0)


def test_example2_case3_task_points() -> None:
    expected = {"F": 1.0, "G": 0.9805, "A": 0.8955, "C": 0.8630, "E": 0.7874, "D": 0.7840,
                "B": 0.7766}  # fmt: skip
    points = np.array([EX2_TASK[name] for name in expected], dtype=float)
    dz = limited_orientation_dexterity(
        (23.0, 22.0, 15.0), points, PAPER_LIMITS, ONE_DEGREE, refine_tol=1e-10
    )
    np.testing.assert_allclose(dz, list(expected.values()), atol=6e-5)
    unrefined = limited_orientation_dexterity((23.0, 22.0, 15.0), points, PAPER_LIMITS, ONE_DEGREE)
    reference = [sampled_orientation_dexterity((23, 22, 15), p, ONE_DEGREE, PAPER_LIMITS.tolist())
                 for p in points]  # fmt: skip
    np.testing.assert_array_equal(unrefined, reference)


def test_d_max_exceeds_l1_in_both_examples() -> None:
    # docs/methods/planar-serial.md errata: the paper's "at d = d_max, l1 > l2 > d > l3" is false in
    # both
    ex1 = polynomial_distance_range(EX1_CUBIC, 14.0, 8.0)
    ex2 = points_distance_range(list(EX2_TASK.values()))
    for d_max, l3 in ((ex1.d_max, 8.0), (math.ceil(ex1.d_max), 8.0), (ex2.d_max, 15.0)):
        l1, _, _ = synthesise_links(0.0, d_max, l3)
        assert d_max > l1


# --- closed forms, shapes, chunking ---------------------------------------------------


def test_forward_kinematics_closed_form_and_batching() -> None:
    q = np.array([[[0.0, 0.0, 0.0], [math.pi / 2, 0.0, 0.0]], [[0.0, math.pi, 0.0], [0, 0, -1]]])
    before = q.copy()
    pose = forward_kinematics((1.0, 1.0, 1.0), q)
    assert pose.shape == (2, 2, 3)
    np.testing.assert_array_equal(q, before)
    expected: list[list[list[float]]] = [
        [[3, 0, 0], [0, 3, math.pi / 2]],
        [[-1, 0, math.pi], [2 + math.cos(1), -math.sin(1), -1]],
    ]
    np.testing.assert_allclose(pose, expected, atol=1e-12)


def test_orientation_samples() -> None:
    for step, count in ((ONE_DEGREE, 360), (0.7, 9), (10.0, 1)):
        n, effective = orientation_samples(step)
        assert n == count
        assert effective == pytest.approx(2 * math.pi / count, rel=1e-15)


def test_reach_radii() -> None:
    assert reach_radii(EX1_LINKS) == (0.0, 37.0)
    assert reach_radii((1.0, 1.0, 3.0)) == (1.0, 5.0)


def test_dexterity_at_the_base() -> None:
    assert exact_orientation_dexterity((1.0, 1.5, 2.0), (0.0, 0.0)) == 1.0
    assert exact_orientation_dexterity((1.0, 1.0, 3.0), (0.0, 0.0)) == 0.0


def test_outputs_are_arrays_of_the_batch_shape() -> None:
    single = exact_orientation_dexterity(EX1_LINKS, (3.0, 4.0))
    assert isinstance(single, np.ndarray) and single.shape == ()
    limited = limited_orientation_dexterity(EX1_LINKS, (3.0, 4.0), PAPER_LIMITS, 0.1)
    assert isinstance(limited, np.ndarray) and limited.shape == ()
    grid = np.zeros((2, 3, 2))
    assert exact_orientation_dexterity(EX1_LINKS, grid).shape == (2, 3)
    assert limited_orientation_dexterity(EX1_LINKS, grid, PAPER_LIMITS, 0.1).shape == (2, 3)
    assert limited_orientation_dexterity(EX1_LINKS, np.zeros((0, 2)), PAPER_LIMITS, 0.1).shape == (
        0,
    )


@pytest.mark.parametrize("refine_tol", [None, 1e-8])
def test_chunking_changes_nothing_and_reports_progress(refine_tol: float | None) -> None:
    rng = np.random.default_rng(7)
    points = rng.uniform(-40.0, 40.0, size=(500, 2))
    before = points.copy()
    whole = limited_orientation_dexterity(
        EX1_LINKS, points, PAPER_LIMITS, ONE_DEGREE, refine_tol=refine_tol
    )
    progress: list[tuple[int, int]] = []
    chunked = limited_orientation_dexterity(
        EX1_LINKS, points, PAPER_LIMITS, ONE_DEGREE, refine_tol=refine_tol,
        max_chunk_elements=360 * 64, on_chunk=lambda done, total: progress.append((done, total)),
    )  # fmt: skip
    np.testing.assert_array_equal(chunked, whole)
    np.testing.assert_array_equal(points, before)
    assert progress == [(min(500, 64 * k), 500) for k in range(1, 9)]


def test_unlimited_joints_refined_match_the_closed_form() -> None:
    full = np.array([[-np.pi, np.pi]] * 3)
    d = np.linspace(0.5, 36.5, 73)
    refined = limited_orientation_dexterity(
        EX1_LINKS, radial(d), full, ONE_DEGREE, refine_tol=1e-12
    )
    np.testing.assert_allclose(
        refined, exact_orientation_dexterity(EX1_LINKS, radial(d)), atol=1e-10
    )


# --- bad parameters -------------------------------------------------------------------


BAD_LIMITS = [[-4.0, 0.0], [0.0, 1.0], [0.0, 1.0]]
REVERSED_LIMITS = [[1.0, 0.0], [0.0, 1.0], [0.0, 1.0]]
BAD_PARAMETERS = [
    (exact_orientation_dexterity, "links", ((1.0, 2.0), (1.0, 1.0)), {}),
    (exact_orientation_dexterity, "links", ((1.0, -2.0, 3.0), (1.0, 1.0)), {}),
    (exact_orientation_dexterity, "links", ((1.0, np.nan, 1.0), (1.0, 1.0)), {}),
    (exact_orientation_dexterity, "points", (EX1_LINKS, [1.0, 2.0, 3.0]), {}),
    (forward_kinematics, "joint_angles", (EX1_LINKS, [0.0, 1.0]), {}),
    (limited_orientation_dexterity, "joint_limits", (EX1_LINKS, (1, 1), BAD_LIMITS, 0.1), {}),
    (limited_orientation_dexterity, "joint_limits", (EX1_LINKS, (1, 1), REVERSED_LIMITS, 0.1), {}),
    (limited_orientation_dexterity, "step", (EX1_LINKS, (1, 1), PAPER_LIMITS, 0.0), {}),
    (limited_orientation_dexterity, "refine_tol", (EX1_LINKS, (1, 1), PAPER_LIMITS, 0.1),
     {"refine_tol": 0.0}),
    (limited_orientation_dexterity, "max_chunk_elements", (EX1_LINKS, (1, 1), PAPER_LIMITS, 0.1),
     {"max_chunk_elements": 10}),
    (orientation_samples, "step", (-1.0,), {}),
    (paper_regions, "distances", (EX1_LINKS, [-1.0]), {}),
    (reach_radii, "links", ((0.0, 1.0, 1.0),), {}),
    (synthesise_links, "l3", (10.0, 20.0, 0.0), {}),
    (synthesise_links, "d_min", (-1.0, 20.0, 8.0), {}),
    (synthesise_links, "d_max", (20.0, 10.0, 8.0), {}),
    (band_area, "bands", ([(3.0, 1.0)],), {}),
    (sampled_orientation_dexterity, "links", ((1, 1), (1, 1), 0.1), {}),
    (sampled_orientation_dexterity, "step", ((1, 1, 1), (1, 1), -0.1), {}),
    (sampled_orientation_dexterity, "joint_limits", ((1, 1, 1), (1, 1), 0.1, [[0, 1]]), {}),
]  # fmt: skip


@pytest.mark.parametrize(("function", "parameter", "args", "kwargs"), BAD_PARAMETERS)
def test_bad_parameters_name_the_parameter(function, parameter, args, kwargs) -> None:
    message = rf"The '{parameter}' parameter of {function.__name__} must be .*\. Got .* instead\."
    with pytest.raises(ValueError, match=message):
        function(*args, **kwargs)


# --- properties -------------------------------------------------------------------------

lengths = st.floats(0.2, 5.0)
designs = st.tuples(lengths, lengths, lengths)
unit = st.floats(0.0, 1.0)
angles = st.floats(-math.pi, math.pi)


def point_in_reach(
    links: tuple[float, float, float], fraction: float, angle: float
) -> tuple[float, float]:
    radius = 1.1 * sum(links) * fraction
    return radius * math.cos(angle), radius * math.sin(angle)


@st.composite
def joint_limits(draw: st.DrawFn) -> list[list[float]]:
    limits = []
    for _ in range(3):
        a, b = sorted((draw(angles), draw(angles)))
        limits.append([a, b])
    return limits


@FAST
@given(designs, unit, angles, st.floats(0.02, 0.3))
def test_exact_matches_per_point_sampling(links, fraction, angle, step) -> None:
    point = point_in_reach(links, fraction, angle)
    n, _ = orientation_samples(step)
    exact = float(exact_orientation_dexterity(links, point))
    sampled = sampled_orientation_dexterity(links, point, step)
    assert abs(exact - sampled) <= 4.0 / n + 1e-12


def count_on_limits(links, point, step, limits) -> tuple[int, int]:
    n, _ = orientation_samples(step)
    fast = limited_orientation_dexterity(links, point, limits, step) * n
    slow = sampled_orientation_dexterity(links, point, step, limits) * n
    return round(float(fast)), round(slow)


@FAST
@given(designs, unit, angles, st.floats(0.02, 0.3), joint_limits())
def test_limited_matches_per_point_sampling(links, fraction, angle, step, limits) -> None:
    point = point_in_reach(links, fraction, angle)
    fast, slow = count_on_limits(links, point, step, limits)
    if fast != slow:  # only a sample sitting on a limit may differ: nudging breaks the tie
        assert abs(fast - slow) <= 1
        for nudge in (1e-9, -1e-9):
            nudged = np.clip(np.asarray(limits) + np.array([-nudge, nudge]), -np.pi, np.pi)
            nudged[:, 1] = np.maximum(nudged[:, 0], nudged[:, 1])
            a, b = count_on_limits(links, point, step, nudged.tolist())
            assert a == b


def transitions(links, point, step, limits) -> int:
    """Feasibility changes between cyclically consecutive samples phi_k."""
    n, h = orientation_samples(step)
    pattern = [feasible_at(links, point, k * h, limits) for k in range(n)]
    return sum(pattern[k] != pattern[(k + 1) % n] for k in range(n))


def feasible_at(links, point, phi, limits) -> bool:
    """One orientation, by the textbook IK (test oracle for the run count only)."""
    l1, l2, l3 = links
    wx, wy = point[0] - l3 * math.cos(phi), point[1] - l3 * math.sin(phi)
    c2 = (wx * wx + wy * wy - l1 * l1 - l2 * l2) / (2 * l1 * l2)
    if not -1 <= c2 <= 1:
        return False
    for th2 in (math.acos(c2), -math.acos(c2)):
        th1 = math.atan2(wy, wx) - math.atan2(l2 * math.sin(th2), l1 + l2 * math.cos(th2))
        wrapped = [math.pi - (math.pi - t) % (2 * math.pi) for t in (th1, th2, phi - th1 - th2)]
        if all(lo <= t <= hi for t, (lo, hi) in zip(wrapped, limits, strict=True)):
            return True
    return False


@FAST
@given(designs, unit, angles, st.floats(0.02, 0.3), joint_limits())
def test_refined_within_one_step_of_each_transition(links, fraction, angle, step, limits) -> None:
    point = point_in_reach(links, fraction, angle)
    n, _ = orientation_samples(step)
    coarse = float(limited_orientation_dexterity(links, point, limits, step))
    fine = float(limited_orientation_dexterity(links, point, limits, step, refine_tol=1e-9))
    # each feasible run's two ends move by less than one step in total
    runs = transitions(links, point, step, limits) / 2
    assert abs(fine - coarse) <= max(runs, 1) / n + 1e-12


@FAST
@given(designs, st.tuples(angles, angles, angles))
def test_forward_kinematics_lands_where_some_orientation_is_reachable(links, q) -> None:
    x, y, _ = forward_kinematics(links, q)
    inner, outer = reach_radii(links)
    d = math.hypot(x, y)
    assert inner - 1e-9 <= d <= outer + 1e-9
    assume(inner + 1e-6 < d < outer - 1e-6)  # the boundary circles have measure zero
    assert exact_orientation_dexterity(links, (x, y)) > 0.0


@FAST
@given(designs, st.floats(0.0, 1.05))
def test_bands_are_where_exact_dexterity_is_one(links, fraction) -> None:
    d = fraction * sum(links)
    bands = full_dexterity_bands(links)
    assume(all(abs(d - edge) > 1e-9 for band in bands for edge in band))
    inside = any(lo <= d <= hi for lo, hi in bands)
    assert (exact_orientation_dexterity(links, (0.0, d)) == 1.0) == inside
