"""2-DOF planar parallel robots with mirror-symmetric geometry: kinematics, conditioning
(1/kappa), pressure angles, W_kappa0 and the optimum design of Huang et al. (2004).

Huang, Li, Li, Chetwynd & Whitehouse, "Optimal kinematic design of 2-DOF parallel
manipulators with well-shaped workspace bounded by a specified conditioning index",
IEEE T-RA 20(3) 2004, restated in docs/methods/planar-parallel.md, which wins where the two
disagree.

Conventions (details in :mod:`.model`): chain i = 1 on
the +x side, actuated joints at (+-e, 0), end-effector point r = (x, y), lengths in one
unit (l1 = 1 normalises the proximal arm, delta = l2 / l1), angles in radians unless a
name ends in ``_deg``. ``working_mode = (m1, m2)`` are the signs in eq (2); the paper's
(+1, -1) is the default. Velocity map eq (4): ``q_dot = J v``, ``J = A^-1 B``; 1/kappa =
sigma_min / sigma_max of J (eq 5), computed in closed form (eq 7). Point functions are
batched on the leading axes of ``points`` (..., 2) and return arrays, NaN where a point
is unreachable in the working mode.

The isotropic design (eq 12) and point are in
:mod:`.isotropic`, the conditioning limit from an
allowable pressure angle (eqs 15-17) in
:mod:`.pressure`, W_kappa0 and W_lambda in :mod:`.kappa_region` and
:mod:`.workspace` (column search: :mod:`.columns`, :mod:`.column_runs`,
:mod:`.maxima`; rectangle: :mod:`.rectangle`), the delta sweep in
:mod:`.sweep` and the per-point SVD reference in
:mod:`.reference`; their public names are re-exported
here, so this module is the one to import.

A job checks its robot once: :class:`~.model.Robot` (an Architecture and a working
mode) is built from its validated inputs and passed on; the functions named
``robot_*`` take it and trust it (no checks), the others check
their arguments and call them.

Errors: bad parameters raise ValueError ("The 'x' parameter of f must be ... Got ...
instead."); numerical outcomes (nothing reachable, no rectangle) are data: NaN fields,
``found`` flags and a ``message``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from worker.common.parameter_errors import bad_parameter
from worker.families.planar_parallel.kinematics.isotropic import (
    isotropic_architecture as isotropic_architecture,
)
from worker.families.planar_parallel.kinematics.isotropic import isotropic_point as isotropic_point
from worker.families.planar_parallel.kinematics.isotropic import (
    robot_isotropic_point as robot_isotropic_point,
)
from worker.families.planar_parallel.kinematics.kappa_region import KappaRegion as KappaRegion
from worker.families.planar_parallel.kinematics.kappa_region import (
    kappa_region_boundary as kappa_region_boundary,
)
from worker.families.planar_parallel.kinematics.kappa_region import (
    robot_kappa_region as robot_kappa_region,
)
from worker.families.planar_parallel.kinematics.model import Actuation as Actuation
from worker.families.planar_parallel.kinematics.model import Architecture as Architecture
from worker.families.planar_parallel.kinematics.model import (
    BoolArray,
    FloatArray,
    chain_terms,
    checked_mode,
    checked_points,
)
from worker.families.planar_parallel.kinematics.model import Robot as Robot
from worker.families.planar_parallel.kinematics.pressure import (
    condition_limit_from_pressure_angle as condition_limit_from_pressure_angle,
)
from worker.families.planar_parallel.kinematics.pressure import (
    max_condition_limit as max_condition_limit,
)
from worker.families.planar_parallel.kinematics.reference import (
    reference_jacobian as reference_jacobian,
)
from worker.families.planar_parallel.kinematics.reference import (
    sampled_inverse_condition as sampled_inverse_condition,
)
from worker.families.planar_parallel.kinematics.robot_values import (
    ConditioningMap as ConditioningMap,
)
from worker.families.planar_parallel.kinematics.robot_values import (
    robot_inverse_condition as robot_inverse_condition,
)
from worker.families.planar_parallel.kinematics.robot_values import (
    robot_inverse_kinematics as robot_inverse_kinematics,
)
from worker.families.planar_parallel.kinematics.robot_values import robot_map as robot_map
from worker.families.planar_parallel.kinematics.robot_values import (
    robot_pressure_angles as robot_pressure_angles,
)
from worker.families.planar_parallel.kinematics.sweep import DesignSweep as DesignSweep
from worker.families.planar_parallel.kinematics.sweep import SweepRow as SweepRow
from worker.families.planar_parallel.kinematics.sweep import design_sweep as design_sweep
from worker.families.planar_parallel.kinematics.workspace import Rectangle as Rectangle
from worker.families.planar_parallel.kinematics.workspace import (
    largest_rectangle as largest_rectangle,
)
from worker.families.planar_parallel.kinematics.workspace import (
    mean_inverse_condition as mean_inverse_condition,
)
from worker.families.planar_parallel.kinematics.workspace import (
    rectangle_min_pressure_angle as rectangle_min_pressure_angle,
)

__all__ = [
    "Actuation",
    "Architecture",
    "ConditioningMap",
    "DesignSweep",
    "KappaRegion",
    "Rectangle",
    "Robot",
    "SweepRow",
    "condition_limit_from_pressure_angle",
    "conditioning_map",
    "design_sweep",
    "inverse_condition",
    "inverse_kinematics",
    "isotropic_architecture",
    "isotropic_point",
    "jacobian",
    "kappa_region_boundary",
    "largest_rectangle",
    "max_condition_limit",
    "mean_inverse_condition",
    "pressure_angles",
    "rectangle_min_pressure_angle",
    "reference_jacobian",
    "robot_inverse_condition",
    "robot_inverse_kinematics",
    "robot_isotropic_point",
    "robot_kappa_region",
    "robot_map",
    "robot_pressure_angles",
    "sampled_inverse_condition",
    "workspace_area",
]

PAPER_MODE = (1, -1)


def _checked_arch(arch: object, function: str) -> Architecture:
    if not isinstance(arch, Architecture):
        raise bad_parameter("arch", function, "an Architecture", arch)
    return arch


def inverse_kinematics(
    arch: Architecture, points: ArrayLike, working_mode: tuple[int, int] = PAPER_MODE
) -> tuple[FloatArray, BoolArray]:
    """Actuated joints at points (..., 2): (joints (..., 2), reachable (...)).

    Proximal arm: th_1i by eq (2) (atan2 form, wrapped to (-pi, pi]), rad; telescopic
    leg: leg lengths |r - sgn(i) e e1|; linear drive: the sliders' x coordinates
    ``x + m_i sqrt(l2^2 - y^2)``. NaN where unreachable (and on a pivot).
    """
    arch = _checked_arch(arch, "inverse_kinematics")
    p = checked_points(points, "inverse_kinematics")
    return robot_inverse_kinematics(
        Robot(arch, checked_mode(working_mode, "inverse_kinematics")), p
    )


def jacobian(
    arch: Architecture, points: ArrayLike, working_mode: tuple[int, int] = PAPER_MODE
) -> FloatArray:
    """J = A^-1 B (..., 2, 2) of eq (4), so that q_dot = J v.

    A = diag(l1 w_i^T Q u_i) (proximal arm; eq 3 multiplied by w_i^T, the paper's l1 = 1),
    E2 (telescopic leg), diag(w_i^T u_i) (linear drive); B = [w1 w2]^T. Units: rad per
    length unit, or length per length. NaN where unreachable, +-inf rows where A is
    singular.
    """
    arch = _checked_arch(arch, "jacobian")
    p = checked_points(points, "jacobian")
    terms = chain_terms(arch, checked_mode(working_mode, "jacobian"), p)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.asarray(terms.w / terms.a[..., None], dtype=np.float64)


def inverse_condition(
    arch: Architecture, points: ArrayLike, working_mode: tuple[int, int] = PAPER_MODE
) -> FloatArray:
    """1/kappa (...) in [0, 1] by eq (7) (rationalised, see
    :func:`.model.inverse_condition_from_terms`); equal to
    sigma_min / sigma_max of :func:`jacobian`. NaN where unreachable, 0 where A is
    singular."""
    arch = _checked_arch(arch, "inverse_condition")
    p = checked_points(points, "inverse_condition")
    mode = checked_mode(working_mode, "inverse_condition")
    return robot_inverse_condition(Robot(arch, mode), p)


def pressure_angles(
    arch: Architecture, points: ArrayLike, working_mode: tuple[int, int] = PAPER_MODE
) -> FloatArray:
    """Pressure angles (beta_1, beta_2) (..., 2), rad, in [0, pi/2]; pi/2 is best.

    The paper's beta_i (eq 8): |A_ii| = sin(beta_i) with A normalised as in eq (7).
    Proximal arm: eq (15), the acute angle between proximal and distal links,
    ``acos(|l1^2 + l2^2 - |p_i|^2| / (2 l1 l2))`` (independent of the working mode).
    Linear drive: the same definition gives acos(|y| / l2), 90 degrees minus the angle
    between link and drive. Telescopic leg: A = E2, so pi/2 everywhere (the force acts
    along the actuator). NaN where unreachable.
    """
    arch = _checked_arch(arch, "pressure_angles")
    p = checked_points(points, "pressure_angles")
    mode = checked_mode(working_mode, "pressure_angles")
    return robot_pressure_angles(Robot(arch, mode), p)


def _checked_axis(values: ArrayLike, name: str, function: str) -> FloatArray:
    requirement = "a non-empty 1-D array of finite coordinates"
    try:
        arr = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise bad_parameter(name, function, requirement, values) from None
    if arr.ndim != 1 or arr.size == 0 or not np.all(np.isfinite(arr)):
        raise bad_parameter(name, function, requirement, values)
    return arr


def conditioning_map(
    arch: Architecture, x: ArrayLike, y: ArrayLike, working_mode: tuple[int, int] = PAPER_MODE
) -> ConditioningMap:
    """Everything per point on the grid x (nx,) by y (ny,), in one vectorised pass."""
    arch = _checked_arch(arch, "conditioning_map")
    xs = _checked_axis(x, "x", "conditioning_map")
    ys = _checked_axis(y, "y", "conditioning_map")
    mode = checked_mode(working_mode, "conditioning_map")
    return robot_map(Robot(arch, mode), xs, ys)


def workspace_area(mask: ArrayLike, x: ArrayLike, y: ArrayLike) -> float:
    """Cell-count area of a (ny, nx) mask on evenly spaced x (nx,), y (ny,) nodes.

    Each True node stands for one dx x dy cell; the error is about half a cell per
    boundary node (use :func:`kappa_region_boundary` for W_kappa0's boundary and area).
    """
    function = "workspace_area"
    xs, ys = _checked_axis(x, "x", function), _checked_axis(y, "y", function)
    cells = np.asarray(mask)
    if cells.dtype != np.bool_ or cells.shape != (ys.size, xs.size):
        raise bad_parameter("mask", function, f"a bool array of shape {(ys.size, xs.size)}",
                            mask)  # fmt: skip
    for name, axis in (("x", xs), ("y", ys)):
        steps = np.diff(axis)
        if axis.size < 2 or not np.allclose(steps, steps[0], rtol=1e-6, atol=0.0) or steps[0] == 0:
            raise bad_parameter(name, function, "at least 2 evenly spaced coordinates", axis)
    dx, dy = abs(xs[1] - xs[0]), abs(ys[1] - ys[0])
    return float(np.count_nonzero(cells) * dx * dy)
