"""Validated inputs of the planar2dof jobs (Huang et al. 2004; METHODS.md §2).

Every model is frozen with ``extra="forbid"`` and rejects NaN and infinity; the field
descriptions become the public JSON schema served at ``GET /v1/processes/{id}``.
Lengths are in the caller's ``length_unit`` (the optimisation is normalised, l1 = 1),
angles in degrees.

Mutually exclusive inputs default to ``None`` and are resolved by properties
(:attr:`OptimisationSpec.deltas` ...), so that a spec dumped to JSON (as the job store
keeps it) validates again unchanged.
"""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal

from pydantic import (
    BeforeValidator,
    Field,
    field_validator,
    model_validator,
)

from worker.jobs.spec_base import MAX_POINTS_PER_AXIS, FrozenSpec, GridSpecBase, entries

__all__ = [
    "DEFAULT_DELTA_RANGE",
    "DEFAULT_DELTA_STEP",
    "MAX_DELTA",
    "MAX_DELTAS",
    "MAX_MEAN_MESH",
    "MAX_POINTS",
    "MAX_POINTS_PER_AXIS",
    "MIN_DELTA",
    "Actuation",
    "ConditioningMapSpec",
    "GridSpec",
    "OptimisationSpec",
    "WorkingMode",
    "sweep_deltas",
]

MAX_POINTS = 1000
#: The paper's range of delta = l2/l1 (1 <= delta <= delta_max = 2.5) and its resolution.
DEFAULT_DELTA_RANGE = (1.0, 2.5)
DEFAULT_DELTA_STEP = 0.01
#: Deltas accepted anywhere (delta_range, delta): eq (12) needs l2 >= l1.
MIN_DELTA = 1.0
MAX_DELTA = 10.0
#: Most deltas one sweep may hold.
MAX_DELTAS = 10_001
MAX_MEAN_MESH = 1001
MAX_ASPECT_RATIO = 100.0

Actuation = Literal["proximal-arm", "telescopic-leg", "linear-drive"]
WorkingMode = tuple[Literal[1, -1], Literal[1, -1]]
Point = tuple[float, float]


def _signs(value: Any) -> Any:
    """working_mode entries must be +1 or -1 (one message for both entries)."""
    if isinstance(value, list | tuple):
        if len(value) != 2:
            raise ValueError(f"working_mode needs two signs [sgn1, sgn2], not {len(value)}")
        bad = [v for v in value if isinstance(v, bool) or v not in (1, -1)]
        if bad:
            raise ValueError(f"working_mode entries must be +1 or -1; got {bad[0]!r}")
    return value


class GridSpec(GridSpecBase):
    """The evaluation grid: ``points_per_axis`` nodes on each axis, ends included."""

    bounds: tuple[float, float, float, float] | None = Field(
        None,
        description=(
            "[x_min, x_max, y_min, y_max] of the grid. Default: the whole reachable "
            "workspace with a 3 % margin: |x| <= l1 + l2 - e, |y| <= l1 + l2 (proximal arms); "
            "|x|, |y| <= 3e (telescopic legs); |x| <= 2 l2, |y| <= l2 (linear drives)."
        ),
    )


_ACTUATION_DESCRIPTION = (
    "The robot of the paper's Fig. 1: 'proximal-arm' (revolute-actuated arms l1 at "
    "(±e, 0), distal links l2; the paper's example), 'telescopic-leg' (legs from pivots at "
    "(±e, 0), actuated by their length) or 'linear-drive' (sliders on a common line, "
    "carrying links l2)."
)
_E_DESCRIPTION = (
    "Half the distance between the two actuated joints (±e, 0), >= 0. Proximal-arm type: "
    "give exactly one of 'e' and 'architecture'; telescopic-leg type: required; "
    "linear-drive type: unused (the sliders share the x axis)."
)
_ARCHITECTURE_DESCRIPTION = (
    "'isotropic': e = (√2/2)(l2 - l1), the optimal architecture of eq (12) (needs "
    "l2 >= l1), isotropic at (0, -H), H = (√2/2)(l1 + l2). Give exactly one of 'e' and "
    "'architecture'."
)
_MODE_DESCRIPTION = (
    "Working mode [sgn1, sgn2], each +1 or -1: the branch of eq (2) taken by chain 1 "
    "(at (+e, 0)) and chain 2 (at (-e, 0)). The paper's mode is [1, -1], the only one "
    "with the isotropic optimum."
)
_LIMIT_MAP_DESCRIPTION = (
    "Conditioning limit 1/kappa0 in (0, 1): the map then outlines W_kappa0 = {points "
    "with 1/kappa >= 1/kappa0} and reports its boundary and area. Omit for no outline."
)
_POINTS_DESCRIPTION = (
    f"Points [[x, y], ...] (at most {MAX_POINTS}) at which 1/kappa, the pressure angles "
    "and the joint angles are reported exactly, in order."
)
_UNIT_DESCRIPTION = "Name of the length unit, used in plots and reported back."
_PLOTS_DESCRIPTION = (
    "Render the PNG/SVG plots. false: data files (CSV/NPZ) only, much faster for design "
    "sweeps."
)


class ConditioningMapSpec(FrozenSpec):
    """Inputs of ``planar2dof-conditioning-map``: 1/kappa and pressure angles on a grid."""

    actuation: Actuation = Field("proximal-arm", description=_ACTUATION_DESCRIPTION)
    l1: float = Field(
        1.0,
        gt=0,
        description="Length of the proximal links (arms), > 0; the paper normalises l1 = 1. "
        "Used by the proximal-arm type only.",
    )
    l2: float | None = Field(
        None,
        gt=0,
        description="Length of the distal links, > 0 (delta = l2/l1). Required for the "
        "proximal-arm and linear-drive types; unused by the telescopic-leg type.",
    )
    e: float | None = Field(None, ge=0, description=_E_DESCRIPTION)
    architecture: Literal["isotropic"] | None = Field(None, description=_ARCHITECTURE_DESCRIPTION)
    working_mode: Annotated[WorkingMode, BeforeValidator(_signs)] = Field(
        (1, -1), description=_MODE_DESCRIPTION
    )
    grid: GridSpec = Field(default_factory=GridSpec, description="The evaluation grid.")
    inverse_condition_limit: float | None = Field(
        None, gt=0, lt=1, description=_LIMIT_MAP_DESCRIPTION
    )
    points: tuple[Point, ...] | None = Field(
        None, min_length=1, max_length=MAX_POINTS, description=_POINTS_DESCRIPTION
    )
    length_unit: str = Field(
        "units", min_length=1, max_length=16, pattern=r"^[\w .°/-]+$", description=_UNIT_DESCRIPTION
    )
    plots: bool = Field(True, description=_PLOTS_DESCRIPTION)

    @model_validator(mode="after")
    def _architecture_fits_the_type(self) -> ConditioningMapSpec:
        if self.l2 is None and self.actuation != "telescopic-leg":
            raise ValueError(f"l2 is required for the {self.actuation} type")
        if self.actuation != "proximal-arm":
            if self.architecture is not None:
                raise ValueError(
                    "'architecture': 'isotropic' (eq 12) is the proximal-arm type's; give "
                    f"'e' for the {self.actuation} type"
                )
            if self.actuation == "telescopic-leg" and self.e is None:
                raise ValueError("the telescopic-leg type needs 'e' (its pivots are at (±e, 0))")
            return self
        if (self.e is None) == (self.architecture is None):
            raise ValueError(
                "give exactly one of 'e' (the half-distance of the actuated joints) and "
                "'architecture': 'isotropic' (e by eq 12)"
            )
        if self.architecture == "isotropic" and self.l2 is not None and self.l2 < self.l1:
            raise ValueError(
                f"architecture 'isotropic' needs l2 >= l1 (eq 12 gives e = (√2/2)(l2 - l1) "
                f"< 0 for l1 = {self.l1:g}, l2 = {self.l2:g})"
            )
        return self


_BETA_DESCRIPTION = (
    "Allowable pressure angle [beta] in degrees (0 < [beta] < 90; the paper suggests "
    "30-35). The conditioning limit 1/kappa0 then follows from eq (17) + eq (7), "
    "maximised over delta in [1, 2.5]. Give exactly one of this and "
    "'inverse_condition_limit'."
)
_LIMIT_OPT_DESCRIPTION = (
    "Conditioning limit 1/kappa0 in (0, 1), used as given. Give exactly one of this and "
    "'allowable_pressure_angle_deg'."
)
_RANGE_DESCRIPTION = (
    "[delta_min, delta_max] of the sweep of delta = l2/l1, within [1, 10] (eq 12 needs "
    f"l2 >= l1), delta_min < delta_max. Default {list(DEFAULT_DELTA_RANGE)} (the paper's). "
    "Not with 'delta'."
)
_STEP_DESCRIPTION = (
    f"Step of the delta sweep (default {DEFAULT_DELTA_STEP:g}, the paper's resolution). The "
    "sweep holds delta_min, delta_min + step, ... and delta_max. Not with 'delta'."
)
_DELTA_DESCRIPTION = (
    "Evaluate one design, delta = l2/l1 in [1, 10], instead of a sweep. S_max (for eta) "
    f"is then still taken over the paper's range {list(DEFAULT_DELTA_RANGE)} at step "
    f"{DEFAULT_DELTA_STEP:g}. Excludes 'delta_range' and 'delta_step'."
)


class OptimisationSpec(FrozenSpec):
    """Inputs of ``planar2dof-optimisation``: the paper's global design of the proximal-arm
    type (isotropic architecture eq 12, rectangle W_lambda in W_kappa0, index eta eq 13)."""

    allowable_pressure_angle_deg: float | None = Field(
        None, gt=0, lt=90, description=_BETA_DESCRIPTION
    )
    inverse_condition_limit: float | None = Field(
        None, gt=0, lt=1, description=_LIMIT_OPT_DESCRIPTION
    )
    aspect_ratio: float = Field(
        4.0,
        gt=0,
        le=MAX_ASPECT_RATIO,
        description=f"Width/height ratio lambda = b/h of the rectangle W_lambda (0 < lambda <= "
        f"{MAX_ASPECT_RATIO:g}; the paper's 4).",
    )
    delta_range: Annotated[
        tuple[float, float] | None, entries(2, "delta_range needs two values [lo, hi]")
    ] = Field(None, description=_RANGE_DESCRIPTION)
    delta_step: float | None = Field(None, gt=0, le=MAX_DELTA, description=_STEP_DESCRIPTION)
    delta: float | None = Field(None, ge=MIN_DELTA, le=MAX_DELTA, description=_DELTA_DESCRIPTION)
    mean_mesh: int = Field(
        101,
        ge=2,
        le=MAX_MEAN_MESH,
        description="Nodes per side of the M x N = mean_mesh² mesh of W_lambda over which the "
        f"mean 1/kappa (eq 14) is taken (2..{MAX_MEAN_MESH}; default 101, as METHODS.md).",
    )
    plots: bool = Field(True, description=_PLOTS_DESCRIPTION)

    @field_validator("delta_range")
    @classmethod
    def _ordered_range(cls, value: tuple[float, float] | None) -> tuple[float, float] | None:
        if value is not None:
            lo, hi = value
            if not MIN_DELTA <= lo <= MAX_DELTA or not MIN_DELTA <= hi <= MAX_DELTA:
                raise ValueError(
                    f"delta_range [{lo:g}, {hi:g}] must lie within [{MIN_DELTA:g}, "
                    f"{MAX_DELTA:g}]: the isotropic architecture of eq (12) needs "
                    "delta = l2/l1 >= 1"
                )
            if not lo < hi:
                raise ValueError(f"delta_range: lo {lo:g} must be less than hi {hi:g}")
        return value

    @model_validator(mode="after")
    def _consistent(self) -> OptimisationSpec:
        if (self.allowable_pressure_angle_deg is None) == (self.inverse_condition_limit is None):
            raise ValueError(
                "give exactly one of 'allowable_pressure_angle_deg' ([beta], the limit then "
                "follows from eq 17) and 'inverse_condition_limit' (1/kappa0)"
            )
        if self.delta is not None and (self.delta_range is not None or self.delta_step is not None):
            raise ValueError(
                "'delta' evaluates one design: give either 'delta' or a sweep "
                "('delta_range' and/or 'delta_step'), not both"
            )
        if self.delta is None:
            count = self.sweep_size
            if count > MAX_DELTAS:
                raise ValueError(
                    f"the sweep holds {count} deltas, more than {MAX_DELTAS}; use a larger "
                    "delta_step or a narrower delta_range"
                )
        return self

    @property
    def sweep_range(self) -> tuple[float, float]:
        """The delta range of the sweep (the paper's [1, 2.5] unless given)."""
        return self.delta_range if self.delta_range is not None else DEFAULT_DELTA_RANGE

    @property
    def sweep_step(self) -> float:
        """The step of the sweep (0.01 unless given)."""
        return self.delta_step if self.delta_step is not None else DEFAULT_DELTA_STEP

    @property
    def sweep_size(self) -> int:
        """How many deltas :func:`sweep_deltas` gives for the sweep's range and step."""
        lo, hi = self.sweep_range
        return _sweep_count(lo, hi, self.sweep_step)


def _sweep_count(lo: float, hi: float, step: float) -> int:
    # A step that divides the range (to rounding) ends exactly on hi; otherwise hi is added.
    intervals = (hi - lo) / step
    whole = math.floor(intervals + 1e-6)
    return whole + 1 + (0 if abs(intervals - round(intervals)) < 1e-6 else 1)


def sweep_deltas(lo: float, hi: float, step: float) -> list[float]:
    """lo, lo + step, ..., and hi (always included), rounded to 12 digits."""
    count = _sweep_count(lo, hi, step)
    values = [round(lo + i * step, 12) for i in range(count)]
    values[-1] = hi
    return values
