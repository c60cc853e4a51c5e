"""The numeric ranges every process supports, published in its input schema.

Every accepted input must compute: a value outside these ranges is refused at the
boundary with a 422 naming the field, never queued to fail in a worker.  Absolute
bounds are JSON-schema ``minimum``/``maximum``; a ratio bound between entries of one
input (the longest link at most :data:`MAX_LENGTH_RATIO` times the shortest) is
published as the schema extension ``x-max-ratio`` beside the field.

A family uses these types and :func:`length_ratio_problem` and may narrow a range
(never widen it) where its method needs it; the narrowing is stated in the field's
description.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Annotated, Any

from pydantic import Field

__all__ = [
    "MAX_COORDINATE",
    "MAX_LENGTH",
    "MAX_LENGTH_RATIO",
    "MIN_LENGTH",
    "MIN_STEP",
    "Coordinate",
    "PositiveLength",
    "length_ratio_problem",
    "ratio_schema",
]

#: Lengths (link lengths, offsets, radii) in any consistent unit: [1e-6, 1e6].
MIN_LENGTH = 1e-6
MAX_LENGTH = 1e6
#: The longest of a set of lengths is at most this many times the shortest.
MAX_LENGTH_RATIO = 1e6
#: Positions (task points, grid bounds) lie in [-1e6, 1e6].
MAX_COORDINATE = 1e6
#: Sweep and grid steps are at least this (in the field's own unit).
MIN_STEP = 1e-6

PositiveLength = Annotated[float, Field(ge=MIN_LENGTH, le=MAX_LENGTH)]
Coordinate = Annotated[float, Field(ge=-MAX_COORDINATE, le=MAX_COORDINATE)]


def ratio_schema(max_ratio: float = MAX_LENGTH_RATIO) -> dict[str, Any]:
    """The schema extension publishing a ratio bound between a field's entries."""
    return {"x-max-ratio": max_ratio}


def length_ratio_problem(
    lengths: Iterable[float], what: str, max_ratio: float = MAX_LENGTH_RATIO
) -> str | None:
    """Why ``lengths`` spread too far (longest over shortest above ``max_ratio``), or
    None when they do not.  Non-positive entries are left to the per-entry bounds."""
    values = [float(v) for v in lengths if float(v) > 0]
    if len(values) < 2:
        return None
    ratio = max(values) / min(values)
    if ratio > max_ratio:
        return (
            f"{what}: the longest ({max(values):g}) is {ratio:.3g} times the shortest "
            f"({min(values):g}); at most {max_ratio:g} is supported"
        )
    return None
