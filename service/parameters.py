"""Query parameters both surfaces share, validated where FastAPI validates parameters
(so a bad value is answered like any other: :func:`service.problems.parameter_problem`)."""

from __future__ import annotations

from typing import Annotated

from fastapi import Query
from pydantic import AfterValidator

from worker.store.sql import decode_cursor

__all__ = ["CursorQuery"]


def _cursor(value: str | None) -> str | None:
    if value is not None:
        decode_cursor(value)  # ValueError names the parameter
    return value


#: ``cursor``: where a ``next`` link continues; only a cursor this service issued.
CursorQuery = Annotated[
    str | None,
    Query(max_length=200, description="Where a `next` link continues."),
    AfterValidator(_cursor),
]
