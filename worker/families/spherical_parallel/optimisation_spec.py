"""Validated inputs of ``spm-optimisation`` (Bai 2010 §5, eqs 28-30; see
docs/methods/spherical-parallel.md).

The design parameters alpha1, alpha2, beta, gamma are each free (searched) or held at a
given value; ``identical_platforms`` ties gamma to beta (the paper's Table 3). Angles
are in degrees; frozen, ``extra="forbid"``, finite floats only.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, ValidationInfo, field_validator

from worker.common.numeric_ranges import MIN_STEP
from worker.families.spherical_parallel.workspace_spec import (
    ANGLE_MARGIN_DEG,
    ANGLE_RANGE,
    MAX_ANGLE_DEG,
    AngleDeg,
    Branch,
    FrozenSpec,
    GammaDeg,
    WorkspaceSpec,
    entries,
    narrower_than,
)

__all__ = [
    "DEFAULT_FREE",
    "INDEX_MAP_POINTS",
    "MAX_EVALUATIONS_PER_START",
    "MAX_STARTS",
    "MIN_SINGULARITY_TOLERANCE",
    "PARAMETERS",
    "SCREEN_PER_START",
    "OptimisationBounds",
    "OptimisationSpec",
    "Parameter",
]

Parameter = Literal["alpha1", "alpha2", "beta", "gamma"]
PARAMETERS: tuple[Parameter, ...] = ("alpha1", "alpha2", "beta", "gamma")
DEFAULT_FREE: tuple[Parameter, ...] = ("alpha1", "alpha2", "beta")
MAX_STARTS = 64
MAX_EVALUATIONS_PER_START = 2000
#: Designs per side of the grid over the optimum's rectangle drawn in the index map.
INDEX_MAP_POINTS = 31
#: Candidate designs screened per start to seed it from the design space (the
#: kinematics' ``screen``; the optima sit on the design-space edges, see
#: docs/methods/spherical-parallel.md).
SCREEN_PER_START = 32
#: Least lambda of eq 30 (|det A| >= 1e-6): the solver's penalty divides by it.
MIN_SINGULARITY_TOLERANCE = 1e-12

_Range = Annotated[tuple[float, float], entries(2, "a search range needs two angles [lo, hi]")]


class OptimisationBounds(FrozenSpec):
    """Search ranges (deg) of the free pyramid angles; the link angles need none: they are
    searched over the design-space rectangle of eq 19."""

    beta_deg: _Range | None = Field(
        None,
        description=f"[lo, hi] of beta in degrees, both {ANGLE_RANGE}, hi - lo at least "
        f"{MIN_STEP:g} (default [1, 179]).",
    )
    gamma_deg: _Range | None = Field(
        None,
        description=f"[lo, hi] of gamma in degrees, 0 <= lo, hi <= {MAX_ANGLE_DEG:.10g}, hi - lo "
        f"at least {MIN_STEP:g} (default [0, 179]).",
    )

    @field_validator("beta_deg", "gamma_deg")
    @classmethod
    def _ordered(cls, value: tuple[float, float] | None) -> tuple[float, float] | None:
        if value is not None:
            lo, hi = value
            if not (0.0 <= lo < hi <= MAX_ANGLE_DEG):
                raise ValueError(
                    f"[{lo:g}, {hi:g}] must satisfy 0 <= lo < hi <= {MAX_ANGLE_DEG:.10g}"
                )
            if narrower_than(lo, hi, MIN_STEP):
                raise ValueError(
                    f"[{lo:.10g}, {hi:.10g}] spans {hi - lo:.6g}°, less than {MIN_STEP:g}°: "
                    "hold the angle instead (drop it from free and give its *_deg)"
                )
        return value

    @field_validator("beta_deg")
    @classmethod
    def _positive_beta(cls, value: tuple[float, float] | None) -> tuple[float, float] | None:
        if value is not None and value[0] < ANGLE_MARGIN_DEG:
            raise ValueError(
                f"beta's lower bound {value[0]:g} must be at least {ANGLE_MARGIN_DEG:g}"
            )
        return value


_FREE_DESCRIPTION = (
    "The design parameters searched, from 'alpha1', 'alpha2', 'beta', 'gamma' (default "
    "alpha1, alpha2, beta, as the paper's Tables 1-2). Every other parameter is held at "
    "its *_deg input (gamma defaults to 0). With identical_platforms, gamma follows beta."
)
_HELD = "Held value in degrees, " + ANGLE_RANGE + ", when {name} is not free; omit when it is free."


class OptimisationSpec(FrozenSpec):
    """Inputs of ``spm-optimisation``: maximise eq 28 over the design space (eq 29, 30).

    Fields are validated in order, each cross-field check on the later field (so every
    message names a field): identical_platforms, then free, then the held *_deg values,
    then bounds.
    """

    workspace: WorkspaceSpec = Field(
        ..., description="The prescribed workspace; its samples are the n of eq 28."
    )
    identical_platforms: bool = Field(
        False,
        description="gamma = beta (identical base and mobile pyramids, the paper's Table 3). "
        "Then 'gamma' is neither free nor given.",
    )
    free: tuple[Parameter, ...] = Field(
        DEFAULT_FREE, min_length=1, max_length=4, description=_FREE_DESCRIPTION
    )
    alpha1_deg: AngleDeg | None = Field(
        None, validate_default=True, description=_HELD.format(name="alpha1")
    )
    alpha2_deg: AngleDeg | None = Field(
        None, validate_default=True, description=_HELD.format(name="alpha2")
    )
    beta_deg: AngleDeg | None = Field(
        None, validate_default=True, description=_HELD.format(name="beta")
    )
    gamma_deg: GammaDeg | None = Field(
        None,
        description=f"Held gamma in degrees (0 to {MAX_ANGLE_DEG:.10g}; default 0, the coaxial "
        "active ball joint) when gamma is not free and the platforms are not identical.",
    )
    bounds: OptimisationBounds = Field(
        default_factory=OptimisationBounds,
        description="{'beta_deg': [lo, hi], 'gamma_deg': [lo, hi]}: search ranges of a free "
        "beta or gamma.",
    )
    starts: int = Field(
        8,
        ge=1,
        le=MAX_STARTS,
        description=f"Least-squares runs (1..{MAX_STARTS}), each from a start seeded from the "
        f"design space (the rectangle of eq 19 and the beta/gamma bounds): the best of "
        f"{SCREEN_PER_START} seeded candidates per start, a third of them on its edges.",
    )
    max_evaluations_per_start: int = Field(
        100,
        ge=5,
        le=MAX_EVALUATIONS_PER_START,
        description="The evaluation budget of one start: the solver's max_nfev (each "
        "finite-difference Jacobian costs another one per variable, not counted here).",
    )
    singularity_tolerance: float | None = Field(
        None,
        ge=MIN_SINGULARITY_TOLERANCE,
        lt=1,
        description="lambda of eq 30, at least 1e-12 and less than 1: require det(A)^2 >= "
        "lambda at every sample (type-II singularity margin; |det A| <= 1; below 1e-12 the "
        "margin is lost in rounding). Omit for none.",
    )
    seed: int = Field(
        0, ge=0, le=2**32 - 1, description="Seed of the random starts (same seed, same result)."
    )
    branch: Branch = Field(-1, description="The branch sign (eq 29; the paper's -1).")
    plots: bool = Field(True, description="Render the PNG/SVG plots. false: data files only.")

    @field_validator("free")
    @classmethod
    def _distinct_free(cls, value: tuple[Parameter, ...], info: ValidationInfo
                       ) -> tuple[Parameter, ...]:  # fmt: skip
        if len(set(value)) != len(value):
            raise ValueError(f"free lists a parameter twice: {list(value)}")
        if "gamma" in value and info.data.get("identical_platforms"):
            raise ValueError("'gamma' cannot be free with identical_platforms: gamma follows beta")
        return value

    @field_validator("alpha1_deg", "alpha2_deg", "beta_deg", "gamma_deg")
    @classmethod
    def _held_or_free(cls, value: float | None, info: ValidationInfo) -> float | None:
        name = str(info.field_name).removesuffix("_deg")
        free = info.data.get("free")
        if free is None:  # free itself failed: reported there
            return value
        if name == "gamma" and value is not None and info.data.get("identical_platforms"):
            raise ValueError(
                "gamma_deg and identical_platforms exclude each other: with identical "
                "platforms gamma = beta"
            )
        if name in free and value is not None:
            raise ValueError(
                f"{name}_deg is given but {name} is free: drop {name}_deg, or drop "
                f"'{name}' from free to hold it there"
            )
        if name != "gamma" and name not in free and value is None:
            raise ValueError(f"{name} is not free: give {name}_deg, the value to hold it at")
        return value

    @field_validator("bounds")
    @classmethod
    def _bounds_of_free(cls, value: OptimisationBounds, info: ValidationInfo
                        ) -> OptimisationBounds:  # fmt: skip
        free = info.data.get("free", ())
        for name in ("beta", "gamma"):
            if getattr(value, f"{name}_deg") is not None and name not in free:
                raise ValueError(f"bounds.{name}_deg is given but {name} is not free")
        return value

    @property
    def held(self) -> dict[str, float]:
        """The held parameters in degrees (gamma 0 unless given or tied to beta)."""
        values = {
            name: getattr(self, f"{name}_deg")
            for name in ("alpha1", "alpha2", "beta", "gamma")
            if name not in self.free
        }
        if self.identical_platforms:
            values.pop("gamma", None)
        elif "gamma" in values and values["gamma"] is None:
            values["gamma"] = 0.0
        return {name: float(value) for name, value in values.items()}

    @property
    def solver_variables(self) -> int:
        """How many variables the solver moves: (s, t) or u for the free link angles,
        plus a free beta and gamma."""
        return sum(name in self.free for name in PARAMETERS)
