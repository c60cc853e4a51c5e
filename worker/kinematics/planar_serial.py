"""Three-link planar serial arms (RRR): kinematics, orientation dexterity and synthesis.

Patel & Sobh, "Optimal Design of Three-Link Planar Manipulators Using Grashof's
Criterion" (2012), restated in METHODS.md §1, which wins where the two disagree.

Conventions: links ``(l1, l2, l3)`` run from the base (at the origin) to the
end-effector, in any one length unit; angles are in radians; the end-effector
orientation is ``phi = th1 + th2 + th3``. The dexterity index about z is
``d_z(p) = |{phi in [0, 2 pi) reachable at p}| / (2 pi)`` (eqs 2-5; planar, so
``d_x = d_y = 0`` and ``D = d_z / 3``). Functions are batched on the leading axes of
their point/angle argument and return an array for it, never a scalar.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "band_area",
    "exact_orientation_dexterity",
    "forward_kinematics",
    "full_dexterity_bands",
    "limited_orientation_dexterity",
    "orientation_samples",
    "paper_regions",
    "reach_radii",
    "region_radii",
    "sampled_orientation_dexterity",
    "synthesise_links",
]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]
Links = tuple[float, float, float]

#: Elements (points x orientations) evaluated at once inside a chunk: small enough that
#: the kernel's ~110 bytes per element stay in cache, which runs 2-3x faster than
#: streaming multi-megabyte temporaries through memory.
_CACHE_BLOCK_ELEMENTS = 2**14


# --- input normalisation (once, at every public entry) --------------------------------


def _bad(parameter: str, function: str, requirement: str, got: Any) -> ValueError:
    shown = repr(got)
    if len(shown) > 80:  # long arrays: name the shape, not the values
        try:
            shown = f"an array of shape {np.shape(got)}"
        except ValueError:
            shown = shown[:77] + "..."
    return ValueError(
        f"The {parameter!r} parameter of {function} must be {requirement}. Got {shown} instead."
    )


def _checked(
    value: object,
    parameter: str,
    function: str,
    requirement: str,
    valid: Callable[[FloatArray], bool],
) -> FloatArray:
    """``value`` as a float64 array (a copy only if needed), or a ValueError naming it."""
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise _bad(parameter, function, requirement, value) from None
    if not (np.all(np.isfinite(arr)) and valid(arr)):
        raise _bad(parameter, function, requirement, value)
    return arr


def _links(links: ArrayLike, function: str) -> Links:
    arr = _checked(
        links,
        "links",
        function,
        "three finite positive lengths (l1, l2, l3)",
        lambda a: a.shape == (3,) and bool(np.all(a > 0)),
    )
    return float(arr[0]), float(arr[1]), float(arr[2])


def _points(points: ArrayLike, function: str) -> FloatArray:
    return _checked(
        points,
        "points",
        function,
        "finite (x, y) coordinates of shape (..., 2)",
        lambda a: a.ndim >= 1 and a.shape[-1] == 2,
    )


def _sample_count(step: float, function: str) -> int:
    if not (isinstance(step, numbers.Real) and step > 0 and math.isfinite(2.0 * math.pi / step)):
        raise _bad("step", function, "a finite positive angle in radians", step)
    return max(1, round(2.0 * math.pi / float(step)))


# --- closed forms (unlimited joints) --------------------------------------------------


def forward_kinematics(links: ArrayLike, joint_angles: ArrayLike) -> FloatArray:
    """End-effector pose from joint angles, eqs (8)-(9).

    links: (3,) lengths; joint_angles: (..., 3) radians ``(th1, th2, th3)``.
    Returns (..., 3): ``[x, y, phi]`` with ``phi = th1 + th2 + th3`` (not wrapped).
    """
    l1, l2, l3 = _links(links, "forward_kinematics")
    q = _checked(
        joint_angles,
        "joint_angles",
        "forward_kinematics",
        "finite angles (rad) of shape (..., 3)",
        lambda a: a.ndim >= 1 and a.shape[-1] == 3,
    )
    absolute = np.cumsum(q, axis=-1)
    lengths = np.array([l1, l2, l3])
    x = np.sum(lengths * np.cos(absolute), axis=-1)
    y = np.sum(lengths * np.sin(absolute), axis=-1)
    return np.stack([x, y, absolute[..., 2]], axis=-1)


def reach_radii(links: ArrayLike) -> tuple[float, float]:
    """(inner, outer) radius of the reachable annulus with unlimited joints.

    outer = l1 + l2 + l3; inner = max(0, 2 max(l) - sum(l)).
    """
    lengths = _links(links, "reach_radii")
    total = sum(lengths)
    return max(0.0, 2.0 * max(lengths) - total), total


def exact_orientation_dexterity(links: ArrayLike, points: ArrayLike) -> FloatArray:
    """Closed-form d_z with unlimited joints (METHODS.md §1; eqs 3 and 5).

    points: (..., 2) in the links' unit. Returns d_z (...) in [0, 1]:
    ``d_z = [acos(clip(c_lo)) - acos(clip(c_hi))] / pi`` with
    ``c_lo = (d^2 + l3^2 - (l1+l2)^2) / (2 d l3)``, ``c_hi = (d^2 + l3^2 - (l1-l2)^2) / (2 d l3)``,
    ``d = |p|``; at d = 0, d_z = 1 if |l1 - l2| <= l3 <= l1 + l2, else 0.
    """
    l1, l2, l3 = _links(links, "exact_orientation_dexterity")
    p = _points(points, "exact_orientation_dexterity")
    # Scale-free form: lengths over the full reach, and clamping d at twice the reach
    # (d_z = 0 there anyway) keep every intermediate O(1).
    scale = l1 + l2 + l3
    a, b, c = l1 / scale, l2 / scale, l3 / scale
    d = np.minimum(np.hypot(p[..., 0], p[..., 1]) / scale, 2.0)
    at_origin = 1.0 if abs(l1 - l2) <= l3 <= l1 + l2 else 0.0
    safe_d = np.where(d > 0.0, d, 1.0)
    with np.errstate(divide="ignore", over="ignore"):
        c_lo = (d * d + c * c - (a + b) ** 2) / (2.0 * safe_d * c)
        c_hi = (d * d + c * c - (a - b) ** 2) / (2.0 * safe_d * c)
    arcs = np.arccos(np.clip(c_lo, -1.0, 1.0)) - np.arccos(np.clip(c_hi, -1.0, 1.0))
    dz = np.clip(arcs / np.pi, 0.0, 1.0)
    return np.asarray(np.where(d > 0.0, dz, at_origin), dtype=np.float64)


def full_dexterity_bands(links: ArrayLike) -> tuple[tuple[float, float], ...]:
    """Closed radius intervals where d_z == 1 with unlimited joints (METHODS.md §1).

    ``[0, min(l3 - |l1-l2|, l1+l2-l3)]`` ∪ ``[l3 + |l1-l2|, l1+l2-l3]``; empty pieces
    dropped, sorted, touching or overlapping pieces merged. This corrects the paper's
    Region 2 (eq 13), e.g. (15, 14, 8) -> ((0, 7), (9, 21)).
    """
    l1, l2, l3 = _links(links, "full_dexterity_bands")
    gap = abs(l1 - l2)
    pieces = [(0.0, min(l3 - gap, l1 + l2 - l3)), (l3 + gap, l1 + l2 - l3)]
    bands: list[tuple[float, float]] = []
    for lo, hi in sorted(piece for piece in pieces if piece[0] <= piece[1]):
        if bands and lo <= bands[-1][1]:
            bands[-1] = (bands[-1][0], max(bands[-1][1], hi))
        else:
            bands.append((lo, hi))
    return tuple(bands)


def band_area(bands: Sequence[tuple[float, float]]) -> float:
    """Area of a union of disjoint annuli: sum of pi (b^2 - a^2) over the bands (a, b)."""
    arr = _checked(
        list(bands),
        "bands",
        "band_area",
        "radius pairs (a, b) with 0 <= a <= b",
        lambda a: (
            a.size == 0
            or (
                a.ndim == 2
                and a.shape[1] == 2
                and bool(np.all((a[:, 0] >= 0) & (a[:, 0] <= a[:, 1])))
            )
        ),
    ).reshape(-1, 2)
    return float(np.pi * np.sum(arr[:, 1] ** 2 - arr[:, 0] ** 2))


def region_radii(links: ArrayLike) -> tuple[float, float, float]:
    """The paper's region boundaries (§5 Example 1): (l3, l1 + l2 - l3, l1 + l2 + l3)."""
    l1, l2, l3 = _links(links, "region_radii")
    return l3, l1 + l2 - l3, l1 + l2 + l3


def paper_regions(links: ArrayLike, distances: ArrayLike) -> NDArray[np.int8]:
    """The paper's regions 1-4 (§5 Example 1, eq 13) for distances (...) from the base.

    1: 0 <= d <= l3; 2: l3 < d <= l1+l2-l3; 3: l1+l2-l3 < d <= l1+l2+l3; 4: beyond reach.
    The first matching rule wins (region 2 is empty when l1 + l2 < 2 l3). The paper's
    labels are kept as printed: region 1 is not "low dexterity" and region 2 is not the
    full-dexterity set; use :func:`full_dexterity_bands` for that.
    """
    r1, r2, r3 = region_radii(links)
    d = _checked(
        distances,
        "distances",
        "paper_regions",
        "finite non-negative distances",
        lambda a: bool(np.all(a >= 0)),
    )
    regions = np.select([d <= r1, d <= r2, d <= r3], [1, 2, 3], default=4)
    return regions.astype(np.int8)


def synthesise_links(d_min: float, d_max: float, l3: float) -> Links:
    """Link lengths by eqs (10)-(11): l1 = (d_max + l3)/2 + 1, l2 = (d_max + l3)/2.

    The "+1" (in the task's length unit) makes |l1 - l2| = 1, so full dexterity at d_min
    needs l3 + 1 <= d_min (METHODS.md §1), not only the paper's l3 < d_min; callers check
    that. Returns (l1, l2, l3).
    """
    if not (math.isfinite(l3) and l3 > 0):
        raise _bad("l3", "synthesise_links", "a finite positive length", l3)
    if not (math.isfinite(d_min) and d_min >= 0):
        raise _bad("d_min", "synthesise_links", "a finite non-negative distance", d_min)
    if not (math.isfinite(d_max) and d_max >= d_min):
        raise _bad("d_max", "synthesise_links", f"a finite distance >= d_min = {d_min}", d_max)
    half = (d_max + l3) / 2.0
    return half + 1.0, half, float(l3)


# --- sampled dexterity with joint limits ----------------------------------------------


def orientation_samples(step: float) -> tuple[int, float]:
    """Orientation grid for a requested step (rad): n = max(1, round(2 pi / step)).

    The samples are ``phi_k = k (2 pi / n)``, k = 0..n-1. Returns (n, 2 pi / n).
    """
    n = _sample_count(step, "orientation_samples")
    return n, 2.0 * math.pi / n


def _joint_limits(joint_limits: ArrayLike, function: str) -> FloatArray:
    return _checked(
        joint_limits,
        "joint_limits",
        function,
        "(3, 2) radians [[lo, hi], ...] with -pi <= lo <= hi <= pi",
        lambda a: (
            a.shape == (3, 2)
            and bool(np.all((-np.pi <= a[:, 0]) & (a[:, 0] <= a[:, 1]) & (a[:, 1] <= np.pi)))
        ),
    )


def _point_features(px: FloatArray, py: FloatArray) -> FloatArray:
    """(4, m) features [px, py, 1, |p|^2] of m points."""
    return np.stack([px, py, np.ones_like(px), px * px + py * py])


def _linear_weights(
    links: Links, limits: FloatArray, cos_phi: FloatArray, sin_phi: FloatArray
) -> FloatArray:
    """(7, k, 4) weights on the point features of the quantities linear in them at phi_k.

    Joint j lies in its limit arc [lo, hi] (mid m_j, half-width h_j, C_j = cos h_j) iff
    its direction vector z_j satisfies z_j . u(m_j) >= C_j |z_j| — the same as
    lo <= wrap(th_j) <= hi up to the measure-zero point -pi. With the wrist
    w = p - l3 u(phi), c2 = cos th2 = (|w|^2 - l1^2 - l2^2) / (2 l1 l2), s2 = |sin th2| and
    the elbow sign ±: z1 = w (k1 ∓ i l2 s2), k1 = l1 + l2 c2 (two-link IK);
    z1 z2 = w (l1 c2 + l2 ± i l1 s2); z3 = e^{i phi} conj(z1 z2); |z1| = |z3| = |w|^2.
    Rotating w into each arc's mid frame, every test becomes
    ``c2 E_j + F_j ± s2 G_j >= 0`` with E_j, F_j, G_j linear in [px, py, 1, |p|^2]:
    rows c2, E1, F1, G1, E3, F3, G3 (th2 needs only c2).
    """
    l1, l2, l3 = links
    mid = 0.5 * (limits[:, 0] + limits[:, 1])
    cos_half = np.cos(0.5 * (limits[:, 1] - limits[:, 0]))
    cm1, cm3 = math.cos(mid[0]), math.cos(mid[2])
    sm1, sm3 = math.sin(mid[0]), math.sin(mid[2])
    ch1, ch3 = float(cos_half[0]), float(cos_half[2])
    inv, norm = 0.5 / (l1 * l2), l1 * l1 + l2 * l2
    one = np.ones_like(cos_phi)
    zero = np.zeros_like(cos_phi)
    # w . u(m1) = px cm1 + py sm1 - l3 cos(phi - m1); w x u(m1) = py cm1 - px sm1 - l3 sin(phi - m1)
    cos1 = cos_phi * cm1 + sin_phi * sm1
    sin1 = sin_phi * cm1 - cos_phi * sm1
    # v = e^{i(phi - m3)}: w . v = px vx + py vy - l3 cm3; w x v = py vx - px vy - l3 sm3
    vx = cos_phi * cm3 + sin_phi * sm3
    vy = sin_phi * cm3 - cos_phi * sm3
    rows = [
        (
            -2.0 * l3 * inv * cos_phi,
            -2.0 * l3 * inv * sin_phi,
            (l3 * l3 - norm) * inv * one,
            inv * one,
        ),
        (l2 * cm1 * one, l2 * sm1 * one, -l2 * l3 * cos1 - 2.0 * ch1 * l1 * l2, zero),
        (l1 * cm1 * one, l1 * sm1 * one, -l1 * l3 * cos1 - ch1 * norm, zero),
        (-l2 * sm1 * one, l2 * cm1 * one, -l2 * l3 * sin1, zero),
        (l1 * vx, l1 * vy, (-l1 * l3 * cm3 - 2.0 * ch3 * l1 * l2) * one, zero),
        (l2 * vx, l2 * vy, (-l2 * l3 * cm3 - ch3 * norm) * one, zero),
        (l1 * vy, -l1 * vx, l1 * l3 * sm3 * one, zero),
    ]
    return np.stack([np.stack(row, axis=-1) for row in rows])


def _require(plus: BoolArray, minus: BoolArray, base: FloatArray, branch: FloatArray) -> None:
    """plus &= base + branch >= 0; minus &= base - branch >= 0 (overwrites ``branch``)."""
    minus &= base >= branch
    np.negative(branch, out=branch)
    plus &= base >= branch


def _feasible(linear: FloatArray, limits: FloatArray) -> BoolArray:
    """Feasibility (...) from the (7, ...) linear quantities; consumes ``linear``."""
    c2, e1, f1, g1, e3, f3, g3 = linear
    s2 = c2 * c2
    np.subtract(1.0, s2, out=s2)
    plus: BoolArray = s2 >= 0.0  # the wrist is within the two-link annulus: |c2| <= 1
    np.maximum(s2, 0.0, out=s2)
    np.sqrt(s2, out=s2)
    minus = plus.copy()
    full = limits[:, 1] - limits[:, 0] >= 2.0 * np.pi
    if not full[1]:
        mid, half = 0.5 * (limits[1, 0] + limits[1, 1]), 0.5 * (limits[1, 1] - limits[1, 0])
        base = c2 * math.cos(mid)
        base -= math.cos(half)
        _require(plus, minus, base, np.multiply(s2, math.sin(mid)))
    for joint, (e, f, g) in ((0, (e1, f1, g1)), (2, (e3, f3, g3))):
        if not full[joint]:
            e *= c2
            e += f
            g *= s2
            _require(plus, minus, e, g)
    plus |= minus
    return plus


def _refined_measure(
    feasible: BoolArray,
    features: FloatArray,
    links: Links,
    limits: FloatArray,
    refine_tol: float,
) -> FloatArray:
    """Feasible measure (rad) per column of an (n, m) sample mask, transitions bisected."""
    n, m = feasible.shape
    step = 2.0 * np.pi / n
    following = np.roll(feasible, -1, axis=0)
    measure: FloatArray = step * np.count_nonzero(feasible & following, axis=0).astype(np.float64)
    samples, columns = np.nonzero(feasible != following)
    start = samples * step
    lo, hi = start.copy(), start + step
    lo_ok = feasible[samples, columns]
    pair_features = features[:, columns]
    for _ in range(max(0, math.ceil(math.log2(step / refine_tol)))):
        mid = 0.5 * (lo + hi)
        weights = _linear_weights(links, limits, np.cos(mid), np.sin(mid))
        linear = np.einsum("jkc,ck->jk", weights, pair_features)
        same = _feasible(linear, limits) == lo_ok
        lo = np.where(same, mid, lo)
        hi = np.where(same, hi, mid)
    edge = 0.5 * (lo + hi)
    piece = np.where(lo_ok, edge - start, start + step - edge)
    measure += np.bincount(columns, weights=piece, minlength=m)
    return measure


def limited_orientation_dexterity(
    links: ArrayLike,
    points: ArrayLike,
    joint_limits: ArrayLike,
    step: float,
    *,
    refine_tol: float | None = None,
    max_chunk_elements: int = 2**22,
    on_chunk: Callable[[int, int], None] | None = None,
) -> FloatArray:
    """d_z with joint limits by orientation sampling (METHODS.md §1, "With joint limits").

    links: (3,); points: (..., 2); joint_limits: (3, 2) rad ``[[lo, hi], ...]`` with
    -pi <= lo <= hi <= pi, joint angles wrapped to (-pi, pi]; step: requested sample
    spacing in rad (see :func:`orientation_samples`). Returns d_z (...) in [0, 1].

    At each sample phi_k the wrist w = p - l3 u(phi_k) is solved on both elbow branches;
    the sample counts if either branch has all three joints within limits, and
    ``d_z = (#feasible samples) / n``. With ``refine_tol`` (rad), every change of
    feasibility between cyclically consecutive samples is located by bisection to within
    ``refine_tol`` and d_z = (measure of the feasible set) / (2 pi). Either way, feasible
    or infeasible features narrower than one step can be missed.

    Work is vectorised over points x orientations, in chunks of points with
    ``chunk_points * n <= max_chunk_elements``; ``on_chunk(done_points, total_points)``
    is called after each chunk. Inside a chunk the kernel runs on cache-sized blocks of
    at most ``min(max_chunk_elements, 2**14)`` elements (about 110 bytes each), so the
    peak memory is that block plus the (...) result, whatever the grid size. The
    per-block matrix product uses BLAS (and its threads, if any).
    """
    function = "limited_orientation_dexterity"
    lengths = _links(links, function)
    p = _points(points, function)
    limits = _joint_limits(joint_limits, function)
    n = _sample_count(step, function)
    if refine_tol is not None and not (math.isfinite(refine_tol) and refine_tol > 0):
        raise _bad("refine_tol", function, "a finite positive angle in radians or None", refine_tol)
    if not (isinstance(max_chunk_elements, numbers.Integral) and max_chunk_elements >= n):
        raise _bad(
            "max_chunk_elements", function, f"an integer >= n = {n} samples", max_chunk_elements
        )
    flat = p.reshape(-1, 2)
    total = flat.shape[0]
    phi = np.arange(n) * (2.0 * np.pi / n)
    weights = _linear_weights(lengths, limits, np.cos(phi), np.sin(phi)).reshape(7 * n, 4)
    chunk = int(max_chunk_elements) // n
    block = max(1, min(chunk * n, _CACHE_BLOCK_ELEMENTS) // n)
    dz = np.empty(total, dtype=np.float64)
    for chunk_start in range(0, total, chunk):
        chunk_stop = min(chunk_start + chunk, total)
        for start in range(chunk_start, chunk_stop, block):
            stop = min(start + block, chunk_stop)
            features = _point_features(flat[start:stop, 0], flat[start:stop, 1])
            linear = (weights @ features).reshape(7, n, stop - start)
            feasible = _feasible(linear, limits)  # (n, points)
            if refine_tol is None:
                dz[start:stop] = np.count_nonzero(feasible, axis=0) / n
            else:
                measure = _refined_measure(feasible, features, lengths, limits, refine_tol)
                dz[start:stop] = np.clip(measure / (2.0 * np.pi), 0.0, 1.0)
        if on_chunk is not None:
            on_chunk(chunk_stop, total)
    return dz.reshape(p.shape[:-1])


# --- the per-point reference sampler (no shared helpers with the code above) ------------


def _wrap(angle: float) -> float:
    """Angle wrapped to (-pi, pi]."""
    return math.pi - (math.pi - angle) % (2.0 * math.pi)


def _within_limits(
    lengths: tuple[float, float],
    wrist: tuple[float, float],
    phi: float,
    limits: Sequence[Sequence[float]],
) -> bool:
    l1, l2 = lengths
    wx, wy = wrist
    c2 = (wx * wx + wy * wy - l1 * l1 - l2 * l2) / (2.0 * l1 * l2)
    if not -1.0 <= c2 <= 1.0:
        return False
    for th2 in (math.acos(c2), -math.acos(c2)):
        th1 = math.atan2(wy, wx) - math.atan2(l2 * math.sin(th2), l1 + l2 * math.cos(th2))
        angles = (_wrap(th1), _wrap(th2), _wrap(phi - th1 - th2))
        if all(lo <= a <= hi for a, (lo, hi) in zip(angles, limits, strict=True)):
            return True
    return False


def sampled_orientation_dexterity(
    links: Sequence[float],
    point: Sequence[float],
    step: float,
    joint_limits: Sequence[Sequence[float]] | None = None,
) -> float:
    """Reference d_z at ONE point: a plain loop over the samples phi_k = k 2 pi / n.

    The straightforward per-point implementation (math module only), kept independent of
    the vectorised code for property tests and the benchmark. Unlimited joints: phi_k
    counts iff |l1 - l2| <= |w| <= l1 + l2; with limits (rad, (3, 2)) it counts iff an
    elbow branch has every wrapped joint angle within its limits. Returns count / n.
    """
    function = "sampled_orientation_dexterity"
    if len(links) != 3 or not all(math.isfinite(v) and v > 0 for v in links):
        raise _bad("links", function, "three finite positive lengths (l1, l2, l3)", links)
    if len(point) != 2 or not all(math.isfinite(v) for v in point):
        raise _bad("point", function, "finite (x, y) coordinates", point)
    if not (step > 0 and math.isfinite(2.0 * math.pi / step)):
        raise _bad("step", function, "a finite positive angle in radians", step)
    if joint_limits is not None and (
        len(joint_limits) != 3
        or not all(
            len(lim) == 2 and -math.pi <= lim[0] <= lim[1] <= math.pi for lim in joint_limits
        )
    ):
        limits_rule = "(3, 2) radians [[lo, hi], ...] with -pi <= lo <= hi <= pi"
        raise _bad("joint_limits", function, limits_rule, joint_limits)
    l1, l2, l3 = (float(v) for v in links)
    x, y = (float(v) for v in point)
    n = max(1, round(2.0 * math.pi / step))
    count = 0
    for k in range(n):
        phi = k * (2.0 * math.pi / n)
        wrist = (x - l3 * math.cos(phi), y - l3 * math.sin(phi))
        if joint_limits is None:
            count += abs(l1 - l2) <= math.hypot(*wrist) <= l1 + l2
        else:
            count += _within_limits((l1, l2), wrist, phi, joint_limits)
    return count / n
