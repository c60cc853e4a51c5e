"""Validated inputs of the spm jobs (Bai 2010; docs/methods/spherical-parallel.md).

Every model is frozen with ``extra="forbid"`` and rejects NaN and infinity; the field
descriptions become the public JSON schema served at ``GET /v1/processes/{id}``. Angles
are in degrees. Optional inputs default to ``None`` and are resolved by properties
(:attr:`ConditioningMapSpec.map_torsions` ...), so that a spec dumped to JSON (as the job
store keeps it) validates again unchanged. The design space's inputs are in
:mod:`worker.families.spherical_parallel.design_space_spec` (re-exported here), the
optimisation's in :mod:`worker.families.spherical_parallel.optimisation_spec`.
"""

from __future__ import annotations

import math
from typing import Annotated

import numpy as np
from pydantic import Field, ValidationInfo, field_validator, model_validator

from worker.common.field_errors import field_error
from worker.families.spherical_parallel.design_space_spec import (
    MAX_BETAS,
    BetaRange,
    DesignSpaceSpec,
    IndexMapSpec,
)
from worker.families.spherical_parallel.workspace_spec import (
    ANGLE_RANGE,
    MAX_ANGLE_DEG,
    AngleDeg,
    Branch,
    FrozenSpec,
    GammaDeg,
    SampleCounts,
    WorkspaceSpec,
    entries,
)
from worker.study_kernels import in_study_template

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
    alpha1_deg: AngleDeg = Field(
        ..., description=f"Base-side link angle alpha1 in degrees, {ANGLE_RANGE}."
    )
    alpha2_deg: AngleDeg = Field(
        ..., description=f"Platform-side link angle alpha2 in degrees, {ANGLE_RANGE}."
    )
    beta_deg: AngleDeg = Field(
        ..., description=f"Half-angle beta of the mobile pyramid in degrees, {ANGLE_RANGE}."
    )
    gamma_deg: GammaDeg = Field(
        0.0,
        description=f"Half-angle gamma of the base pyramid in degrees, 0 to {MAX_ANGLE_DEG:.10g}; "
        "0 (the default) is the coaxial-input 'active ball joint' of the paper's Fig. 2.",
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
        description="The sign of (u_i x w_i) . v_i kept on every leg: -1 (the paper's eq 29) or 1.",
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
        tuple[Annotated[AzimuthTilt, entries(2, "a torsion sweep needs [psi1, psi2]")], ...] | None
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

    @model_validator(mode="after")
    def _design_reaches_the_workspace(self, info: ValidationInfo) -> ConditioningMapSpec:
        """Refuse a design whose legs close (eq 12) at no orientation of the workspace:
        every map would be empty.  Checked on the boundary-inclusive grid of the
        closed workspace (22,464 orientations, a few milliseconds), the equal-weight
        samples and, before refusing, a grid ten times denser; closure does not depend
        on the branch.  A design study's template skips it: its kernel makes the same
        check (:func:`~worker.families.spherical_parallel.kinematics.reach.reaching`)
        design by design."""
        if in_study_template(info.context):
            return self
        # lazy: the reach check (scipy) loads when inputs are validated, not with the registry
        from worker.families.spherical_parallel.kinematics import SpmDesign, Workspace
        from worker.families.spherical_parallel.kinematics.reach import ReachGrids, reaching

        ws_spec = self.workspace
        lo, hi = (math.radians(a) for a in ws_spec.torsion_deg)
        ws = Workspace(
            math.radians(ws_spec.tilt_max_deg),
            (lo, lo + 2.0 * math.pi) if ws_spec.full_turn else (lo, hi),
            ws_spec.full_turn,
        )
        design = SpmDesign.from_degrees(
            self.alpha1_deg, self.alpha2_deg, self.beta_deg, self.gamma_deg
        )
        angles = [[design.alpha1, design.alpha2, design.beta, design.gamma]]
        if bool(reaching(np.asarray(angles), ReachGrids(ws))[0]):
            return self
        raise field_error(
            self, "workspace",
            f"the design (alpha1, alpha2, beta, gamma) = ({self.alpha1_deg:g}, "
            f"{self.alpha2_deg:g}, {self.beta_deg:g}, {self.gamma_deg:g}) deg cannot reach "
            "the prescribed workspace at all: its legs close (eq 12) at none of the "
            "workspace's orientations, so every map would be empty. spm-design-space "
            "gives the link angles that reach all of it.", ws_spec.model_dump(),
        )  # fmt: skip

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
