"""Validated inputs of the spm jobs (Bai 2010; METHODS.md §3).

Every model is frozen with ``extra="forbid"`` and rejects NaN and infinity; the field
descriptions become the public JSON schema served at ``GET /v1/processes/{id}``. Angles
are in degrees. Optional inputs default to ``None`` and are resolved by properties
(:attr:`ConditioningMapSpec.map_torsions` ...), so that a spec dumped to JSON (as the job
store keeps it) validates again unchanged. The optimisation's inputs are in
:mod:`worker.jobs.spm.optimisation_spec`.
"""

from __future__ import annotations

import math
from typing import Annotated, Any

from pydantic import (
    Discriminator,
    Field,
    Tag,
    ValidationInfo,
    field_validator,
    model_validator,
)

from worker.jobs.spm.workspace_spec import (
    AngleDeg,
    Branch,
    FrozenSpec,
    GammaDeg,
    SampleCounts,
    WorkspaceSpec,
    entries,
)

__all__ = [
    "MAX_BETAS",
    "MAX_ORIENTATIONS",
    "SWEEP_POINTS",
    "BetaRange",
    "ConditioningMapSpec",
    "DesignSpaceSpec",
    "IndexMapSpec",
    "MapGrid",
    "SampleCounts",
    "WorkspaceSpec",
]

MAX_ORIENTATIONS = 1000
MAX_MAP_PANELS = 6
MAX_SWEEPS = 6
MAX_BETAS = 721
#: Points of a torsion sweep: psi3 from 0 to 360° every 1° (ends included).
SWEEP_POINTS = 361
#: psi1 of the paper's Fig. 7 (its three curves are at psi2 = 15, 30, 45 in a 45° cone).
FIG_7_AZIMUTH_DEG = 35.0

Orientation = tuple[float, float, float]
AzimuthTilt = tuple[float, float]


def _check_psi(where: str, psi1: float, psi2: float, psi3: float | None = None) -> None:
    if not -360.0 <= psi1 <= 360.0:
        raise ValueError(f"{where}: azimuth psi1 {psi1:g} is outside [-360, 360]")
    if not 0.0 <= psi2 <= 180.0:
        raise ValueError(f"{where}: tilt psi2 {psi2:g} is outside [0, 180]")
    if psi3 is not None and not -360.0 <= psi3 <= 360.0:
        raise ValueError(f"{where}: torsion psi3 {psi3:g} is outside [-360, 360]")


class _Design(FrozenSpec):
    alpha1_deg: AngleDeg = Field(..., description="Base-side link angle alpha1 (0 < . < 180).")
    alpha2_deg: AngleDeg = Field(
        ..., description="Platform-side link angle alpha2 (0 < . < 180)."
    )
    beta_deg: AngleDeg = Field(
        ..., description="Half-angle beta of the mobile pyramid (0 < . < 180)."
    )
    gamma_deg: GammaDeg = Field(
        0.0,
        description="Half-angle gamma of the base pyramid (0 <= . < 180); 0 (the default) "
        "is the coaxial-input 'active ball joint' of the paper's Fig. 2.",
    )


class MapGrid(FrozenSpec):
    """The azimuth x tilt grid of the 1/kappa maps (the paper's Fig. 6 style)."""

    azimuth: int = Field(
        121, ge=5, le=721, description="Azimuths psi1 over [0, 360], ends included (default "
        "121: every 3°)."
    )  # fmt: skip
    tilt: int = Field(
        41, ge=2, le=361, description="Tilts psi2 over [0, T], ends included (default 41)."
    )


class ConditioningMapSpec(_Design):
    """Inputs of ``spm-conditioning-map``: inverse kinematics and 1/kappa over a workspace."""

    workspace: WorkspaceSpec = Field(..., description="The prescribed workspace and its sampling.")
    branch: Branch = Field(
        -1,
        description="The sign of (u_i x w_i) . v_i kept on every leg: -1 (the paper's eq 29) "
        "or 1.",
    )
    orientations: (
        tuple[Annotated[Orientation, entries(3, "an orientation needs [psi1, psi2, psi3]")], ...]
        | None
    ) = Field(
        None,
        min_length=1,
        max_length=MAX_ORIENTATIONS,
        description=f"Orientations [[psi1, psi2, psi3], ...] in degrees (at most "
        f"{MAX_ORIENTATIONS}; azimuth and torsion in [-360, 360], tilt in [0, 180]) at which "
        "the joint angles, kappa and 1/kappa are reported exactly, in order.",
    )
    map_torsions_deg: tuple[float, ...] | None = Field(
        None,
        min_length=1,
        max_length=MAX_MAP_PANELS,
        description="Torsions psi3 (deg, in [-360, 360]) of the 1/kappa maps over tilt x "
        "azimuth, one panel each (at most 6). Default: lo, lo + 30, lo + 60 for a full turn; "
        "lo, the mid-point and hi for a limited range.",
    )
    map_grid: MapGrid = Field(default_factory=MapGrid, description="Resolution of the maps.")
    torsion_sweeps: (
        tuple[Annotated[AzimuthTilt, entries(2, "a torsion sweep needs [psi1, psi2]")], ...]
        | None
    ) = Field(
        None,
        min_length=1,
        max_length=MAX_SWEEPS,
        description="[[psi1, psi2], ...] in degrees (at most 6) at which 1/kappa is traced "
        f"along a full torsion turn (the paper's Fig. 7). Default: psi1 = "
        f"{FIG_7_AZIMUTH_DEG:g} at psi2 = T/3, 2T/3 and T (the paper's 15, 30, 45 for T = 45).",
    )
    plots: bool = Field(
        True, description="Render the PNG/SVG plots. false: data files (CSV/NPZ) only."
    )

    @field_validator("orientations")
    @classmethod
    def _orientations_in_range(
        cls, value: tuple[Orientation, ...] | None
    ) -> tuple[Orientation, ...] | None:
        for index, (psi1, psi2, psi3) in enumerate(value or ()):
            _check_psi(f"orientations[{index}]", psi1, psi2, psi3)
        return value

    @field_validator("map_torsions_deg")
    @classmethod
    def _torsions_in_range(cls, value: tuple[float, ...] | None) -> tuple[float, ...] | None:
        for index, psi3 in enumerate(value or ()):
            if not -360.0 <= psi3 <= 360.0:
                raise ValueError(f"map_torsions_deg[{index}]: {psi3:g} is outside [-360, 360]")
        return value

    @field_validator("torsion_sweeps")
    @classmethod
    def _sweeps_in_range(
        cls, value: tuple[AzimuthTilt, ...] | None
    ) -> tuple[AzimuthTilt, ...] | None:
        for index, (psi1, psi2) in enumerate(value or ()):
            _check_psi(f"torsion_sweeps[{index}]", psi1, psi2)
        return value

    @property
    def map_torsions(self) -> tuple[float, ...]:
        """The torsions (deg) of the map panels, defaults filled in."""
        if self.map_torsions_deg is not None:
            return self.map_torsions_deg
        lo, hi = self.workspace.torsion_deg
        if self.workspace.full_turn:
            return (lo, lo + 30.0, lo + 60.0)
        return (lo, 0.5 * (lo + hi), hi)

    @property
    def sweeps(self) -> tuple[AzimuthTilt, ...]:
        """The [psi1, psi2] (deg) of the torsion sweeps, defaults filled in."""
        if self.torsion_sweeps is not None:
            return self.torsion_sweeps
        tilt = self.workspace.tilt_max_deg
        return tuple((FIG_7_AZIMUTH_DEG, tilt * k / 3.0) for k in (1, 2, 3))


class BetaRange(FrozenSpec):
    """beta = start, start + step, ... up to stop (included when it lands on a step)."""

    start: AngleDeg = Field(..., description="First beta in degrees (0 < . < 180).")
    stop: AngleDeg = Field(..., description="Last beta in degrees (0 < . < 180), >= start.")
    step: float = Field(..., gt=0, le=180, description="Step in degrees (> 0).")

    @model_validator(mode="after")
    def _ordered(self) -> BetaRange:
        if self.stop < self.start:
            raise ValueError(f"stop {self.stop:g} must not be less than start {self.start:g}")
        if self.count > MAX_BETAS:
            raise ValueError(
                f"the range holds {self.count} betas, more than {MAX_BETAS}; use a larger step"
            )
        return self

    @property
    def count(self) -> int:
        return math.floor((self.stop - self.start) / self.step + 1e-9) + 1

    def values(self) -> tuple[float, ...]:
        """The betas in degrees, rounded to 12 digits."""
        return tuple(round(self.start + i * self.step, 12) for i in range(self.count))


def _beta_kind(value: Any) -> str | None:
    if isinstance(value, dict | BetaRange):
        return "range"
    if isinstance(value, list | tuple):
        return "list"
    return None


BetaSelection = Annotated[
    Annotated[tuple[AngleDeg, ...], Tag("list")] | Annotated[BetaRange, Tag("range")],
    Discriminator(
        _beta_kind,
        custom_error_type="beta_selection",
        custom_error_message="beta_deg must be a list of angles [b1, b2, ...] or a range "
        "{'start', 'stop', 'step'}, in degrees",
    ),
]


class IndexMapSpec(FrozenSpec):
    """The conditioning index over one beta's design space (the paper's Fig. 6)."""

    beta_deg: AngleDeg = Field(..., description="The beta (deg) whose rectangle is mapped.")
    points_per_side: int = Field(
        31,
        ge=3,
        le=101,
        description="Designs per side of the (s, t) grid spanning the rectangle, "
        "a1 - a2 = s D1, a1 + a2 - 180 = t D2, s, t in [-1, 1] (default 31).",
    )
    branch: Branch = Field(-1, description="The branch sign (eq 29; the paper's -1).")


class DesignSpaceSpec(FrozenSpec):
    """Inputs of ``spm-design-space``: the feasible (alpha1, alpha2) rectangle per beta."""

    workspace: WorkspaceSpec = Field(
        ...,
        description="The prescribed workspace. The design space holds on the continuous "
        "workspace; its samples are used only by 'index_map'.",
    )
    identical_platforms: bool = Field(
        False, description="gamma = beta for every beta (the paper's Table 3). Not with gamma_deg."
    )
    gamma_deg: GammaDeg | None = Field(
        None,
        description="Base pyramid half-angle gamma (deg, default 0). Not with "
        "identical_platforms.",
    )
    beta_deg: BetaSelection = Field(
        ...,
        description="The betas (deg): a list [b1, b2, ...] (at most 721) or a range "
        "{'start', 'stop', 'step'}.",
    )
    index_map: IndexMapSpec | None = Field(
        None,
        description="Also map mean(1/kappa^2) (eq 28) over the workspace samples across "
        "one beta's rectangle (the paper's Fig. 6). Omit for none.",
    )
    plots: bool = Field(True, description="Render the PNG/SVG plots. false: data files only.")

    @field_validator("beta_deg")
    @classmethod
    def _bounded_list(cls, value: tuple[float, ...] | BetaRange) -> tuple[float, ...] | BetaRange:
        if isinstance(value, tuple) and not 1 <= len(value) <= MAX_BETAS:
            raise ValueError(f"beta_deg holds {len(value)} angles; give 1 to {MAX_BETAS}")
        return value

    @field_validator("gamma_deg")
    @classmethod
    def _one_gamma(cls, value: float | None, info: ValidationInfo) -> float | None:
        if value is not None and info.data.get("identical_platforms"):
            raise ValueError(
                "gamma_deg and identical_platforms exclude each other: with identical "
                "platforms gamma = beta for every beta"
            )
        return value

    @property
    def betas(self) -> tuple[float, ...]:
        """The betas in degrees, in the order given (a range: increasing)."""
        value = self.beta_deg
        return value.values() if isinstance(value, BetaRange) else value

    def gamma_for(self, beta: float) -> float:
        """gamma (deg) at ``beta``: beta with identical platforms, else gamma_deg or 0."""
        if self.identical_platforms:
            return beta
        return 0.0 if self.gamma_deg is None else self.gamma_deg
