"""Validated inputs of ``spm-design-space`` (Bai 2010 §4, eqs 14-19; see
docs/methods/spherical-parallel.md).

The betas (a list, or a range {start, stop, step} whose count is bounded without
dividing by the step), the base pyramid, and an optional index map over one beta's
rectangle. Angles in degrees; frozen, ``extra="forbid"``, finite floats only.
"""

from __future__ import annotations

import math
from typing import Annotated, Any

from pydantic import Discriminator, Field, Tag, ValidationInfo, field_validator

from worker.common.numeric_ranges import MIN_STEP
from worker.families.spherical_parallel.workspace_spec import (
    ANGLE_RANGE,
    MAX_ANGLE_DEG,
    AngleDeg,
    Branch,
    FrozenSpec,
    GammaDeg,
    WorkspaceSpec,
)

__all__ = ["MAX_BETAS", "BetaRange", "BetaSelection", "DesignSpaceSpec", "IndexMapSpec"]

MAX_BETAS = 721


class BetaRange(FrozenSpec):
    """beta = start, start + step, ... up to stop (included when it lands on a step)."""

    start: AngleDeg = Field(..., description=f"First beta in degrees, {ANGLE_RANGE}.")
    stop: AngleDeg = Field(
        ..., description=f"Last beta in degrees, {ANGLE_RANGE}, not less than start."
    )
    step: float = Field(
        ...,
        ge=MIN_STEP,
        le=180,
        description=f"Step in degrees, from {MIN_STEP:g} to 180; the range holds at most "
        f"{MAX_BETAS} betas.",
    )

    @field_validator("stop")
    @classmethod
    def _ordered(cls, stop: float, info: ValidationInfo) -> float:
        start = info.data.get("start")
        if start is not None and stop < start:
            raise ValueError(f"stop {stop:g} must not be less than start {start:g}")
        return stop

    @field_validator("step")
    @classmethod
    def _bounded_count(cls, step: float, info: ValidationInfo) -> float:
        start, stop = info.data.get("start"), info.data.get("stop")
        if start is not None and stop is not None and stop - start >= step * (MAX_BETAS - 1e-9):
            # compared, not divided: a step of 5e-324 would overflow the count
            raise ValueError(
                f"the range [{start:g}, {stop:g}] at step {step:g} holds more than "
                f"{MAX_BETAS} betas; use a larger step"
            )
        return step

    @property
    def count(self) -> int:
        return math.floor((self.stop - self.start) / self.step + 1e-9) + 1

    def values(self) -> tuple[float, ...]:
        """The betas in degrees, rounded to 12 digits."""
        return tuple(round(self.start + i * self.step, 12) for i in range(self.count))


def _beta_kind(value: Any) -> str | None:
    # Capitalised tags: the service's field paths leave them out (inputs.beta_deg.step).
    if isinstance(value, dict | BetaRange):
        return "BetaRange"
    if isinstance(value, list | tuple):
        return "BetaList"
    return None


BetaSelection = Annotated[
    Annotated[tuple[AngleDeg, ...], Tag("BetaList")] | Annotated[BetaRange, Tag("BetaRange")],
    Discriminator(
        _beta_kind,
        custom_error_type="beta_selection",
        custom_error_message="beta_deg must be a list of angles [b1, b2, ...] or a range "
        "{'start', 'stop', 'step'}, in degrees",
    ),
]


class IndexMapSpec(FrozenSpec):
    """The conditioning index over one beta's design space (the paper's Fig. 6)."""

    beta_deg: AngleDeg = Field(
        ..., description=f"The beta (deg, {ANGLE_RANGE}) whose rectangle is mapped."
    )
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
        description=f"Base pyramid half-angle gamma (deg, 0 to {MAX_ANGLE_DEG:.10g}; default 0). "
        "Not with identical_platforms.",
    )
    beta_deg: BetaSelection = Field(
        ...,
        description=f"The betas in degrees, each {ANGLE_RANGE}: a list [b1, b2, ...] (at most "
        f"{MAX_BETAS}) or a range {{'start', 'stop', 'step'}} (step at least {MIN_STEP:g}).",
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
