"""The inputs every spm job shares: a prescribed workspace and its sampling, design angles.

A workspace is a pointing cone of opening 2T (tilt psi2 in [0, T], every azimuth psi1)
with a torsion range psi3 in [lo, hi] (``[0, 360]`` is a full turn), sampled as
METHODS.md §3 states by default (the paper's 4 x 12 x 3 = 144 orientations, read
literally). Angles are in degrees; the kinematics converts to radians.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, field_validator

from worker.jobs.spec_base import FrozenSpec, entries

__all__ = [
    "FULL_TURN_DEG",
    "MAX_SAMPLE_COUNT",
    "AngleDeg",
    "Branch",
    "FrozenSpec",
    "GammaDeg",
    "SampleCounts",
    "WorkspaceSpec",
    "entries",
]

FULL_TURN_DEG = 360.0
#: Slack (deg) when deciding that a torsion range is a full turn.
FULL_TURN_TOLERANCE_DEG = 1e-9
#: Most samples along one of psi1, psi2, psi3 (the product is bounded by the cost limits).
MAX_SAMPLE_COUNT = 360

#: A link or pyramid angle in degrees, strictly between 0 and 180.
AngleDeg = Annotated[float, Field(gt=0, lt=180)]
#: The base pyramid's half-angle in degrees, 0 (coaxial inputs) up to 180 (excluded).
GammaDeg = Annotated[float, Field(ge=0, lt=180)]
#: The sign of (u_i x w_i) . v_i kept on every leg (eq 29: the paper's -1).
Branch = Literal[-1, 1]


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
    "Torsion range [lo, hi] of psi3 in degrees, -360 <= lo < hi <= 360 and hi - lo <= 360. "
    "[0, 360] (the default) is a full turn, with lo as the torsion origin of the samples; "
    "the paper's Table 3 uses a 30° range, [-15, 15]."
)


class WorkspaceSpec(FrozenSpec):
    """A prescribed orientation workspace: a pointing cone plus a torsion range."""

    tilt_max_deg: float = Field(
        ...,
        gt=0,
        lt=180,
        description="Half-opening T of the pointing cone in degrees (0 < T < 180): tilt psi2 "
        "in [0, T] at every azimuth. A 'cone of 120° opening' is T = 60.",
    )
    torsion_deg: Annotated[
        tuple[float, float], entries(2, "torsion_deg needs two angles [lo, hi]")
    ] = Field((0.0, FULL_TURN_DEG), description=_TORSION_DESCRIPTION)
    samples: SampleCounts = Field(
        default_factory=SampleCounts,
        description="Sample counts {'azimuth', 'tilt', 'torsion'}; the default 4 x 12 x 3 = 144 "
        "is the paper's, read literally (METHODS.md §3). Denser grids move the indices by "
        "about ±0.04 and optimum angles by 1-2°.",
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
