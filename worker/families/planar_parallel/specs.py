"""Validated inputs of the planar2dof jobs (Huang et al. 2004; docs/methods/planar-parallel.md).

Every model is frozen with ``extra="forbid"`` and rejects NaN and infinity; the field
descriptions become the public JSON schema served at ``GET /v1/processes/{id}``.
Lengths are in the caller's ``length_unit`` (the optimisation is normalised, l1 = 1),
angles in degrees. The numeric ranges follow :mod:`worker.common.numeric_ranges`: lengths
in [1e-6, 1e6], the longest of l1, l2, e at most 1e6 times the shortest, positions in
[-1e6, 1e6]; the grid's sides within a factor 1e6 of the robot's longest length, its
steps at least 1e-6. The optimisation's inputs are in
:mod:`worker.families.planar_parallel.optimisation_spec` (re-exported here).

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
    JsonValue,
    ValidationInfo,
    field_validator,
    model_validator,
)

from worker.common.field_errors import field_error
from worker.common.numeric_ranges import (
    MAX_LENGTH,
    MAX_LENGTH_RATIO,
    MIN_LENGTH,
    MIN_STEP,
    Coordinate,
    PositiveLength,
    length_ratio_problem,
    ratio_schema,
)
from worker.common.specs import MAX_POINTS_PER_AXIS, FrozenSpec, GridSpecBase
from worker.families.planar_parallel.optimisation_spec import (
    DEFAULT_DELTA_RANGE,
    DEFAULT_DELTA_STEP,
    MAX_DELTA,
    MAX_DELTAS,
    MAX_MEAN_MESH,
    MIN_DELTA,
    MIN_INVERSE_CONDITION_LIMIT,
    PLOTS_DESCRIPTION,
    OptimisationSpec,
    sweep_deltas,
)
from worker.study_kernels import in_study_template

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
    "robot_size",
    "sweep_deltas",
]

MAX_POINTS = 1000

Actuation = Literal["proximal-arm", "telescopic-leg", "linear-drive"]
WorkingMode = tuple[Literal[1, -1], Literal[1, -1]]
Point = tuple[Coordinate, Coordinate]
_LENGTHS = f"[{MIN_LENGTH:g}, {MAX_LENGTH:g}]"
_RATIO = (
    f"the longest of l1, l2 and e (proximal-arm type) at most {MAX_LENGTH_RATIO:g} times the "
    "shortest"
)


def _signs(value: Any) -> Any:
    """working_mode entries must be +1 or -1 (one message for both entries)."""
    if isinstance(value, list | tuple):
        if len(value) != 2:
            raise ValueError(f"working_mode needs two signs [sgn1, sgn2], not {len(value)}")
        bad = [v for v in value if isinstance(v, bool) or v not in (1, -1)]
        if bad:
            raise ValueError(f"working_mode entries must be +1 or -1; got {bad[0]!r}")
    return value


#: The unit of a length or position input, for the pages: the job's ``length_unit``.
LENGTH_UNIT: dict[str, JsonValue] = {"x-unit": "length"}
#: Lengths that also keep within a ratio of each other (worker.common.numeric_ranges).
_LENGTH_FIELD: dict[str, JsonValue] = {**ratio_schema(), **LENGTH_UNIT}


class GridSpec(GridSpecBase):
    """The evaluation grid: ``points_per_axis`` nodes on each axis, ends included."""

    bounds: tuple[Coordinate, Coordinate, Coordinate, Coordinate] | None = Field(
        None,
        description=(
            "[x_min, x_max, y_min, y_max] of the grid, each in [-1e6, 1e6], with steps "
            f"(x_max - x_min)/(points_per_axis - 1) and the same in y of at least {MIN_STEP:g}; "
            f"each side within a factor {MAX_LENGTH_RATIO:g} of the robot's longest length. "
            "Default: the whole reachable workspace with a 3 % margin: |x| <= l1 + l2 - e, "
            "|y| <= l1 + l2 (proximal arms); |x|, |y| <= 3e (telescopic legs); |x| <= 2 l2, "
            "|y| <= l2 (linear drives)."
        ),
        json_schema_extra=_LENGTH_FIELD,
    )

    @model_validator(mode="after")
    def _steps_not_too_fine(self) -> GridSpec:
        if self.bounds is not None:
            x_min, x_max, y_min, y_max = self.bounds
            intervals = self.points_per_axis - 1
            for axis, lo, hi in (("x", x_min, x_max), ("y", y_min, y_max)):
                side = hi - lo  # compared, not divided: no overflow; ends' rounding spared
                if side < MIN_STEP * intervals - 2.0 * math.ulp(max(abs(lo), abs(hi))):
                    raise field_error(
                        self, "bounds",
                        f"the grid's {axis} step {side / intervals:.10g} is below {MIN_STEP:g}: "
                        f"widen the bounds or use fewer than {self.points_per_axis} points "
                        "per axis", self.bounds,
                    )  # fmt: skip
        return self


_ACTUATION_DESCRIPTION = (
    "The robot of the paper's Fig. 1: 'proximal-arm' (revolute-actuated arms l1 at "
    "(±e, 0), distal links l2; the paper's example), 'telescopic-leg' (legs from pivots at "
    "(±e, 0), actuated by their length) or 'linear-drive' (sliders on a common line, "
    "carrying links l2)."
)
_L1_DESCRIPTION = (
    f"Length of the proximal links (arms), in {_LENGTHS}; the paper normalises l1 = 1; "
    f"{_RATIO}. Used by the proximal-arm type only."
)
_L2_DESCRIPTION = (
    f"Length of the distal links, in {_LENGTHS} (delta = l2/l1); {_RATIO}. Required for the "
    "proximal-arm and linear-drive types; unused by the telescopic-leg type."
)
_E_DESCRIPTION = (
    f"Half the distance between the two actuated joints (±e, 0): 0, or a length in {_LENGTHS}; "
    f"{_RATIO}. Proximal-arm type: give exactly one of 'e' and 'architecture'; "
    "telescopic-leg type: required; linear-drive type: unused (the sliders share the x axis)."
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
    f"Conditioning limit 1/kappa0, at least {MIN_INVERSE_CONDITION_LIMIT:g} and less than 1: "
    "the map then outlines W_kappa0 = {points with 1/kappa >= 1/kappa0} and reports its "
    "boundary and area. Omit for no outline."
)
_POINTS_DESCRIPTION = (
    f"Points [[x, y], ...] (at most {MAX_POINTS}, coordinates in [-1e6, 1e6]) at which "
    "1/kappa, the pressure angles and the joint angles are reported exactly, in order."
)
_UNIT_DESCRIPTION = "Name of the length unit, used in plots and reported back."


def robot_size(actuation: str, l1: float, l2: float | None, e: float | None) -> float:
    """The robot's longest length its type uses (l1, l2, e; l2 alone for linear drives,
    e alone for telescopic legs); 0 when it has none (telescopic legs with e = 0)."""
    if actuation == "linear-drive":
        return l2 or 0.0
    if actuation == "telescopic-leg":
        return e or 0.0
    l2 = l2 or l1
    return max(l1, l2, math.sqrt(0.5) * (l2 - l1) if e is None else e)


class ConditioningMapSpec(FrozenSpec):
    """Inputs of ``planar2dof-conditioning-map``: 1/kappa and pressure angles on a grid."""

    actuation: Actuation = Field("proximal-arm", description=_ACTUATION_DESCRIPTION)
    l1: PositiveLength = Field(1.0, description=_L1_DESCRIPTION, json_schema_extra=_LENGTH_FIELD)
    l2: PositiveLength | None = Field(
        None, description=_L2_DESCRIPTION, json_schema_extra=_LENGTH_FIELD
    )
    e: float | None = Field(
        None, ge=0, le=MAX_LENGTH, description=_E_DESCRIPTION, json_schema_extra=_LENGTH_FIELD
    )
    architecture: Literal["isotropic"] | None = Field(None, description=_ARCHITECTURE_DESCRIPTION)
    working_mode: Annotated[WorkingMode, BeforeValidator(_signs)] = Field(
        (1, -1), description=_MODE_DESCRIPTION
    )
    grid: GridSpec = Field(default_factory=GridSpec, description="The evaluation grid.")
    inverse_condition_limit: float | None = Field(
        None, ge=MIN_INVERSE_CONDITION_LIMIT, lt=1, description=_LIMIT_MAP_DESCRIPTION
    )
    points: tuple[Point, ...] | None = Field(
        None,
        min_length=1,
        max_length=MAX_POINTS,
        description=_POINTS_DESCRIPTION,
        json_schema_extra=LENGTH_UNIT,
    )
    length_unit: str = Field(
        "units", min_length=1, max_length=16, pattern=r"^[\w .°/-]+$", description=_UNIT_DESCRIPTION
    )
    plots: bool = Field(True, description=PLOTS_DESCRIPTION)

    @field_validator("e")
    @classmethod
    def _zero_or_length(cls, value: float | None) -> float | None:
        if value is not None and 0.0 < value < MIN_LENGTH:
            raise ValueError(
                f"e is 0 (coincident actuated joints) or a length in {_LENGTHS}; got {value:g}"
            )
        return value

    @model_validator(mode="after")
    def _architecture_fits_the_type(self, info: ValidationInfo) -> ConditioningMapSpec:
        """The type's inputs, then (the study kernel's, per design, in a design study's
        template: :func:`~worker.study_kernels.in_study_template`) the dimensions:
        eq (12)'s l2 >= l1, the lengths' ratio, chains that can meet, a grid that fits."""
        dimensions = not in_study_template(info.context)
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
            return self._grid_fits_the_robot() if dimensions else self
        if (self.e is None) == (self.architecture is None):
            raise ValueError(
                "give exactly one of 'e' (the half-distance of the actuated joints) and "
                "'architecture': 'isotropic' (e by eq 12)"
            )
        if not dimensions:
            return self
        if self.architecture == "isotropic" and self.l2 is not None and self.l2 < self.l1:
            raise ValueError(
                f"architecture 'isotropic' needs l2 >= l1 (eq 12 gives e = (√2/2)(l2 - l1) "
                f"< 0 for l1 = {self.l1:g}, l2 = {self.l2:g})"
            )
        self._lengths_in_ratio()
        self._chains_can_meet()
        return self._grid_fits_the_robot()

    def _chains_can_meet(self) -> None:
        """Each proximal-arm chain reaches the annulus |l1 - l2| <= |p_i| <= l1 + l2
        around its actuated joint at (±e, 0); the two annuli share an area iff
        e < l1 + l2 (on the y axis both distances are sqrt(e^2 + y^2) >= e, and any
        point is at least e from one of the joints)."""
        if self.e is None or self.l2 is None:
            return
        reach = self.l1 + self.l2
        if self.e >= reach:
            raise field_error(
                self, "e",
                f"the two chains can never meet: their actuated joints are 2e = "
                f"{2 * self.e:g} apart and each arm reaches at most l1 + l2 = {reach:g}, so "
                f"the reachable set is empty (it needs e < l1 + l2)", self.e,
            )  # fmt: skip

    def _lengths_in_ratio(self) -> None:
        given = {"l1": self.l1, "l2": self.l2, "e": self.e}
        lengths = {name: v for name, v in given.items() if v is not None and v > 0}
        problem = length_ratio_problem(lengths.values(), "l1, l2 and e")
        if problem is not None:
            ordered = sorted(lengths, key=lengths.__getitem__)
            name = next(n for n in ("e", "l2", "l1") if n in (ordered[0], ordered[-1]))
            raise field_error(self, name, problem, lengths[name])

    def _grid_fits_the_robot(self) -> ConditioningMapSpec:
        size = robot_size(self.actuation, self.l1, self.l2, self.e)
        if self.grid.bounds is None or size <= 0:
            return self
        x_min, x_max, y_min, y_max = self.grid.bounds
        for axis, side in (("x", x_max - x_min), ("y", y_max - y_min)):
            if not size / MAX_LENGTH_RATIO <= side <= size * MAX_LENGTH_RATIO:
                raise field_error(
                    self, ("grid", "bounds"),
                    f"the grid's {axis} side {side:g} and the robot's longest length "
                    f"{size:g} differ by more than a factor {MAX_LENGTH_RATIO:g}: the map "
                    "would be flat, or the robot a dot in it", self.grid.bounds,
                )  # fmt: skip
        return self
