"""Validated inputs of ``planar2dof-optimisation`` (Huang et al. 2004 §III-C; see
docs/methods/planar-parallel.md).

The proximal-arm robot normalised to l1 = 1, so every input is a ratio or an angle: delta
= l2/l1 in [1, 10], lambda = b/h in [1/100, 100], [beta] in degrees, 1/kappa0. Frozen,
``extra="forbid"``, finite floats only; the sweep's defaults are resolved by properties
(:attr:`OptimisationSpec.sweep_range` ...) so that a dumped spec validates again unchanged.
"""

from __future__ import annotations

import math
from typing import Annotated

from pydantic import Field, field_validator, model_validator

from worker.common.field_errors import field_error
from worker.common.numeric_ranges import MIN_STEP
from worker.common.specs import FrozenSpec, entries

__all__ = [
    "DEFAULT_DELTA_RANGE",
    "DEFAULT_DELTA_STEP",
    "MAX_ASPECT_RATIO",
    "MAX_DELTA",
    "MAX_DELTAS",
    "MAX_MEAN_MESH",
    "MAX_PRESSURE_ANGLE_DEG",
    "MIN_ASPECT_RATIO",
    "MIN_DELTA",
    "MIN_INVERSE_CONDITION_LIMIT",
    "MIN_PRESSURE_ANGLE_DEG",
    "PLOTS_DESCRIPTION",
    "OptimisationSpec",
    "eq17_reach",
    "sweep_deltas",
]

#: The paper's range of delta = l2/l1 (1 <= delta <= delta_max = 2.5) and its resolution.
DEFAULT_DELTA_RANGE = (1.0, 2.5)
DEFAULT_DELTA_STEP = 0.01
#: Deltas accepted anywhere (delta_range, delta): eq (12) needs l2 >= l1.
MIN_DELTA = 1.0
MAX_DELTA = 10.0
#: Most deltas one sweep may hold.
MAX_DELTAS = 10_001
MAX_MEAN_MESH = 1001
#: lambda = b/h either way: a rectangle at most 100 times wider than high, or higher.
MAX_ASPECT_RATIO = 100.0
MIN_ASPECT_RATIO = 1.0 / MAX_ASPECT_RATIO
#: Least conditioning limit 1/kappa0: below it W_kappa0 is the whole reachable workspace
#: to rounding (and the telescopic legs' search box, which grows as 1/limit, leaves the
#: coordinate range).
MIN_INVERSE_CONDITION_LIMIT = 1e-6
#: [beta] in degrees: below 1° eq (17)'s point sits where the links fold and 1/kappa0 is
#: lost in rounding; 90° (excluded) would ask for 1/kappa0 = 1, a single point.
MIN_PRESSURE_ANGLE_DEG = 1.0
MAX_PRESSURE_ANGLE_DEG = 90.0
#: delta_range must start at least this far below eq (17)'s reach (1/kappa0 then >= 1e-3).
EQ17_REACH_MARGIN = 1e-6

PLOTS_DESCRIPTION = (
    "Render the PNG/SVG plots. false: data files (CSV/NPZ) only, much faster for design sweeps."
)
_BETA_DESCRIPTION = (
    f"Allowable pressure angle [beta] in degrees, from {MIN_PRESSURE_ANGLE_DEG:g} up to (not "
    f"including) {MAX_PRESSURE_ANGLE_DEG:g} (the paper suggests 30-35; below 1° eq 17's "
    "point sits where the links fold). The conditioning limit 1/kappa0 then follows from "
    "eq (17) + eq (7), maximised over the swept deltas (over [1, 2.5] for a single delta) "
    "where eq (17)'s point is in reach, delta < delta_+([beta]) (2.62 to 3.73): a "
    "delta_range must start below it. Give exactly one of this and 'inverse_condition_limit'."
)
_LIMIT_OPT_DESCRIPTION = (
    f"Conditioning limit 1/kappa0, at least {MIN_INVERSE_CONDITION_LIMIT:g} and less than 1, "
    "used as given. Give exactly one of this and 'allowable_pressure_angle_deg'."
)
_RANGE_DESCRIPTION = (
    f"[delta_min, delta_max] of the sweep of delta = l2/l1, within [{MIN_DELTA:g}, "
    f"{MAX_DELTA:g}] (eq 12 needs l2 >= l1), delta_min < delta_max. Default "
    f"{list(DEFAULT_DELTA_RANGE)} (the paper's). Not with 'delta'."
)
_STEP_DESCRIPTION = (
    f"Step of the delta sweep, from {MIN_STEP:g} to {MAX_DELTA:g} (default "
    f"{DEFAULT_DELTA_STEP:g}, the paper's resolution); the sweep holds delta_min, "
    f"delta_min + step, ... and delta_max, at most {MAX_DELTAS:,} deltas. Not with 'delta'."
)
_DELTA_DESCRIPTION = (
    f"Evaluate one design, delta = l2/l1 in [{MIN_DELTA:g}, {MAX_DELTA:g}], instead of a "
    f"sweep. S_max (for eta) is then still taken over the paper's range "
    f"{list(DEFAULT_DELTA_RANGE)} at step {DEFAULT_DELTA_STEP:g}. Excludes 'delta_range' "
    "and 'delta_step'."
)


def eq17_reach(allowable_deg: float) -> float:
    """delta_+: eq (17)'s point (e, y0) is in reach of both chains iff delta < delta_+,
    the larger root of delta^2 - (3 + cos[beta]) delta + 1 (2.618 at 90°, 3.732 at 0°)."""
    c = 3.0 + math.cos(math.radians(allowable_deg))
    return 0.5 * (c + math.sqrt(c * c - 4.0))


class OptimisationSpec(FrozenSpec):
    """Inputs of ``planar2dof-optimisation``: the paper's global design of the proximal-arm
    type (isotropic architecture eq 12, rectangle W_lambda in W_kappa0, index eta eq 13)."""

    allowable_pressure_angle_deg: float | None = Field(
        None, ge=MIN_PRESSURE_ANGLE_DEG, lt=MAX_PRESSURE_ANGLE_DEG, description=_BETA_DESCRIPTION
    )
    inverse_condition_limit: float | None = Field(
        None, ge=MIN_INVERSE_CONDITION_LIMIT, lt=1, description=_LIMIT_OPT_DESCRIPTION
    )
    aspect_ratio: float = Field(
        4.0,
        ge=MIN_ASPECT_RATIO,
        le=MAX_ASPECT_RATIO,
        description=f"Width/height ratio lambda = b/h of the rectangle W_lambda, from "
        f"{MIN_ASPECT_RATIO:g} to {MAX_ASPECT_RATIO:g} (the paper's 4).",
    )
    delta_range: Annotated[
        tuple[float, float] | None, entries(2, "delta_range needs two values [lo, hi]")
    ] = Field(None, description=_RANGE_DESCRIPTION)
    delta_step: float | None = Field(None, ge=MIN_STEP, le=MAX_DELTA, description=_STEP_DESCRIPTION)
    delta: float | None = Field(None, ge=MIN_DELTA, le=MAX_DELTA, description=_DELTA_DESCRIPTION)
    mean_mesh: int = Field(
        101,
        ge=2,
        le=MAX_MEAN_MESH,
        description="Nodes per side of the M x N = mean_mesh² mesh of W_lambda over which the "
        f"mean 1/kappa (eq 14) is taken (2..{MAX_MEAN_MESH}; default 101: the mean depends on "
        "the mesh, see docs/methods/planar-parallel.md).",
    )
    plots: bool = Field(True, description=PLOTS_DESCRIPTION)

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
            lo, hi = self.sweep_range
            if hi - lo > self.sweep_step * (MAX_DELTAS - 1):  # no division: no overflow
                raise field_error(
                    self, "delta_step",
                    f"the sweep of [{lo:g}, {hi:g}] at step {self.sweep_step:g} holds more "
                    f"than {MAX_DELTAS} deltas; use a larger delta_step or a narrower "
                    "delta_range", self.delta_step,
                )  # fmt: skip
            self._eq17_in_reach(lo)
        return self

    def _eq17_in_reach(self, lo: float) -> None:
        angle = self.allowable_pressure_angle_deg
        if angle is None:
            return
        reach = eq17_reach(angle)
        if lo > reach - EQ17_REACH_MARGIN:
            raise field_error(
                self, "delta_range",
                f"with [beta] = {angle:g}°, eq (17)'s point is out of reach for delta >= "
                f"{reach:.6g}: no delta of the sweep from {lo:g} gives a conditioning limit; "
                f"start delta_range below {reach - EQ17_REACH_MARGIN:.6g} or give "
                "'inverse_condition_limit'", self.delta_range,
            )  # fmt: skip

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
