"""The per-point reference for 1/kappa of 2-DOF planar parallel robots.

The straightforward way, written independently of the vectorised kernel in
:mod:`.model`: inverse kinematics by the paper's eq (2)
(half-angle tangent via atan2, in its cancellation-free form), the unit vectors of
eq (1), A and B of eq (4), J = A^-1 B by ``numpy.linalg.solve`` and the singular values
by ``numpy.linalg.svd``. Kept for property tests and the benchmark.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from worker.common.parameter_errors import bad_parameter
from worker.families.planar_parallel.kinematics.model import Architecture, checked_mode

__all__ = ["reference_jacobian", "sampled_inverse_condition"]


def _proximal_rows(
    arch: Architecture, x: float, y: float, mode: tuple[int, int]
) -> tuple[list[float], list[list[float]]] | None:
    """(A diagonal, B rows) for the proximal arm by eqs (1)-(4), or None if unreachable."""
    diagonal, rows = [], []
    for sign, m in zip((1.0, -1.0), mode, strict=True):
        a_i = -2.0 * arch.l1 * y
        b_i = -2.0 * arch.l1 * (x - sign * arch.e)
        # C_i of eq (2), x^2 + y^2 + e^2 + l1^2 - l2^2 - 2 sgn(i) e x, without cancellation
        c_i = (x - sign * arch.e) ** 2 + y * y + arch.l1**2 - arch.l2**2
        discriminant = a_i * a_i - c_i * c_i + b_i * b_i
        if discriminant < 0.0 or (x - sign * arch.e) ** 2 + y * y == 0.0:
            return None
        root = m * math.sqrt(discriminant)
        # eq (2): tan(theta / 2) = (-A + root) / (C - B), or its rationalised twin
        # (C + B) / (-A - root) where -A and root have opposite signs (no cancellation;
        # if A = 0 the pair of larger norm: one of them is 0 / 0 at a reach boundary)
        primary, twin = (-a_i + root, c_i - b_i), (c_i + b_i, -a_i - root)
        if -a_i * m < 0.0 or (-a_i * m == 0.0 and math.hypot(*twin) > math.hypot(*primary)):
            primary = twin
        theta = 2.0 * math.atan2(*primary)
        u = (math.cos(theta), math.sin(theta))
        w = ((x - sign * arch.e - arch.l1 * u[0]) / arch.l2, (y - arch.l1 * u[1]) / arch.l2)
        diagonal.append(arch.l1 * (w[0] * -u[1] + w[1] * u[0]))  # l1 w^T Q u
        rows.append(list(w))
    return diagonal, rows


def _rows(
    arch: Architecture, x: float, y: float, mode: tuple[int, int]
) -> tuple[list[float], list[list[float]]] | None:
    if arch.actuation == "proximal-arm":
        return _proximal_rows(arch, x, y, mode)
    diagonal, rows = [], []
    for sign, m in zip((1.0, -1.0), mode, strict=True):
        if arch.actuation == "telescopic-leg":
            length = math.hypot(x - sign * arch.e, y)
            if length == 0.0:
                return None
            diagonal.append(1.0)
            rows.append([(x - sign * arch.e) / length, y / length])
        else:
            if abs(y) > arch.l2:
                return None
            slider = x + m * math.sqrt(arch.l2**2 - y * y)
            w = [(x - slider) / arch.l2, y / arch.l2]
            diagonal.append(w[0])  # w^T u with u = e1
            rows.append(w)
    return diagonal, rows


def reference_jacobian(
    arch: Architecture, point: Sequence[float], working_mode: tuple[int, int] = (1, -1)
) -> np.ndarray | None:
    """J = A^-1 B (2, 2) at one point, or None where unreachable or A is singular."""
    mode = checked_mode(working_mode, "reference_jacobian")
    x, y = (float(v) for v in point)
    terms = _rows(arch, x, y, mode)
    if terms is None:
        return None
    diagonal, rows = terms
    try:
        return np.asarray(np.linalg.solve(np.diag(diagonal), np.array(rows)), dtype=np.float64)
    except np.linalg.LinAlgError:
        return None


def sampled_inverse_condition(
    arch: Architecture, point: Sequence[float], working_mode: tuple[int, int] = (1, -1)
) -> float:
    """1/kappa = sigma_min / sigma_max of J at ONE point by numpy SVD (eq 5).

    NaN where unreachable, 0 where A is singular (J does not exist).
    """
    function = "sampled_inverse_condition"
    if not isinstance(arch, Architecture):
        raise bad_parameter("arch", function, "an Architecture", arch)
    if len(point) != 2 or not all(math.isfinite(float(v)) for v in point):
        raise bad_parameter("point", function, "finite (x, y) coordinates", point)
    mode = checked_mode(working_mode, function)
    x, y = (float(v) for v in point)
    if _rows(arch, x, y, mode) is None:
        return math.nan
    jacobian = reference_jacobian(arch, (x, y), mode)
    if jacobian is None:
        return 0.0
    singular_values = np.linalg.svd(jacobian, compute_uv=False)
    return float(singular_values[-1] / singular_values[0])
