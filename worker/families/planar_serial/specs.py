"""Validated inputs of the planar3r jobs (Patel & Sobh; docs/methods/planar-serial.md).

Every model is frozen with ``extra="forbid"`` and rejects NaN and infinity; the field
descriptions become the public JSON schema served at ``GET /v1/processes/{id}``.
Lengths are in the caller's ``length_unit``, angles in degrees.
"""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import (
    AfterValidator,
    BaseModel,
    BeforeValidator,
    Discriminator,
    Field,
    JsonValue,
    Tag,
    ValidationInfo,
    field_validator,
    model_validator,
)

from worker.common.field_errors import field_error
from worker.common.numeric_ranges import (
    MAX_COORDINATE,
    MIN_LENGTH,
    Coordinate,
    PositiveLength,
    length_ratio_problem,
    ratio_schema,
)
from worker.common.specs import MAX_POINTS_PER_AXIS, FrozenSpec, GridSpecBase
from worker.families.planar_serial.joint_limits_input import (
    JOINT_LIMITS_DESCRIPTION,
    JointLimitsDeg,
    checked_joint_limits_deg,
)
from worker.families.planar_serial.kinematics.inputs import Arm
from worker.study_kernels import in_study_template

__all__ = [
    "MAX_ORIENTATION_STEP_DEG",
    "MAX_POINTS_PER_AXIS",
    "MAX_TASK_POINTS",
    "MIN_ORIENTATION_STEP_DEG",
    "DexterityMapSpec",
    "GridSpec",
    "JointLimitsDeg",
    "PolylineTrajectory",
    "PolynomialTrajectory",
    "SynthesisSpec",
    "TaskInputs",
    "Trajectory",
    "default_task_labels",
]

MIN_ORIENTATION_STEP_DEG = 0.1
MAX_ORIENTATION_STEP_DEG = 30.0
MAX_TASK_POINTS = 1000
MAX_TRAJECTORY_SAMPLES = 10_000
MAX_POLYLINE_VERTICES = 10_000
MAX_POLYNOMIAL_COEFFICIENTS = 10

#: A position in the plane, each coordinate in [-1e6, 1e6].
Point = tuple[Coordinate, Coordinate]
#: A link length in [1e-6, 1e6] (worker.common.numeric_ranges).
Length = PositiveLength

#: The unit of a length or position input, for the pages: the job's ``length_unit``.
LENGTH_UNIT: dict[str, JsonValue] = {"x-unit": "length"}
#: A polynomial coefficient (the trajectory's y must stay within the coordinate range).
Coefficient = Annotated[float, Field(ge=-MAX_COORDINATE, le=MAX_COORDINATE)]


def default_task_labels(count: int) -> tuple[str, ...]:
    """Spreadsheet-style labels: A, B, ..., Z, AA, AB, ... (``count`` of them)."""
    labels = []
    for index in range(count):
        label = ""
        n = index + 1
        while n:
            n, rem = divmod(n - 1, 26)
            label = chr(ord("A") + rem) + label
        labels.append(label)
    return tuple(labels)


class GridSpec(GridSpecBase):
    """The evaluation grid: ``points_per_axis`` nodes on each axis, ends included."""

    bounds: tuple[Coordinate, Coordinate, Coordinate, Coordinate] | None = Field(
        None,
        description=(
            "[x_min, x_max, y_min, y_max] of the grid, each in [-1e6, 1e6], each side at "
            "least 1e-6 long. Default: the square ±1.05·(l1 + l2 + l3) around the base, "
            "which holds the whole reachable disk."
        ),
        json_schema_extra=LENGTH_UNIT,
    )

    @model_validator(mode="after")
    def _wide_enough(self) -> GridSpec:
        if self.bounds is not None:
            x_min, x_max, y_min, y_max = self.bounds
            if x_max - x_min < MIN_LENGTH or y_max - y_min < MIN_LENGTH:
                raise ValueError(
                    f"bounds: each side of the grid must be at least {MIN_LENGTH:g} long "
                    f"(x: {x_max - x_min:g}, y: {y_max - y_min:g})"
                )
        return self


class PolylineTrajectory(FrozenSpec):
    """A trajectory through the given vertices, in order, with straight segments."""

    points: tuple[Point, ...] = Field(
        ...,
        min_length=2,
        max_length=MAX_POLYLINE_VERTICES,
        description="Vertices [[x, y], ...] of the polyline (at least 2), in order.",
        json_schema_extra=LENGTH_UNIT,
    )
    samples: int = Field(
        200,
        ge=2,
        le=MAX_TRAJECTORY_SAMPLES,
        description="Points spaced evenly by arc length (ends included) at which the "
        "dexterity along the trajectory is evaluated.",
    )

    @field_validator("points")
    @classmethod
    def _positive_length(cls, points: tuple[Point, ...]) -> tuple[Point, ...]:
        if all(p == points[0] for p in points):
            raise ValueError("points: the polyline has zero length (all vertices coincide)")
        return points


class PolynomialTrajectory(FrozenSpec):
    """A trajectory y = a_n x^n + ... + a_0 for x from ``x_start`` to ``x_end``."""

    polynomial: tuple[Coefficient, ...] = Field(
        ...,
        min_length=1,
        max_length=MAX_POLYNOMIAL_COEFFICIENTS,
        description="Coefficients [a_n, ..., a_1, a_0] of y(x), highest power first "
        f"(1..{MAX_POLYNOMIAL_COEFFICIENTS} of them).",
    )
    x_start: Coordinate = Field(
        ..., description="x at the start of the trajectory.", json_schema_extra=LENGTH_UNIT
    )
    x_end: Coordinate = Field(
        ...,
        description="x at the end of the trajectory (≠ x_start).",
        json_schema_extra=LENGTH_UNIT,
    )
    samples: int = Field(
        200,
        ge=2,
        le=MAX_TRAJECTORY_SAMPLES,
        description="Points spaced evenly in x (ends included) at which the dexterity "
        "along the trajectory is evaluated.",
    )

    @model_validator(mode="after")
    def _distinct_ends(self) -> PolynomialTrajectory:
        if abs(self.x_end - self.x_start) < MIN_LENGTH:
            raise ValueError(
                f"x_start and x_end must differ by at least {MIN_LENGTH:g} "
                f"({self.x_start:g} and {self.x_end:g})"
            )
        x = np.linspace(self.x_start, self.x_end, self.samples)
        with np.errstate(all="ignore"):
            y = np.polyval(np.asarray(self.polynomial, dtype=float), x)
        if not np.all(np.isfinite(y)) or float(np.max(np.abs(y))) > MAX_COORDINATE:
            raise ValueError(
                f"polynomial: y(x) leaves [-{MAX_COORDINATE:g}, {MAX_COORDINATE:g}] between "
                f"x_start and x_end; every trajectory point must be a valid coordinate"
            )
        return self


def _trajectory_kind(value: Any) -> str | None:
    if isinstance(value, dict):
        keys = set(value)
    elif isinstance(value, BaseModel):
        keys = set(type(value).model_fields)
    else:
        return None
    has_points, has_polynomial = "points" in keys, "polynomial" in keys
    if has_points == has_polynomial:
        return None  # both or neither: reported with the custom message below
    return "polyline" if has_points else "polynomial"


Trajectory = Annotated[
    Annotated[PolylineTrajectory, Tag("polyline")]
    | Annotated[PolynomialTrajectory, Tag("polynomial")],
    Discriminator(
        _trajectory_kind,
        custom_error_type="trajectory_kind",
        custom_error_message=(
            "trajectory must be an object with exactly one of 'points' (a polyline "
            "[[x, y], ...]) or 'polynomial' (coefficients of y(x), highest power first, "
            "with 'x_start' and 'x_end')"
        ),
    ),
]

_LINKS_DESCRIPTION = (
    "Link lengths [l1, l2, l3], from the base to the end-effector, each in [1e-6, 1e6], "
    "the longest at most 1e6 times the shortest."
)
_TASK_POINTS_DESCRIPTION = f"Task points [[x, y], ...] (at most {MAX_TASK_POINTS})."
_LABELS_DESCRIPTION = "Labels of the task points, one each (default A, B, C, ...)."
_STEP_DESCRIPTION = (
    "Orientation sampling step in degrees, used only with joint limits and method "
    "'orientation-sampling' "
    f"({MIN_ORIENTATION_STEP_DEG:g}..{MAX_ORIENTATION_STEP_DEG:g}). The n = round(360 / step) "
    "samples are spaced exactly 360/n apart; that effective step is reported."
)
_METHOD_DESCRIPTION = (
    "How d_z is computed under joint limits: 'exact-events' (default) sums the feasible "
    "orientation arcs between closed-form events (a joint at a limit, the wrist at the "
    "edge of the two-link annulus), exact to rounding; 'orientation-sampling' counts "
    "orientations every orientation_step_deg (task points refined by bisection). "
    "Without joint limits the exact closed form is used either way."
)
_UNIT_DESCRIPTION = "Name of the length unit, used in plots and reported back."


def _three_entries(what: str) -> BeforeValidator:
    """Reject a list of the wrong length with one message instead of per-item errors."""

    def check(value: Any) -> Any:
        if isinstance(value, list | tuple) and len(value) != 3:
            raise ValueError(f"{what}, not {len(value)}")
        return value

    return BeforeValidator(check)


class TaskInputs(FrozenSpec):
    """Fields shared by every planar3r job: limits, grid, task, unit, plots."""

    joint_limits_deg: Annotated[
        JointLimitsDeg | None,
        _three_entries("joint_limits_deg needs one [lo, hi] pair per joint (3)"),
        AfterValidator(checked_joint_limits_deg),
    ] = Field(None, description=JOINT_LIMITS_DESCRIPTION)
    grid: GridSpec = Field(default_factory=GridSpec, description="The evaluation grid.")
    task_points: tuple[Point, ...] | None = Field(
        None,
        min_length=1,
        max_length=MAX_TASK_POINTS,
        description=_TASK_POINTS_DESCRIPTION,
        json_schema_extra=LENGTH_UNIT,
    )
    task_labels: tuple[Annotated[str, Field(min_length=1, max_length=32)], ...] | None = Field(
        None, description=_LABELS_DESCRIPTION
    )
    trajectory: Trajectory | None = Field(
        None,
        description="A trajectory: {'points': [[x, y], ...], 'samples': n} (a polyline) or "
        "{'polynomial': [a_n, ..., a_0], 'x_start': x0, 'x_end': x1, 'samples': n} (y(x)).",
    )
    length_unit: str = Field(
        "units", min_length=1, max_length=16, pattern=r"^[\w .°/-]+$", description=_UNIT_DESCRIPTION
    )
    plots: bool = Field(
        True,
        description="Render the PNG/SVG plots. false: data files (CSV/NPZ) only, much "
        "faster for design sweeps.",
    )

    @model_validator(mode="after")
    def _labels_match_points(self) -> TaskInputs:
        if self.task_labels is not None:
            if self.task_points is None:
                raise ValueError("task_labels given without task_points")
            if len(self.task_labels) != len(self.task_points):
                raise ValueError(
                    f"task_labels has {len(self.task_labels)} labels for "
                    f"{len(self.task_points)} task points"
                )
        return self

    @property
    def labels(self) -> tuple[str, ...]:
        """The task points' labels, defaulted to A, B, C, ..."""
        if self.task_labels is not None:
            return self.task_labels
        return default_task_labels(len(self.task_points or ()))


class _TaskSpec(TaskInputs):
    """Fields shared by the map and synthesis jobs: how d_z is evaluated under limits."""

    orientation_step_deg: float = Field(
        1.0, ge=MIN_ORIENTATION_STEP_DEG, le=MAX_ORIENTATION_STEP_DEG, description=_STEP_DESCRIPTION
    )
    method: Literal["exact-events", "orientation-sampling"] = Field(
        "exact-events", description=_METHOD_DESCRIPTION
    )


class _ArmSpec(FrozenSpec):
    links: Annotated[
        tuple[Length, Length, Length],
        _three_entries("links needs three lengths [l1, l2, l3]"),
    ] = Field(
        ..., description=_LINKS_DESCRIPTION, json_schema_extra={**ratio_schema(), **LENGTH_UNIT}
    )

    @field_validator("links")
    @classmethod
    def _spread(
        cls, links: tuple[float, float, float], info: ValidationInfo
    ) -> tuple[float, float, float]:
        """The links, checked once here and kept as an :class:`Arm` that the family's
        kinematics trust.  A design study's template skips the spread: its kernel checks
        each design's links."""
        if not in_study_template(info.context):
            problem = length_ratio_problem(links, "links")
            if problem is not None:
                raise ValueError(problem)
        return Arm(*links)


class _DesignSpec(FrozenSpec):
    l3: Length = Field(
        ...,
        description="Length of the last link, in [1e-6, 1e6] (the paper chooses "
        "l3 < d_min; full dexterity over the task needs l3 + |l1 - l2| <= d_min, i.e. "
        "l3 <= d_min - 1).",
        json_schema_extra=LENGTH_UNIT,
    )
    round_distances: bool = Field(
        False,
        description="Round d_min down and d_max up to whole units before eqs (10)-(11), "
        "as the paper does in Example 1 (10 and 20).",
    )


# The mixins come last so that their fields lead the published schema.
class DexterityMapSpec(_TaskSpec, _ArmSpec):
    """Inputs of ``planar3r-dexterity-map``: d_z and D = d_z/3 over a grid."""

    @model_validator(mode="after")
    def _grid_meets_the_reach(self, info: ValidationInfo) -> DexterityMapSpec:
        """A grid that holds no point of the reachable annulus (unlimited joints: radii
        max(0, 2 max(l) - sum(l)) to sum(l); joint limits only shrink it) would map
        nothing.  A design study's template skips it: its kernel checks each design
        (:mod:`worker.families.planar_serial.study`)."""
        if self.grid.bounds is None or in_study_template(info.context):
            return self
        x_min, x_max, y_min, y_max = self.grid.bounds
        outer = sum(self.links)
        inner = max(0.0, 2.0 * max(self.links) - outer)
        nearest = math.hypot(max(x_min, 0.0, -x_max), max(y_min, 0.0, -y_max))
        farthest = math.hypot(max(abs(x_min), abs(x_max)), max(abs(y_min), abs(y_max)))
        if nearest >= outer or farthest <= inner:
            where = (
                f"its nearest point is {nearest:g} from the base, beyond the reach "
                f"l1 + l2 + l3 = {outer:g}"
                if nearest >= outer
                else f"it lies within {farthest:g} of the base, inside the unreachable "
                f"disk of radius 2 max(l) - (l1 + l2 + l3) = {inner:g}"
            )
            raise field_error(
                self, ("grid", "bounds"),
                f"the grid holds no reachable point: {where}", self.grid.bounds,
            )  # fmt: skip
        return self


class SynthesisSpec(_TaskSpec, _DesignSpec):
    """Inputs of ``planar3r-synthesis``: link lengths by the paper's eqs (10)-(11)."""

    @model_validator(mode="after")
    def _needs_task(self) -> SynthesisSpec:
        if self.task_points is None and self.trajectory is None:
            raise ValueError("planar3r-synthesis needs task_points or a trajectory (or both)")
        return self
