"""Exact orientation dexterity of three-link planar arms with joint limits, by events.

At a point p the feasible orientations phi (some elbow branch has every joint within its
limits) form a union of arcs.  Feasibility can change only where one of these
*events* happens, each a circle-circle intersection with a closed form
(docs/methods/planar-serial.md, "Joint limits: exact events"):

* the wrist w = p - l3 u(phi) on the edge of the two-link annulus, |w| = l1 + l2 or
  |w| = |l1 - l2| (the elbow branches meet; th2 = 0 or +-180 deg);
* th2 at a limit t: |w|^2 = l1^2 + l2^2 + 2 l1 l2 cos t;
* th1 at a limit t: the elbow is fixed at E = l1 u(t), so |w - E| = l2;
* th3 at a limit t: the link-2 direction is phi - t, so the elbow
  E = p - (l3 + l2 e^{-it}) e^{i phi} and |E| = l1.

Every one of them reads ``a . u(phi) = k`` for a vector a and a number k fixed by the
point, so ``phi = atan2(a) +- atan2(sqrt(|a|^2 - k^2), k)`` when |a| >= |k| (two roots,
one when tangent, none otherwise; a = 0, a point at the base or an elbow over the
point, gives none: that condition does not depend on phi).  An angle crossing +-180 deg
matters only when a limit sits there, and that limit's own event covers it.

The events of a point, with a cut at phi = 0 so that a point without events has one
arc, are sorted; one orientation inside each sub-arc, its middle, is tested with the
per-orientation check of :mod:`.joint_limits` (both elbow branches), and the lengths of
the feasible sub-arcs add up to d_z * 2 pi: exact to rounding, whatever the arc widths.
Conventions as in :mod:`worker.families.planar_serial.kinematics`.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from worker.common.parameter_errors import bad_parameter
from worker.families.planar_serial.kinematics.inputs import (
    BoolArray,
    FloatArray,
    LinkLengths,
    checked_joint_limits,
    checked_link_rows,
    checked_links,
    checked_points,
)
from worker.families.planar_serial.kinematics.joint_limits import feasible_orientations

__all__ = [
    "event_conditions",
    "event_count",
    "events_dexterity",
    "exact_limited_orientation_dexterity",
    "feasible_arcs",
    "orientation_events",
]

#: Points per chunk: up to 21 events each and ~100 bytes per sub-arc in flight, so a
#: chunk's temporaries stay in cache (larger chunks run slower, not faster).
DEFAULT_CHUNK_POINTS = 2**11
TWO_PI = 2.0 * math.pi


def _free(limits: FloatArray) -> BoolArray:
    """(3,) joints whose limits span the full turn (no constraint, no event)."""
    return np.asarray(limits[:, 1] - limits[:, 0] >= TWO_PI, dtype=bool)


def _limit_angles(limits: FloatArray, joint: int) -> tuple[float, ...]:
    """Distinct limit angles of a constrained joint (-pi and pi are one angle)."""
    if _free(limits)[joint]:
        return ()
    lo, hi = (float(v) for v in limits[joint])
    return (lo,) if math.isclose(lo, hi, abs_tol=0.0) else (lo, hi)


def event_count(limits: FloatArray) -> int:
    """Number of event columns :func:`orientation_events` returns for these limits."""
    conditions = 2 + sum(len(_limit_angles(limits, joint)) for joint in range(3))
    return 2 * conditions


def _roots(ax: FloatArray, ay: FloatArray, k: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Both solutions phi of ``ax cos phi + ay sin phi = k`` (NaN where none).

    No root when |a| < |k| (the square root of a negative number is NaN and stays NaN);
    a = 0 with k = 0 (a condition met at every phi) gives the harmless cut phi = 0.
    """
    with np.errstate(invalid="ignore"):
        half = np.arctan2(np.sqrt(ax * ax + ay * ay - k * k), k)
    centre = np.arctan2(ay, ax)
    return centre - half, centre + half


def event_conditions(
    links: LinkLengths, limits: FloatArray, px: FloatArray, py: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The event conditions ``ax cos phi + ay sin phi = k`` at m points: (ax, ay, k).

    links (three numbers, or three (m,) columns, one design per point) and limits
    checked; px, py: (m,) coordinates.  Each output is (m, C) with C = event_count(limits)
    / 2 columns: annulus edges, th2 limits, th1 limits, th3 limits.  ax and ay are affine
    in (px, py), k is quadratic: along a ray from the base they are polynomials of degree
    1 and 2 in the distance (:mod:`.ray.events`).
    """
    l1, l2, l3 = links
    ax: list[FloatArray] = []
    ay: list[FloatArray] = []
    k: list[FloatArray] = []
    p2 = px * px + py * py
    wrist_radii2 = [(l1 + l2) ** 2, (l1 - l2) ** 2]
    wrist_radii2 += [
        l1 * l1 + l2 * l2 + 2.0 * l1 * l2 * math.cos(t) for t in _limit_angles(limits, 1)
    ]
    for radius2 in wrist_radii2:  # |p - l3 u|^2 = R^2  <=>  p . u = (|p|^2 + l3^2 - R^2) / (2 l3)
        ax.append(px)
        ay.append(py)
        k.append((p2 + (l3 * l3 - radius2)) / (2.0 * l3))
    for t in _limit_angles(limits, 0):  # |q - l3 u| = l2 with q = p - l1 u(t)
        qx, qy = px - l1 * math.cos(t), py - l1 * math.sin(t)
        ax.append(qx)
        ay.append(qy)
        k.append((qx * qx + qy * qy + (l3 * l3 - l2 * l2)) / (2.0 * l3))
    for t in _limit_angles(limits, 2):  # |p - c e^{i phi}| = l1 with c = l3 + l2 e^{-it}
        cx, cy = l3 + l2 * math.cos(t), -l2 * math.sin(t)
        # Re(conj(p) c e^{i phi}) = (|p|^2 + |c|^2 - l1^2) / 2, conj(p) c = zr + i zi
        ax.append(px * cx + py * cy)
        ay.append(py * cx - px * cy)
        k.append(0.5 * (p2 + (cx * cx + cy * cy - l1 * l1)))
    return np.stack(ax, axis=-1), np.stack(ay, axis=-1), np.stack(k, axis=-1)


def orientation_events(
    links: LinkLengths, limits: FloatArray, px: FloatArray, py: FloatArray
) -> FloatArray:
    """Event orientations (m, event_count) in rad, NaN where a condition has no root.

    links (three numbers, or three (m,) columns, one design per point) and limits
    checked; px, py: (m,) coordinates.  Column order: the conditions of
    :func:`event_conditions` in turn, two roots each (centre - half, centre + half).
    """
    ax, ay, k = event_conditions(links, limits, px, py)
    minus, plus = _roots(ax, ay, k)
    return np.stack([minus, plus], axis=-1).reshape(px.shape[0], -1)


def _sub_arcs(events: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Sub-arc (starts, lengths), each (m, E + 1), from events (m, E) and a cut at 0.

    Starts are sorted in [0, 2 pi) with the first at 0 (a missing event, NaN, becomes
    another cut at 0: an empty sub-arc); each sub-arc runs to the next start, the last
    to 2 pi.
    """
    m, count = events.shape
    starts = np.zeros((m, count + 1))
    wrapped = starts[:, 1:]
    np.nan_to_num(events, copy=False, nan=0.0)
    # roots lie in (-2 pi, 2 pi]: one turn added or taken off wraps them to [0, 2 pi)
    np.add(events, np.where(events < 0.0, TWO_PI, 0.0), out=wrapped)
    wrapped -= np.where(wrapped >= TWO_PI, TWO_PI, 0.0)
    starts.sort(axis=1)
    lengths = np.empty_like(starts)
    np.subtract(starts[:, 1:], starts[:, :-1], out=lengths[:, :-1])
    np.subtract(TWO_PI, starts[:, -1], out=lengths[:, -1])
    return starts, lengths


def _at_rows(links: LinkLengths, rows: NDArray[np.intp]) -> LinkLengths:
    """The links of the chosen rows: three numbers stay, three columns are indexed."""
    l1, l2, l3 = links
    if isinstance(l1, np.ndarray):
        return l1[rows], np.asarray(l2)[rows], np.asarray(l3)[rows]
    return links


def _chunk_measure(links: LinkLengths, limits: FloatArray, flat: FloatArray) -> FloatArray:
    """Feasible measure (rad) at each of the (m, 2) points (links: one design, or one
    per point as three (m,) columns)."""
    px, py = flat[:, 0], flat[:, 1]
    starts, lengths = _sub_arcs(orientation_events(links, limits, px, py))
    rows, cols = np.nonzero(lengths > 0.0)
    length = lengths[rows, cols]
    middle = starts[rows, cols] + 0.5 * length
    feasible = feasible_orientations(_at_rows(links, rows), limits, px[rows], py[rows], middle)
    measure = np.bincount(rows[feasible], weights=length[feasible], minlength=len(px))
    return np.asarray(measure, dtype=np.float64)


def exact_limited_orientation_dexterity(
    links: ArrayLike,
    points: ArrayLike,
    joint_limits: ArrayLike,
    *,
    chunk_points: int = DEFAULT_CHUNK_POINTS,
    on_chunk: Callable[[int, int], None] | None = None,
) -> FloatArray:
    """Exact d_z with joint limits, from the closed-form events (module docstring).

    links: (3,), or designs (..., 3) broadcast against the points' leading axes (the
    design search evaluates a population at once); points: (..., 2); joint_limits:
    (3, 2) rad ``[[lo, hi], ...]`` with -pi <= lo <= hi <= pi, joint angles wrapped to
    (-pi, pi]. Returns d_z in [0, 1], of the points' shape (broadcast with the
    designs'): the measure of the feasible orientations over 2 pi.

    Points beyond the reach l1 + l2 + l3 or inside the unreachable disk get 0 without
    work; the others are processed ``chunk_points`` at a time (peak memory about
    ``chunk_points`` x 21 sub-arcs x 100 bytes), ``on_chunk(done, total)`` after each.
    """
    function = "exact_limited_orientation_dexterity"
    lengths = checked_link_rows(links, function)
    p = checked_points(points, function)
    limits = checked_joint_limits(joint_limits, function)
    if not (isinstance(chunk_points, numbers.Integral) and chunk_points >= 1):
        raise bad_parameter("chunk_points", function, "a positive integer", chunk_points)
    return events_dexterity(lengths, p, limits, int(chunk_points), on_chunk)


def events_dexterity(
    lengths: FloatArray,
    p: FloatArray,
    limits: FloatArray,
    chunk_points: int = DEFAULT_CHUNK_POINTS,
    on_chunk: Callable[[int, int], None] | None = None,
) -> FloatArray:
    """:func:`exact_limited_orientation_dexterity` of inputs already checked: designs
    ``(3,)`` or ``(..., 3)`` finite and positive, points ``(..., 2)`` finite, limits
    (3, 2) rad in [-pi, pi] with lo <= hi (the study kernel's tiles)."""
    shape = np.broadcast_shapes(lengths.shape[:-1], p.shape[:-1])
    flat = np.broadcast_to(p, (*shape, 2)).reshape(-1, 2)
    # one design: three numbers; designs: one row of links per point
    rows = None if lengths.ndim == 1 else np.broadcast_to(lengths, (*shape, 3)).reshape(-1, 3)
    # one design: three numbers (unused when there are rows)
    single = (float(lengths.flat[0]), float(lengths.flat[1]), float(lengths.flat[2]))
    per_point = lengths if rows is None else rows
    outer = per_point.sum(axis=-1)
    inner = np.maximum(0.0, 2.0 * per_point.max(axis=-1) - outer)
    distance = np.hypot(flat[:, 0], flat[:, 1])
    candidates = np.flatnonzero((distance <= outer) & (distance >= inner))
    total = flat.shape[0]
    dz = np.zeros(total, dtype=np.float64)
    step = int(chunk_points)
    for start in range(0, max(total, 1), step):
        stop = min(start + step, total)
        lo, hi = np.searchsorted(candidates, [start, stop])
        chosen = candidates[lo:hi]
        if chosen.size:
            chosen_links: LinkLengths = (
                single if rows is None else (rows[chosen, 0], rows[chosen, 1], rows[chosen, 2])
            )
            measure = _chunk_measure(chosen_links, limits, flat[chosen])
            dz[chosen] = np.clip(measure / TWO_PI, 0.0, 1.0)
        if on_chunk is not None:
            on_chunk(stop, total)
    return dz.reshape(shape)


def feasible_arcs(
    links: ArrayLike, point: ArrayLike, joint_limits: ArrayLike
) -> tuple[tuple[float, float], ...]:
    """The feasible orientations at ONE point as merged arcs ((start, end), ...) in rad.

    Starts in [0, 2 pi), each end > its start (an arc may run past 2 pi); the whole
    circle is ((0, 2 pi),).  The same events and tests as
    :func:`exact_limited_orientation_dexterity`, for inspection and tests.
    """
    function = "feasible_arcs"
    lengths = checked_links(links, function)
    p = checked_points(point, function).reshape(-1, 2)
    limits = checked_joint_limits(joint_limits, function)
    if p.shape[0] != 1:
        raise bad_parameter("point", function, "one (x, y) point", point)
    starts, widths = _sub_arcs(orientation_events(lengths, limits, p[:, 0], p[:, 1]))
    ends = np.append(starts[0, 1:], TWO_PI)
    keep = widths[0] > 0.0
    start, end = starts[0, keep], ends[keep]
    x, y = np.full(start.shape, p[0, 0]), np.full(start.shape, p[0, 1])
    ok = feasible_orientations(lengths, limits, x, y, 0.5 * (start + end))
    arcs: list[list[float]] = []
    for a, b, good in zip(start.tolist(), end.tolist(), ok.tolist(), strict=True):
        if not good:
            continue
        if arcs and arcs[-1][1] == a:
            arcs[-1][1] = b
        else:
            arcs.append([a, b])
    if len(arcs) > 1 and arcs[0][0] == 0.0 and arcs[-1][1] == TWO_PI:
        arcs[-1][1] = TWO_PI + arcs.pop(0)[1]  # the last arc runs on through 2 pi
    return tuple((a, b) for a, b in arcs)
