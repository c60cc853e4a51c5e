"""Building blocks shared by every family's input models.

:class:`FrozenSpec` is the base of every input model (frozen, ``extra="forbid"``, finite
floats only); :func:`entries` checks a list's length before its items, with one message;
:class:`GridSpecBase` is the ``grid`` input of the map jobs (a family subclasses it to
describe its own default bounds).
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, field_validator

__all__ = ["MAX_POINTS_PER_AXIS", "Bounds", "FrozenSpec", "GridSpecBase", "entries"]

#: Largest grid side accepted by any map job (2001 x 2001 nodes).
MAX_POINTS_PER_AXIS = 2001

Bounds = tuple[float, float, float, float]


class FrozenSpec(BaseModel):
    """Frozen, ``extra="forbid"``, finite floats only: the base of every input model."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


def entries(count: int, what: str) -> BeforeValidator:
    """Reject a list of the wrong length with one message instead of per-item errors."""

    def check(value: Any) -> Any:
        if isinstance(value, list | tuple) and len(value) != count:
            raise ValueError(f"{what}, not {len(value)}")
        return value

    return BeforeValidator(check)


class GridSpecBase(FrozenSpec):
    """The evaluation grid: ``points_per_axis`` nodes on each axis, ends included."""

    bounds: Bounds | None = Field(None, description="[x_min, x_max, y_min, y_max] of the grid.")
    points_per_axis: int = Field(
        201,
        ge=2,
        le=MAX_POINTS_PER_AXIS,
        description=f"Grid nodes per axis (2..{MAX_POINTS_PER_AXIS}); the grid has N² nodes.",
    )

    @field_validator("bounds")
    @classmethod
    def _ordered_bounds(cls, bounds: Bounds | None) -> Bounds | None:
        if bounds is not None:
            x_min, x_max, y_min, y_max = bounds
            if not x_min < x_max:
                raise ValueError(f"bounds: x_min {x_min:g} must be less than x_max {x_max:g}")
            if not y_min < y_max:
                raise ValueError(f"bounds: y_min {y_min:g} must be less than y_max {y_max:g}")
        return bounds
