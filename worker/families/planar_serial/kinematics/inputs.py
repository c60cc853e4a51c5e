"""Input normalisation of the three-link planar arm modules (once, at every public entry).

Each check returns its argument as float64 data (a copy only if needed) or raises a
ValueError naming the parameter, the function and what it must be.  Links checked
once travel as an :class:`Arm`, which every check trusts: a job builds one from its
validated inputs and passes it down, so its kinematics never check the links again.
The array aliases and :func:`~worker.common.arrays.checked_array` are every family's
(:mod:`worker.common.arrays`), re-exported here for this family's modules.
"""

from __future__ import annotations

import math
import numbers
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from worker.common.arrays import BoolArray, FloatArray, checked_array
from worker.common.parameter_errors import bad_parameter

__all__ = [
    "Arm",
    "BoolArray",
    "FloatArray",
    "LinkLengths",
    "Links",
    "checked_array",
    "checked_joint_limits",
    "checked_link_rows",
    "checked_links",
    "checked_points",
    "sample_count",
]

Links = tuple[float, float, float]
#: Link lengths as three numbers, or as three columns (m,) that go with m points (one
#: design per point: the batched-design paths of the exact d_z).
LinkLengths = Links | tuple[FloatArray, FloatArray, FloatArray]


class Arm(NamedTuple):
    """Links (l1, l2, l3) checked once: finite and positive.  A tuple of three floats
    (it goes wherever :data:`Links` does) that every check of this package trusts;
    build it with :meth:`checked` (or, from inputs a validated model already checked,
    directly)."""

    l1: float
    l2: float
    l3: float

    @classmethod
    def checked(cls, links: ArrayLike, function: str = "Arm") -> Arm:
        """The links checked (ValueError naming ``function`` if they are not)."""
        return cls(*checked_links(links, function))


def checked_links(links: ArrayLike, function: str) -> Links:
    if isinstance(links, Arm):
        return links
    arr = checked_array(
        links,
        "links",
        function,
        "three finite positive lengths (l1, l2, l3)",
        lambda a: a.shape == (3,) and bool(np.all(a > 0)),
    )
    return float(arr[0]), float(arr[1]), float(arr[2])


def checked_link_rows(links: ArrayLike, function: str) -> FloatArray:
    """Designs ``(..., 3)``: one (l1, l2, l3) per leading index, or one design (3,)."""
    if isinstance(links, Arm):
        return np.asarray(links, dtype=np.float64)
    return checked_array(
        links,
        "links",
        function,
        "finite positive lengths (l1, l2, l3) of shape (3,) or (..., 3)",
        lambda a: a.ndim >= 1 and a.shape[-1] == 3 and bool(np.all(a > 0)),
    )


def checked_points(points: ArrayLike, function: str) -> FloatArray:
    return checked_array(
        points,
        "points",
        function,
        "finite (x, y) coordinates of shape (..., 2)",
        lambda a: a.ndim >= 1 and a.shape[-1] == 2,
    )


def sample_count(step: float, function: str) -> int:
    if not (isinstance(step, numbers.Real) and step > 0 and math.isfinite(2.0 * math.pi / step)):
        raise bad_parameter("step", function, "a finite positive angle in radians", step)
    return max(1, round(2.0 * math.pi / float(step)))


def checked_joint_limits(joint_limits: ArrayLike, function: str) -> FloatArray:
    return checked_array(
        joint_limits,
        "joint_limits",
        function,
        "(3, 2) radians [[lo, hi], ...] with -pi <= lo <= hi <= pi",
        lambda a: (
            a.shape == (3, 2)
            and bool(np.all((-np.pi <= a[:, 0]) & (a[:, 0] <= a[:, 1]) & (a[:, 1] <= np.pi)))
        ),
    )
