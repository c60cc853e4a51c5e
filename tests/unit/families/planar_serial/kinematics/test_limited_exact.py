"""Exact d_z under joint limits (closed-form events): the paper's Case 3 numbers, the
degenerate cases, and properties against the independent sampler, the bisection
refinement and the closed form for unlimited joints."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from tests.unit.families.planar_serial.kinematics.strategies import angles, designs, limits
from worker.families.planar_serial.kinematics import (
    exact_orientation_dexterity,
    limited_orientation_dexterity,
    orientation_samples,
    sampled_orientation_dexterity,
)
from worker.families.planar_serial.kinematics.joint_limits import (
    _linear_weights,
    _pair_quantities,
    _point_features,
)
from worker.families.planar_serial.kinematics.limited_exact import (
    event_count,
    exact_limited_orientation_dexterity,
    feasible_arcs,
    orientation_events,
)

PAPER_LIMITS = np.radians([[-150.0, 150.0], [-150.0, 150.0], [-175.0, 175.0]])
FREE = np.array([[-math.pi, math.pi]] * 3)
EX1_LINKS = (15.0, 14.0, 8.0)
EX2_LINKS = (23.0, 22.0, 15.0)
PROPERTY = settings(
    max_examples=300, deadline=None, derandomize=True,
    suppress_health_check=[HealthCheck.filter_too_much],
)  # fmt: skip


@st.composite
def points(draw: st.DrawFn, links: tuple[float, float, float]) -> tuple[float, float]:
    radius = 1.05 * sum(links) * draw(st.floats(0.0, 1.0))
    angle = draw(angles)
    return radius * math.cos(angle), radius * math.sin(angle)


def exact(links, point, limits_rad) -> float:
    return float(exact_limited_orientation_dexterity(links, point, limits_rad))


# -- the paper's numbers (docs/methods/planar-serial.md, Case 3) ------------------------


@pytest.mark.parametrize(
    ("point", "expected"),
    [((14, 14), 1.0), ((12, 8), 0.8807), ((10, -3), 0.7436), ((9, -7), 0.7697),
     ((8, -8), 0.7273)],
)  # fmt: skip
def test_example_1_case_3(point: tuple[float, float], expected: float) -> None:
    assert exact(EX1_LINKS, point, PAPER_LIMITS) == pytest.approx(expected, abs=6e-5)


def test_example_2_case_3() -> None:
    task = [(20, -21), (-7, 27), (16, 19), (-8, -25), (-10, 16), (-15, 11), (18, 0)]
    expected = [1.0, 0.9805, 0.8955, 0.8630, 0.7874, 0.7840, 0.7766]
    got = exact_limited_orientation_dexterity(EX2_LINKS, task, PAPER_LIMITS)
    np.testing.assert_allclose(got, expected, atol=6e-5)


def test_example_1_task_points_agree_with_the_bisection_to_rounding() -> None:
    task = [(14, 14), (12, 8), (10, -3), (9, -7), (8, -8)]
    events = exact_limited_orientation_dexterity(EX1_LINKS, task, PAPER_LIMITS)
    refined = limited_orientation_dexterity(
        EX1_LINKS, task, PAPER_LIMITS, math.radians(1.0), refine_tol=1e-12
    )
    np.testing.assert_allclose(events, refined, atol=1e-11)


def test_example_1_point_e_has_two_arcs() -> None:
    arcs = feasible_arcs(EX1_LINKS, (8, -8), PAPER_LIMITS)
    assert len(arcs) == 2
    total = sum(b - a for a, b in arcs) / (2 * math.pi)
    assert total == pytest.approx(exact(EX1_LINKS, (8, -8), PAPER_LIMITS), abs=1e-14)
    assert feasible_arcs(EX1_LINKS, (14, 14), PAPER_LIMITS) == ((0.0, 2 * math.pi),)


# -- a feasible arc far narrower than any sampling step --------------------------------


def test_an_arc_narrower_than_a_hundredth_of_a_degree_is_found() -> None:
    # Only th2 is limited, to [60, 60.005] deg: feasible iff the wrist distance |w| lies
    # in [R(60.005), R(60)], R(t)^2 = l1^2 + l2^2 + 2 l1 l2 cos t, i.e. p . u(phi) in
    # [k(R(60)), k(R(60.005))] with k(R) = (|p|^2 + l3^2 - R^2) / (2 l3): two arcs,
    # symmetric about the direction of p, in closed form.
    links, point = (1.0, 1.0, 1.0), (1.3, 0.4)
    lo, hi = math.radians(60.0), math.radians(60.005)
    narrow = np.array([[-math.pi, math.pi], [lo, hi], [-math.pi, math.pi]])
    d = math.hypot(*point)

    def angle(t: float) -> float:
        radius2 = 2.0 + 2.0 * math.cos(t)
        return math.acos((d * d + 1.0 - radius2) / (2.0 * d))

    expected = 2.0 * (angle(lo) - angle(hi)) / (2.0 * math.pi)
    arcs = feasible_arcs(links, point, narrow)
    assert len(arcs) == 2
    assert all(0 < math.degrees(b - a) < 0.01 for a, b in arcs)
    assert exact(links, point, narrow) == pytest.approx(expected, rel=1e-9)
    # the sampler, even refined, sees nothing: no sample falls inside either arc
    one_degree = math.radians(1.0)
    assert sampled_orientation_dexterity(links, point, one_degree, narrow.tolist()) == 0.0
    refined = limited_orientation_dexterity(links, point, narrow, one_degree, refine_tol=1e-12)
    assert float(refined) == 0.0


# -- degenerate cases ---------------------------------------------------------------


def test_a_point_at_the_base_has_only_th1_events() -> None:
    # at the base |w| = l3 for every phi: no annulus, th2 or th3 event; th1 turns with phi
    events = orientation_events(EX1_LINKS, PAPER_LIMITS, np.zeros(1), np.zeros(1))
    finite = np.isfinite(events[0])
    assert finite[8:12].all() and not finite[:8].any() and not finite[12:].any()
    got = exact(EX1_LINKS, (0.0, 0.0), PAPER_LIMITS)
    refined = limited_orientation_dexterity(
        EX1_LINKS, (0.0, 0.0), PAPER_LIMITS, math.radians(0.5), refine_tol=1e-12
    )
    assert got == pytest.approx(float(refined), abs=1e-10)


@pytest.mark.parametrize(("th2_limit", "expected"), [(150.0, 1.0), (90.0, 0.0)])
def test_a_point_without_events_is_decided_by_one_orientation(
    th2_limit: float, expected: float
) -> None:
    # links (1, 1, 1) at the base: |w| = 1, so th2 = +-120 deg for every phi
    only_th2 = np.radians([[-180, 180], [-th2_limit, th2_limit], [-180, 180]])
    events = orientation_events((1.0, 1.0, 1.0), only_th2, np.zeros(1), np.zeros(1))
    assert np.isnan(events).all()
    assert exact((1.0, 1.0, 1.0), (0.0, 0.0), only_th2) == expected


def test_equal_links_with_the_wrist_through_the_base() -> None:
    # l1 = l2 and |p| = l3: at phi = arg p the wrist is at the base and th1 is free
    links, point = (1.0, 1.0, 0.5), (0.5 * math.cos(0.3), 0.5 * math.sin(0.3))
    limited = np.radians([[-60, 100], [-170, 170], [-120, 150]])
    got = exact(links, point, limited)
    refined = limited_orientation_dexterity(
        links, point, limited, math.radians(0.25), refine_tol=1e-12
    )
    assert got == pytest.approx(float(refined), abs=1e-9)
    assert 0.0 < got < 1.0


def test_tangent_circles() -> None:
    # |p| = l1 + l2 - l3: the wrist circle touches the outer edge of the annulus at one phi
    links = EX1_LINKS
    on_edge = (21.0, 0.0)
    assert exact(links, on_edge, FREE) == pytest.approx(1.0, abs=1e-12)
    got = exact(links, on_edge, PAPER_LIMITS)
    refined = limited_orientation_dexterity(
        links, on_edge, PAPER_LIMITS, math.radians(0.5), refine_tol=1e-12
    )
    assert got == pytest.approx(float(refined), abs=1e-9)


def test_outside_the_reach_is_zero_without_work() -> None:
    far = exact_limited_orientation_dexterity(EX1_LINKS, [(37.5, 0.0), (0, -40)], PAPER_LIMITS)
    np.testing.assert_array_equal(far, [0.0, 0.0])


# -- batching, chunking, counting, bad input ------------------------------------------


def test_batch_shape_and_chunking_change_nothing() -> None:
    rng = np.random.default_rng(7)
    grid = rng.uniform(-38, 38, (4, 5, 2))
    calls: list[tuple[int, int]] = []
    whole = exact_limited_orientation_dexterity(EX1_LINKS, grid, PAPER_LIMITS)
    chunked = exact_limited_orientation_dexterity(
        EX1_LINKS, grid, PAPER_LIMITS, chunk_points=6, on_chunk=lambda *a: calls.append(a)
    )
    assert whole.shape == (4, 5)
    np.testing.assert_array_equal(whole, chunked)
    assert calls == [(6, 20), (12, 20), (18, 20), (20, 20)]


@PROPERTY
@given(
    st.lists(designs, min_size=1, max_size=4),
    st.lists(st.tuples(st.floats(-8, 8), st.floats(-8, 8)), min_size=1, max_size=5),
    limits(),
)
def test_designs_at_once_equal_one_at_a_time(
    many: list[tuple[float, float, float]], where: list[tuple[float, float]], lims: np.ndarray
) -> None:
    # the design search evaluates a population in one call: links (s, 1, 3) against
    # points (n, 2) must give what each design gives alone (the same arithmetic)
    rows = np.asarray(many)[:, np.newaxis, :]
    together = exact_limited_orientation_dexterity(rows, where, lims)
    alone = np.stack([exact_limited_orientation_dexterity(one, where, lims) for one in many])
    assert together.shape == (len(many), len(where))
    np.testing.assert_allclose(together, alone, rtol=0.0, atol=1e-12)
    unlimited = exact_orientation_dexterity(rows, where)
    np.testing.assert_allclose(
        unlimited, np.stack([exact_orientation_dexterity(one, where) for one in many]),
        rtol=0.0, atol=1e-12,
    )  # fmt: skip


def test_designs_broadcast_and_chunk_like_points() -> None:
    rng = np.random.default_rng(3)
    links = rng.uniform(2.0, 15.0, (3, 1, 3))
    grid = rng.uniform(-30, 30, (4, 2))
    whole = exact_limited_orientation_dexterity(links, grid, PAPER_LIMITS)
    chunked = exact_limited_orientation_dexterity(links, grid, PAPER_LIMITS, chunk_points=5)
    assert whole.shape == (3, 4)
    np.testing.assert_array_equal(whole, chunked)
    # one design per point: the diagonal of the all-pairs table
    paired = exact_limited_orientation_dexterity(links[:, 0, :], grid[:3], PAPER_LIMITS)
    np.testing.assert_array_equal(paired, np.diagonal(whole[:, :3]))


def test_event_count() -> None:
    assert event_count(PAPER_LIMITS) == 16
    assert event_count(FREE) == 4
    # -180 and 180 are one angle only when lo == hi; a limit pair at the same angle: one
    assert event_count(np.array([[0.5, 0.5], [-math.pi, math.pi], [-math.pi, 0.0]])) == 10


@pytest.mark.parametrize(
    ("kwargs", "parameter"),
    [
        ({"links": (1, -1, 1)}, "links"),
        ({"links": [[1, 1, 1], [1, 0, 1]]}, "links"),
        ({"links": [[1, 1]]}, "links"),
        ({"points": [[np.nan, 0]]}, "points"),
        ({"joint_limits": [[1, 0]] * 3}, "joint_limits"),
        ({"chunk_points": 0}, "chunk_points"),
    ],
)
def test_bad_parameters_name_the_parameter(kwargs: dict, parameter: str) -> None:
    args = {"links": EX1_LINKS, "points": [[1.0, 2.0]], "joint_limits": PAPER_LIMITS}
    args.update(kwargs)
    chunk = {"chunk_points": args.pop("chunk_points")} if "chunk_points" in args else {}
    with pytest.raises(ValueError, match=f"'{parameter}'"):
        exact_limited_orientation_dexterity(
            args["links"], args["points"], args["joint_limits"], **chunk
        )


# -- properties ----------------------------------------------------------------------


@PROPERTY
@given(st.data(), designs)
def test_free_joints_give_the_closed_form(data: st.DataObject, links) -> None:
    point = data.draw(points(links))
    assert exact(links, point, FREE) == pytest.approx(
        float(exact_orientation_dexterity(links, point)), abs=1e-12
    )


@PROPERTY
@given(st.data(), designs, limits(), st.floats(0.02, 0.2))
def test_exact_within_one_sample_per_arc_of_the_reference_sampler(
    data: st.DataObject, links, limits_rad, step
) -> None:
    # the sampler counts each feasible arc [a, b] to within one sample
    point = data.draw(points(links))
    n, _ = orientation_samples(step)
    sampled = sampled_orientation_dexterity(links, point, step, limits_rad.tolist())
    arcs = feasible_arcs(links, point, limits_rad)
    assert abs(exact(links, point, limits_rad) - sampled) <= max(len(arcs), 1) / n + 1e-9


@PROPERTY
@given(st.data(), designs, limits())
def test_exact_equals_the_bisection_when_no_feature_is_narrower_than_a_step(
    data: st.DataObject, links, limits_rad
) -> None:
    point = data.draw(points(links))
    step = math.radians(0.5)
    arcs = feasible_arcs(links, point, limits_rad)
    widths = [b - a for a, b in arcs]
    gaps = [(arcs[(i + 1) % len(arcs)][0] - b) % (2 * math.pi) for i, (_, b) in enumerate(arcs)]
    assume(all(w > 2.5 * step for w in widths + (gaps if len(arcs) > 1 else [])))
    refined = limited_orientation_dexterity(links, point, limits_rad, step, refine_tol=1e-12)
    assert exact(links, point, limits_rad) == pytest.approx(float(refined), abs=1e-9)


@PROPERTY
@given(designs, limits(), st.lists(st.tuples(angles, angles, angles), min_size=1, max_size=5))
def test_pair_quantities_match_the_sampler_weights(links, limits_rad, rows) -> None:
    px, py, phi = np.array(rows).T
    direct = _pair_quantities(links, limits_rad, px, py, phi)
    weights = _linear_weights(links, limits_rad, np.cos(phi), np.sin(phi))
    via_weights = np.einsum("jkc,ck->jk", weights, _point_features(px, py))
    np.testing.assert_allclose(direct, via_weights, rtol=1e-9, atol=1e-9)
