"""Validated inputs of ``planar3r-design``: link lengths (and optionally the base) chosen
for a task under joint limits (docs/methods/planar-serial.md, "Designing the links").

Frozen, ``extra="forbid"``, finite floats only, like every planar3r input; the task
(points and/or trajectory), joint limits, plot grid, unit and plots switch are those of
the other planar3r jobs (:class:`~worker.families.planar_serial.specs.TaskInputs`).

The tool link l3 is held, as in ``planar3r-synthesis``: ``l3``, by default the paper
rule's l3 for the budget (eqs 10-11: d_max + 2 l3 + 1 = total_length_max).  Only
``link_bounds`` makes l3 a design variable, so the two are not given together.
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import Field, field_validator, model_validator

from worker.common.field_errors import field_error, fields_error
from worker.common.numeric_ranges import MAX_LENGTH_RATIO, Coordinate, PositiveLength
from worker.common.specs import entries
from worker.families.planar_serial.jobs.trajectories import task_distance_range
from worker.families.planar_serial.specs import LENGTH_UNIT, TaskInputs

__all__ = [
    "DEFAULT_LOWER_FRACTION",
    "DEFAULT_STARTS",
    "MAX_GENERATIONS",
    "MAX_POPULATION",
    "MAX_STARTS",
    "POLISH_EVALUATIONS_PER_VARIABLE",
    "DesignSpec",
]

#: Default least link length, as a fraction of total_length_max.
DEFAULT_LOWER_FRACTION = 1e-3
MAX_GENERATIONS = 1000
MAX_POPULATION = 100
DEFAULT_STARTS = 8
MAX_STARTS = 32
#: Most Nelder-Mead evaluations of the polish, per free variable.
POLISH_EVALUATIONS_PER_VARIABLE = 200

LinkBound = Annotated[tuple[PositiveLength, PositiveLength], entries(2, "a link bound is [lo, hi]")]

_OBJECTIVE_DESCRIPTION = (
    "'max_min_dz' (default): maximise the smallest d_z over the task points and the "
    "trajectory samples (ties: the shorter arm). 'min_length': the shortest total length "
    "l1 + l2 + l3 that keeps every task point and trajectory sample at d_z >= dz_target."
)
_BOUNDS_DESCRIPTION = (
    "Search bounds [[lo, hi], [lo, hi], [lo, hi]] of l1, l2, l3 (0 < lo <= hi); giving "
    "them makes l3 a design variable within its pair (not with 'l3'). Default: l3 held "
    f"(see 'l3'), l1 and l2 each in [{DEFAULT_LOWER_FRACTION:g} total_length_max, "
    "total_length_max - l3]. The lower bounds must leave room: lo1 + lo2 + lo3 <= "
    "total_length_max; the largest hi (capped at total_length_max) at most "
    f"{MAX_LENGTH_RATIO:g} times the smallest lo."
)
_L3_DESCRIPTION = (
    "Length of the tool link, held during the search (as in planar3r-synthesis). Default: "
    "the paper rule's l3 for the budget, (total_length_max - d_max - 1) / 2 with d_max the "
    "task's largest distance from the origin (the trajectory's when there is one; rounded "
    "up with round_distances), the l3 paper_l3 also defaults to. To design l3 as well, "
    "give link_bounds instead (not both)."
)
_BASE_DESCRIPTION = (
    "[x_lo, x_hi, y_lo, y_hi]: the base position becomes a free variable within this box "
    "(x_lo < x_hi, y_lo < y_hi). Default: the base stays at the origin."
)
_PAPER_L3_DESCRIPTION = (
    "l3 of the paper's rule (eqs 10-11) reported for comparison (paper_rule); it does not "
    "set the design's l3 (see 'l3'). Default: the l3 for which the rule's total length "
    "d_max + 2 l3 + 1 equals total_length_max."
)
_STARTS_DESCRIPTION = (
    f"Independent starts of the search (1..{MAX_STARTS}), start i seeded from seed "
    "(numpy's SeedSequence(seed).spawn); the best is kept, and success needs at least two "
    "starts agreeing on the best score within 1e-4. Cost and time limit grow with it."
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
    l3: PositiveLength | None = Field(
        None, description=_L3_DESCRIPTION, json_schema_extra=LENGTH_UNIT
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
    starts: int = Field(DEFAULT_STARTS, ge=1, le=MAX_STARTS, description=_STARTS_DESCRIPTION)
    max_generations: int = Field(
        100,
        ge=1,
        le=MAX_GENERATIONS,
        description=f"Generations of differential evolution per start (1..{MAX_GENERATIONS}); "
        "all are run.",
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
        if self.l3 is not None and self.link_bounds is not None:
            raise fields_error(
                self, {"l3": self.l3, "link_bounds": self.link_bounds},
                "give either 'l3' (the tool length, held) or 'link_bounds' (l3 designed "
                "within its pair), not both",
            )  # fmt: skip
        self._held_l3_fits()
        bounds = self.search_bounds
        lows = sum(lo for lo, _ in bounds)
        spread = max(hi for _, hi in bounds) / min(lo for lo, _ in bounds)
        field = "link_bounds" if self.link_bounds is not None else self._l3_field
        held = "" if self.held_l3 is None else f" (l3 held at {self.held_l3:g})"
        if spread > MAX_LENGTH_RATIO:
            raise field_error(
                self, field,
                f"the longest link allowed is {spread:.3g} times the shortest{held}, more "
                f"than {MAX_LENGTH_RATIO:g}",
                getattr(self, field),
            )  # fmt: skip
        if self.free_variables == 0:
            raise field_error(
                self, "link_bounds",
                "every link's bounds are a single length (lo = hi) and the base is fixed: "
                "nothing is left to design (planar3r-dexterity-map evaluates one design)",
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
    def _l3_field(self) -> str:
        return "l3" if self.l3 is not None else "total_length_max"

    def _held_l3_fits(self) -> None:
        """A held l3 must be positive and leave l1 and l2 their least lengths."""
        if self.link_bounds is not None:
            return
        l3 = self.held_l3
        assert l3 is not None  # held whenever link_bounds is not given
        room = self.total_length_max * (1.0 - 2.0 * DEFAULT_LOWER_FRACTION)
        if self.l3 is None and l3 <= 0.0:
            _, d_max = self.rule_distances
            raise field_error(
                self, "total_length_max",
                f"total_length_max = {self.total_length_max:g} leaves the paper's rule no "
                f"positive l3 (d_max + 2 l3 + 1 = total_length_max with d_max = {d_max:g}): "
                "give l3 (held), or link_bounds to design it",
                self.total_length_max,
            )  # fmt: skip
        if l3 > room:
            raise field_error(
                self, self._l3_field,
                f"l3 = {l3:g} leaves l1 and l2 less than {DEFAULT_LOWER_FRACTION:g} "
                f"total_length_max each (total_length_max = {self.total_length_max:g})",
                getattr(self, self._l3_field),
            )  # fmt: skip

    @property
    def rule_distances(self) -> tuple[float, float]:
        """(d_min, d_max) the paper's rule uses: the task's exact distance range from the
        origin (the trajectory's when there is one, as in the paper), rounded outward to
        whole units with round_distances."""
        found = task_distance_range(self.trajectory, self.task_points)
        if self.round_distances:
            return float(math.floor(found.d_min)), float(math.ceil(found.d_max))
        return found.d_min, found.d_max

    @property
    def budget_l3(self) -> float:
        """The paper rule's l3 for the budget: d_max + 2 l3 + 1 = total_length_max (may be
        zero or negative: the budget leaves the rule no tool)."""
        return (self.total_length_max - self.rule_distances[1] - 1.0) / 2.0

    @property
    def held_l3(self) -> float | None:
        """The l3 held during the search (``l3``, else the budget's; with link_bounds,
        their l3 pair if it is one length), None when l3 is a design variable."""
        if self.link_bounds is not None:
            lo, hi = self.search_bounds[2]
            return lo if lo == hi else None
        return self.l3 if self.l3 is not None else self.budget_l3

    @property
    def search_bounds(self) -> tuple[tuple[float, float], ...]:
        """[lo, hi] of each link, the default resolved (a held l3 as [l3, l3]); hi capped
        at total_length_max."""
        if self.link_bounds is None:
            l3 = self.held_l3
            assert l3 is not None
            lo = DEFAULT_LOWER_FRACTION * self.total_length_max
            return (lo, self.total_length_max - l3), (lo, self.total_length_max - l3), (l3, l3)
        return tuple((lo, min(hi, self.total_length_max)) for lo, hi in self.link_bounds)

    @property
    def free_variables(self) -> int:
        """Variables of the search: the links with lo < hi, and the base's two with
        base_box."""
        links = sum(1 for lo, hi in self.search_bounds if lo < hi)
        return links + (0 if self.base_box is None else 2)
