"""Validated inputs of ``planar3r-design``: link lengths (and optionally the base) chosen
for a task under joint limits (docs/methods/planar-serial.md, "Designing the links").

Frozen, ``extra="forbid"``, finite floats only, like every planar3r input; the task
(points and/or trajectory), joint limits, plot grid, unit and plots switch are those of
the other planar3r jobs (:class:`~worker.families.planar_serial.specs.TaskInputs`).
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, field_validator, model_validator

from worker.common.field_errors import field_error
from worker.common.numeric_ranges import MAX_LENGTH_RATIO, Coordinate, PositiveLength
from worker.common.specs import entries
from worker.families.planar_serial.specs import LENGTH_UNIT, TaskInputs

__all__ = [
    "DEFAULT_LOWER_FRACTION",
    "MAX_GENERATIONS",
    "MAX_POPULATION",
    "POLISH_EVALUATIONS_PER_VARIABLE",
    "DesignSpec",
]

#: Default least link length, as a fraction of total_length_max.
DEFAULT_LOWER_FRACTION = 1e-3
MAX_GENERATIONS = 1000
MAX_POPULATION = 100
#: Most Nelder-Mead evaluations of the polish, per free variable.
POLISH_EVALUATIONS_PER_VARIABLE = 200

LinkBound = Annotated[tuple[PositiveLength, PositiveLength], entries(2, "a link bound is [lo, hi]")]

_OBJECTIVE_DESCRIPTION = (
    "'max_min_dz' (default): maximise the smallest d_z over the task points and the "
    "trajectory samples (ties: the shorter arm). 'min_length': the shortest total length "
    "l1 + l2 + l3 that keeps every task point and trajectory sample at d_z >= dz_target."
)
_BOUNDS_DESCRIPTION = (
    "Search bounds [[lo, hi], [lo, hi], [lo, hi]] of l1, l2, l3 (0 < lo <= hi). Default: "
    f"each link in [{DEFAULT_LOWER_FRACTION:g} total_length_max, total_length_max]. The "
    "lower bounds must leave room: lo1 + lo2 + lo3 <= total_length_max; the largest hi "
    f"(capped at total_length_max) at most {MAX_LENGTH_RATIO:g} times the smallest lo."
)
_BASE_DESCRIPTION = (
    "[x_lo, x_hi, y_lo, y_hi]: the base position becomes a free variable within this box "
    "(x_lo < x_hi, y_lo < y_hi). Default: the base stays at the origin."
)
_PAPER_L3_DESCRIPTION = (
    "l3 of the paper's rule (eqs 10-11) reported for comparison. Default: the l3 for which "
    "the rule's total length d_max + 2 l3 + 1 equals total_length_max."
)


class DesignSpec(TaskInputs):
    """Inputs of ``planar3r-design``: the best link lengths for a task under joint limits,
    by a seeded global search (differential evolution) over the exact d_z."""

    objective: Literal["max_min_dz", "min_length"] = Field(
        "max_min_dz", description=_OBJECTIVE_DESCRIPTION
    )
    dz_target: float = Field(
        1.0, gt=0.0, le=1.0, description="The d_z every task point must keep with 'min_length'."
    )
    total_length_max: PositiveLength = Field(
        ...,
        description="Largest total length l1 + l2 + l3 of a design.",
        json_schema_extra=LENGTH_UNIT,
    )
    link_bounds: Annotated[
        tuple[LinkBound, LinkBound, LinkBound] | None,
        entries(3, "link_bounds needs one [lo, hi] pair per link (3)"),
    ] = Field(None, description=_BOUNDS_DESCRIPTION, json_schema_extra=LENGTH_UNIT)
    base_box: Annotated[
        tuple[Coordinate, Coordinate, Coordinate, Coordinate] | None,
        entries(4, "base_box needs four values [x_lo, x_hi, y_lo, y_hi]"),
    ] = Field(None, description=_BASE_DESCRIPTION, json_schema_extra=LENGTH_UNIT)
    paper_l3: PositiveLength | None = Field(
        None, description=_PAPER_L3_DESCRIPTION, json_schema_extra=LENGTH_UNIT
    )
    round_distances: bool = Field(
        False,
        description="For the paper's rule: round d_min down and d_max up to whole units "
        "first, as the paper does in Example 1.",
    )
    seed: int = Field(
        0, ge=0, le=2**32 - 1, description="Seed of the search: same seed, same result."
    )
    max_generations: int = Field(
        100,
        ge=1,
        le=MAX_GENERATIONS,
        description=f"Generations of differential evolution (1..{MAX_GENERATIONS}); all are run.",
    )
    population_size: int = Field(
        15,
        ge=5,
        le=MAX_POPULATION,
        description="Population per free variable (scipy's popsize, "
        f"5..{MAX_POPULATION}): 3 links, 5 with base_box.",
    )

    @field_validator("link_bounds")
    @classmethod
    def _ordered_bounds(
        cls, value: tuple[tuple[float, float], ...] | None
    ) -> tuple[tuple[float, float], ...] | None:
        for index, (lo, hi) in enumerate(value or ()):
            if lo > hi:
                raise ValueError(f"link_bounds[{index}]: lo {lo:g} exceeds hi {hi:g}")
        return value

    @field_validator("base_box")
    @classmethod
    def _ordered_box(
        cls, value: tuple[float, float, float, float] | None
    ) -> tuple[float, float, float, float] | None:
        if value is not None:
            x_lo, x_hi, y_lo, y_hi = value
            if not (x_lo < x_hi and y_lo < y_hi):
                raise ValueError(
                    f"base_box [{x_lo:g}, {x_hi:g}, {y_lo:g}, {y_hi:g}] needs x_lo < x_hi and "
                    "y_lo < y_hi (to fix the base elsewhere, shift the task instead)"
                )
        return value

    @model_validator(mode="after")
    def _consistent(self) -> DesignSpec:
        if self.task_points is None and self.trajectory is None:
            raise ValueError("planar3r-design needs task_points or a trajectory (or both)")
        bounds = self.search_bounds
        lows = sum(lo for lo, _ in bounds)
        spread = max(hi for _, hi in bounds) / min(lo for lo, _ in bounds)
        if spread > MAX_LENGTH_RATIO:
            raise field_error(
                self, ("link_bounds",),
                f"the longest link allowed is {spread:.3g} times the shortest, more than "
                f"{MAX_LENGTH_RATIO:g}",
                self.link_bounds,
            )  # fmt: skip
        if lows > self.total_length_max:
            raise field_error(
                self, ("link_bounds",),
                f"the lower bounds add up to {lows:g}, more than total_length_max = "
                f"{self.total_length_max:g}: no design fits",
                self.link_bounds,
            )  # fmt: skip
        return self

    @property
    def search_bounds(self) -> tuple[tuple[float, float], ...]:
        """[lo, hi] of each link, the default resolved; hi capped at total_length_max."""
        if self.link_bounds is None:
            lo = DEFAULT_LOWER_FRACTION * self.total_length_max
            return ((lo, self.total_length_max),) * 3
        return tuple((lo, min(hi, self.total_length_max)) for lo, hi in self.link_bounds)

    @property
    def free_variables(self) -> int:
        return 3 if self.base_box is None else 5
