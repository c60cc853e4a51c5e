"""Design and workspace records of spherical parallel manipulators, and their input checks.

Bai (2010), restated in docs/methods/spherical-parallel.md. Both records validate themselves on
construction (the boundary); every function taking them trusts them. Angles are in
radians; :meth:`SpmDesign.from_degrees` and :meth:`SpmDesign.degrees` are conveniences
for callers that speak degrees.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

from numpy.typing import ArrayLike

from worker.common.arrays import BoolArray as BoolArray
from worker.common.arrays import FloatArray as FloatArray
from worker.common.arrays import checked_array
from worker.common.parameter_errors import bad_parameter

__all__ = [
    "BoolArray",
    "FloatArray",
    "SpmDesign",
    "Workspace",
    "checked_branch",
    "checked_design",
    "checked_orientations",
    "checked_workspace",
]

_FULL_TURN = 2.0 * math.pi
#: Slack allowed when checking that a full-turn torsion range spans exactly 2 pi.
_SPAN_TOLERANCE = 1e-9


def _is_real(value: object) -> bool:
    return isinstance(value, numbers.Real) and math.isfinite(float(value))


@dataclass(frozen=True)
class SpmDesign:
    """Design parameters (rad) of a spherical parallel manipulator.

    alpha1: base-side link angle, in (0, pi); alpha2: platform-side link angle, in
    (0, pi); beta: half-angle of the mobile pyramid, in (0, pi); gamma: half-angle of the
    base pyramid, in [0, pi) (gamma = 0 is the coaxial "active ball joint" of Fig. 2).
    Values are stored as Python floats.
    """

    alpha1: float
    alpha2: float
    beta: float
    gamma: float = 0.0

    def __post_init__(self) -> None:
        for name in ("alpha1", "alpha2", "beta"):
            value = getattr(self, name)
            if not (_is_real(value) and 0.0 < float(value) < math.pi):
                raise bad_parameter(name, "SpmDesign", "a finite angle in (0, pi) rad", value)
            object.__setattr__(self, name, float(value))
        if not (_is_real(self.gamma) and 0.0 <= float(self.gamma) < math.pi):
            raise bad_parameter("gamma", "SpmDesign", "a finite angle in [0, pi) rad", self.gamma)
        object.__setattr__(self, "gamma", float(self.gamma))

    @classmethod
    def from_degrees(
        cls, alpha1: float, alpha2: float, beta: float, gamma: float = 0.0
    ) -> SpmDesign:
        """The design with the given angles in degrees."""
        return cls(*(math.radians(a) for a in (alpha1, alpha2, beta, gamma)))

    def degrees(self) -> tuple[float, float, float, float]:
        """(alpha1, alpha2, beta, gamma) in degrees."""
        return (
            math.degrees(self.alpha1),
            math.degrees(self.alpha2),
            math.degrees(self.beta),
            math.degrees(self.gamma),
        )


@dataclass(frozen=True)
class Workspace:
    """A prescribed orientation workspace (rad): a pointing cone plus a torsion range.

    tilt_max: the cone's half-opening T, in (0, pi) (a "cone of 120° opening" is
    T = 60°): psi2 in [0, T], psi1 over a full turn. torsion: (lo, hi), psi3 in
    [lo, hi]. full_turn: psi3 over a full turn; then ``torsion`` must be
    ``(lo, lo + 2 pi)`` and ``lo`` is the torsion origin of the samples (the default is
    ``(0, 2 pi)``). A limited range needs ``full_turn=False`` and ``lo <= hi < lo + 2 pi``.
    """

    tilt_max: float
    torsion: tuple[float, float] = (0.0, _FULL_TURN)
    full_turn: bool = True

    def __post_init__(self) -> None:
        tilt = self.tilt_max
        if not (_is_real(tilt) and 0.0 < float(tilt) < math.pi):
            raise bad_parameter("tilt_max", "Workspace", "a finite angle in (0, pi) rad", tilt)
        object.__setattr__(self, "tilt_max", float(tilt))
        torsion = self.torsion
        if not (
            isinstance(torsion, tuple)
            and len(torsion) == 2
            and all(_is_real(v) for v in torsion)
            and float(torsion[0]) <= float(torsion[1])
        ):
            raise bad_parameter(
                "torsion", "Workspace", "a tuple (lo, hi) of finite angles (rad), lo <= hi", torsion
            )
        lo, hi = float(torsion[0]), float(torsion[1])
        if self.full_turn and abs(hi - lo - _FULL_TURN) > _SPAN_TOLERANCE:
            raise bad_parameter(
                "torsion", "Workspace", "(lo, lo + 2 pi) when full_turn is True", torsion
            )
        if not self.full_turn and hi - lo >= _FULL_TURN - _SPAN_TOLERANCE:
            raise bad_parameter(
                "torsion", "Workspace", "shorter than a full turn when full_turn is False", torsion
            )
        object.__setattr__(self, "torsion", (lo, hi))
        object.__setattr__(self, "full_turn", bool(self.full_turn))


def checked_branch(branch: object, function: str) -> int:
    """The branch sign as an int, -1 or +1, or a ValueError naming it."""
    valid = isinstance(branch, numbers.Integral) and not isinstance(branch, bool)
    if not valid or branch not in (-1, 1):
        raise bad_parameter(
            "branch", function, "-1 or 1 (the sign of (u_i x w_i) . v_i, eq 29)", branch
        )
    return int(branch)


def checked_orientations(value: ArrayLike, parameter: str, function: str) -> FloatArray:
    """Finite orientations psi = (psi1, psi2, psi3) rad of shape (..., 3), as float64."""
    return checked_array(
        value,
        parameter,
        function,
        "finite angles (psi1, psi2, psi3) in rad of shape (..., 3)",
        lambda a: a.ndim >= 1 and a.shape[-1] == 3,
    )


def checked_design(design: object, function: str) -> SpmDesign:
    if not isinstance(design, SpmDesign):
        raise bad_parameter("design", function, "an SpmDesign", design)
    return design


def checked_workspace(ws: object, function: str) -> Workspace:
    if not isinstance(ws, Workspace):
        raise bad_parameter("ws", function, "a Workspace", ws)
    return ws
