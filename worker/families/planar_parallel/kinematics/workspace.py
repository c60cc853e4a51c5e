"""The largest centred rectangle W_lambda inside W_kappa0 and the mean 1/kappa over it
(Huang et al. 2004 §III-C; docs/methods/planar-parallel.md). Re-exported by
:mod:`worker.families.planar_parallel.kinematics`; conventions as there.

W_kappa0 = {reachable points of the working mode with 1/kappa >= limit} itself is in
:mod:`.kappa_region`; the rectangle search (on the lowest run of each column,
:mod:`.columns`) is in :mod:`.rectangle`.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from worker.common.parameter_errors import bad_parameter
from worker.families.planar_parallel.kinematics.columns import search_box, single
from worker.families.planar_parallel.kinematics.model import (
    Architecture,
    checked_limit,
    checked_mode,
    inverse_condition_kernel,
)
from worker.families.planar_parallel.kinematics.pressure import min_pressure_angle_in_rectangle
from worker.families.planar_parallel.kinematics.rectangle import RectangleArrays, solve_rectangles

__all__ = [
    "Rectangle",
    "largest_rectangle",
    "mean_inverse_condition",
    "rectangle_from_arrays",
    "rectangle_min_pressure_angle",
]


@dataclass(frozen=True)
class Rectangle:
    """W_lambda: width b, height h, centred at (0, -H_prime), lambda = b / h; S = b h.

    found False (NaN sizes) when no rectangle centred on x = 0 fits; message says why or
    sums up the result. boundary_min_inverse_condition: the least 1/kappa met on the
    boundary check (>= limit - 1e-9 whenever found).
    """

    found: bool
    b: float
    h: float
    H_prime: float
    S: float
    message: str
    limit: float = math.nan
    aspect_ratio: float = math.nan
    boundary_min_inverse_condition: float = math.nan


def _positive_int(value: object, name: str, function: str, minimum: int) -> int:
    if not (isinstance(value, numbers.Integral) and not isinstance(value, bool)
            and int(value) >= minimum):  # fmt: skip
        raise bad_parameter(name, function, f"an integer >= {minimum}", value)
    return int(value)


def _positive_real(value: object, name: str, function: str, requirement: str) -> float:
    if not (isinstance(value, numbers.Real) and not isinstance(value, bool)
            and math.isfinite(float(value)) and float(value) > 0):  # fmt: skip
        raise bad_parameter(name, function, requirement, value)
    return float(value)


_STATUS = {
    1: "no rectangle centred on x = 0 fits: W_kappa0 has no run on x = 0",
    2: "the rectangle reaches the end of the searched span (enlarge x_half_span)",
    3: "shrunk about its centre to pass the boundary check (a feature narrower than the "
    "column spacing)",
}


def rectangle_from_arrays(
    rects: RectangleArrays, index: int, limit: float, aspect: float, samples: int
) -> Rectangle:
    """Row ``index`` of a batched result as a :class:`Rectangle`."""
    status = int(rects.status[index])
    if not rects.found[index]:
        reason = _STATUS.get(status, "no rectangle found")
        return Rectangle(False, math.nan, math.nan, math.nan, math.nan, reason, limit, aspect)
    h = float(rects.h[index])
    b, centre, check = aspect * h, float(rects.centre[index]), float(rects.boundary_min[index])
    message = (
        f"W_lambda at 1/kappa >= {limit:g}, lambda = {aspect:g}: b = {b:.6f}, h = {h:.6f}, "
        f"H' = {-centre:.6f}, S = {b * h:.6f}; boundary check: min 1/kappa = {check:.6f} "
        f"on 4 x {samples} samples"
    )
    if status in (2, 3):
        message += "; " + _STATUS[status]
    return Rectangle(True, b, h, -centre, b * h, message, limit, aspect, check)


def largest_rectangle(
    arch: Architecture,
    limit: float,
    aspect_ratio: float = 4.0,
    working_mode: tuple[int, int] = (1, -1),
    *,
    columns: int = 257,
    rows: int = 160,
    boundary_samples: int = 512,
    x_half_span: float | None = None,
) -> Rectangle:
    """W_lambda: the largest rectangle of aspect b/h = ``aspect_ratio``, centred on x = 0,
    inside W_kappa0 (Fig. 6), by the exact envelope method of
    :mod:`.rectangle` (equivalent to the paper's
    bisection on h with a search over the centre H'); h and H' to ~1e-7.

    ``columns`` abscissae over [0, X] (both signs unless the working mode is mirror-
    symmetric), ``rows`` scan heights each; the result is checked on
    ``boundary_samples`` points per edge. X as in
    :func:`.kappa_region.kappa_region_boundary`, except the linear drive's default is
    ``aspect_ratio * l2``.
    """
    function = "largest_rectangle"
    value = checked_limit(limit, function)
    aspect = _positive_real(aspect_ratio, "aspect_ratio", function, "a positive ratio b/h")
    mode = checked_mode(working_mode, function)
    count = _positive_int(columns, "columns", function, 3)
    scans = _positive_int(rows, "rows", function, 3)
    samples = _positive_int(boundary_samples, "boundary_samples", function, 2)
    if x_half_span is not None:
        x_half_span = _positive_real(x_half_span, "x_half_span", function, "a positive length")
    elif arch.actuation == "linear-drive":
        x_half_span = aspect * arch.l2
    span, y_low, y_high = search_box(arch, value, x_half_span)
    box = (np.array([span]), np.array([y_low]), np.array([y_high]))
    rects = solve_rectangles(single(arch, mode, value), aspect, box, count, scans, samples)
    return rectangle_from_arrays(rects, 0, value, aspect, samples)


def _checked_rectangle(rect: object, function: str) -> Rectangle:
    if not isinstance(rect, Rectangle):
        raise bad_parameter("rect", function, "a Rectangle", rect)
    return rect


def mean_inverse_condition(
    arch: Architecture, rect: Rectangle, mesh: int = 101, working_mode: tuple[int, int] = (1, -1)
) -> float:
    """Mean 1/kappa over the mesh x mesh nodes of W_lambda, eq (14) (edges included).

    Nodes: x = linspace(-b/2, b/2, mesh), y = linspace(-H' - h/2, -H' + h/2, mesh); the
    jobs use 101 x 101 by default (report the mesh: 5 x 5 and 401 x 401 differ in the 2nd
    and 4th decimals, docs/methods/planar-parallel.md). NaN if the rectangle was not found; NaN if a
    node is unreachable.
    """
    function = "mean_inverse_condition"
    rect = _checked_rectangle(rect, function)
    nodes = _positive_int(mesh, "mesh", function, 2)
    mode = checked_mode(working_mode, function)
    if not rect.found:
        return math.nan
    x = np.linspace(-rect.b / 2.0, rect.b / 2.0, nodes)
    y = np.linspace(-rect.H_prime - rect.h / 2.0, -rect.H_prime + rect.h / 2.0, nodes)
    return float(np.mean(inverse_condition_kernel(arch, mode, x[None, :], y[:, None])))


def rectangle_min_pressure_angle(arch: Architecture, rect: Rectangle) -> float:
    """Exact min over W_lambda of beta_min = min(beta_1, beta_2), rad (eq 15; NaN if not
    found). For the proximal arm the minimum sits where the paper's eq (16) says when
    |e| <= b/2: at (+-e, top edge), or at a far corner."""
    rect = _checked_rectangle(rect, "rectangle_min_pressure_angle")
    if not rect.found:
        return math.nan
    top, bottom = -rect.H_prime + rect.h / 2.0, -rect.H_prime - rect.h / 2.0
    angle = min_pressure_angle_in_rectangle(arch, arch.l2, arch.e, rect.b / 2.0, bottom, top)
    return float(angle)
