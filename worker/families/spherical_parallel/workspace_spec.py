"""The inputs every spm job shares: a prescribed workspace and its sampling, design angles.

A workspace is a pointing cone of opening 2T (tilt psi2 in [0, T], every azimuth psi1)
with a torsion range psi3 in [lo, hi] (``[0, 360]`` is a full turn), sampled as
docs/methods/spherical-parallel.md states by default (the paper's 4 x 12 x 3 = 144
orientations, read literally). Angles are in degrees; the kinematics converts to
radians. Link and pyramid angles and the cone's half-opening stay at least
:data:`ANGLE_MARGIN_DEG` away from 0 and 180 (where a leg or the cone degenerates and
the conversion to radians can round onto the excluded end); a torsion range spans at
least ``MIN_STEP`` (1e-6) degrees.
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import Field, field_validator

from worker.common.numeric_ranges import MIN_STEP
from worker.common.specs import FrozenSpec, entries

__all__ = [
    "ANGLE_MARGIN_DEG",
    "ANGLE_RANGE",
    "FULL_TURN_DEG",
    "MAX_ANGLE_DEG",
    "MAX_SAMPLE_COUNT",
    "AngleDeg",
    "Branch",
    "FrozenSpec",
    "GammaDeg",
    "SampleCounts",
    "WorkspaceSpec",
    "entries",
    "narrower_than",
]

FULL_TURN_DEG = 360.0
#: Slack (deg) when deciding that a torsion range is a full turn.
FULL_TURN_TOLERANCE_DEG = 1e-9
#: Most samples along one of psi1, psi2, psi3 (the product is bounded by the cost limits).
MAX_SAMPLE_COUNT = 360

#: How close (deg) a link or pyramid angle, or the cone's half-opening, may come to the
#: degenerate 0 and 180.
ANGLE_MARGIN_DEG = 1e-6
MAX_ANGLE_DEG = 180.0 - ANGLE_MARGIN_DEG
#: The range of link and pyramid angles, in words.
ANGLE_RANGE = f"in [{ANGLE_MARGIN_DEG:g}, 180 - {ANGLE_MARGIN_DEG:g}]"
#: A link or pyramid angle in degrees, in [1e-6, 180 - 1e-6].
AngleDeg = Annotated[float, Field(ge=ANGLE_MARGIN_DEG, le=MAX_ANGLE_DEG)]
#: The base pyramid's half-angle in degrees, 0 (coaxial inputs) up to 180 - 1e-6.
GammaDeg = Annotated[float, Field(ge=0, le=MAX_ANGLE_DEG)]
#: The sign of (u_i x w_i) . v_i kept on every leg (eq 29: the paper's -1).
Branch = Literal[-1, 1]


def narrower_than(lo: float, hi: float, width: float) -> bool:
    """Whether [lo, hi] spans less than ``width`` beyond the rounding of its ends (a range
    typed as [lo, lo + width] is not)."""
    return hi - lo < width - 2.0 * math.ulp(max(abs(lo), abs(hi)))


class SampleCounts(FrozenSpec):
    """How many equal-weight samples along azimuth psi1, tilt psi2 and torsion psi3."""

    azimuth: int = Field(
        4,
        ge=1,
        le=MAX_SAMPLE_COUNT,
        description="Azimuths psi1 = 360 k / azimuth, k = 0.. (default 4: 0, 90, 180, 270).",
    )
    tilt: int = Field(
        12,
        ge=1,
        le=MAX_SAMPLE_COUNT,
        description="Tilts psi2 at the mid-points of equal-volume cells of [0, T]: "
        "psi2_k = acos(1 - (1 - cos T)(k - 1/2)/tilt), k = 1..tilt (default 12).",
    )
    torsion: int = Field(
        3,
        ge=1,
        le=MAX_SAMPLE_COUNT,
        description="Torsions psi3: evenly spaced over a full turn from lo (default 3: lo, "
        "lo + 120, lo + 240), or evenly spaced over a limited [lo, hi] with both ends "
        "included (the mid-point if 1).",
    )

    @property
    def count(self) -> int:
        """azimuth x tilt x torsion."""
        return self.azimuth * self.tilt * self.torsion


_TORSION_DESCRIPTION = (
    f"Torsion range [lo, hi] of psi3 in degrees, -360 <= lo < hi <= 360 and {MIN_STEP:g} <= "
    "hi - lo <= 360. "
    "[0, 360] (the default) is a full turn, with lo as the torsion origin of the samples; "
    "the paper's Table 3 uses a 30° range, [-15, 15]."
)


class WorkspaceSpec(FrozenSpec):
    """A prescribed orientation workspace: a pointing cone plus a torsion range."""

    tilt_max_deg: float = Field(
        ...,
        ge=ANGLE_MARGIN_DEG,
        le=MAX_ANGLE_DEG,
        description="Half-opening T of the pointing cone in degrees, in [1e-6, 180 - 1e-6]: "
        "tilt psi2 in [0, T] at every azimuth. A 'cone of 120° opening' is T = 60.",
    )
    torsion_deg: Annotated[
        tuple[float, float], entries(2, "torsion_deg needs two angles [lo, hi]")
    ] = Field((0.0, FULL_TURN_DEG), description=_TORSION_DESCRIPTION)
    samples: SampleCounts = Field(
        default_factory=SampleCounts,
        description="Sample counts {'azimuth', 'tilt', 'torsion'}; the default 4 x 12 x 3 = 144 "
        "is the paper's, read literally (docs/methods/spherical-parallel.md). Denser grids "
        "move the indices by about ±0.04 and optimum angles by 1-2°.",
    )

    @field_validator("torsion_deg")
    @classmethod
    def _ordered_torsion(cls, value: tuple[float, float]) -> tuple[float, float]:
        lo, hi = value
        for name, angle in (("lo", lo), ("hi", hi)):
            if not -FULL_TURN_DEG <= angle <= FULL_TURN_DEG:
                raise ValueError(f"torsion_deg: {name} {angle:g} is outside [-360, 360]")
        if not lo < hi:
            raise ValueError(f"torsion_deg: lo {lo:g} must be less than hi {hi:g}")
        if narrower_than(lo, hi, MIN_STEP):
            raise ValueError(
                f"torsion_deg: the range [{lo:.10g}, {hi:.10g}] spans {hi - lo:.6g}°, less "
                f"than {MIN_STEP:g}°; give a wider range"
            )
        if hi - lo > FULL_TURN_DEG + FULL_TURN_TOLERANCE_DEG:
            raise ValueError(
                f"torsion_deg: hi - lo = {hi - lo:g} exceeds a full turn (360); use [lo, lo + 360]"
            )
        return value

    @property
    def full_turn(self) -> bool:
        """Whether psi3 covers a full turn (hi - lo = 360)."""
        lo, hi = self.torsion_deg
        return hi - lo >= FULL_TURN_DEG - FULL_TURN_TOLERANCE_DEG
