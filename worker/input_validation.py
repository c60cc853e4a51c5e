"""A process's inputs, validated: by its model, then by the schema it publishes.

Every refusal is a field error ``{"field", "message", "type"}`` naming its place as a
dotted path (``inputs.links[0]``), gathered in one :class:`InvalidInputs`.  The
submission validates a request's inputs here, and a design study each design's.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from pydantic import BaseModel, ValidationError

from worker.errors import InvalidInputs
from worker.input_schema import schema_errors
from worker.processes import ProcessDefinition

__all__ = ["field_errors", "field_path", "validate_inputs"]


def field_path(loc: Sequence[str | int]) -> str:
    """A pydantic location as a dotted field path: ``("inputs", "links", 0)`` ->
    ``inputs.links[0]``."""
    # Drop the union-member tags pydantic inserts (e.g. "PolylineTrajectory" or
    # "function-after[...]"); the last element is always a real field name.
    parts = [
        str(p)
        for i, p in enumerate(loc)
        if i == len(loc) - 1 or not (isinstance(p, str) and (p[:1].isupper() or "[" in p))
    ]
    field = ""
    for part in parts:
        field += f"[{part}]" if part.isdigit() else (f".{part}" if field else part)
    return field or "inputs"


def field_errors(exc: ValidationError, prefix: tuple[str | int, ...] = ()) -> list[dict[str, Any]]:
    """Pydantic errors as ``{"field", "message", "type"}`` with dotted field paths."""
    return [
        {"field": field_path((*prefix, *err.get("loc", ()))), "message": err["msg"],
         "type": err["type"]}
        for err in exc.errors(include_url=False)
    ]  # fmt: skip


def validate_inputs(definition: ProcessDefinition, raw: Mapping[str, Any]) -> BaseModel:
    """The validated inputs model, or :class:`InvalidInputs` naming every bad field."""
    try:
        inputs = definition.inputs_model.model_validate(raw)
    except ValidationError as exc:
        raise InvalidInputs(field_errors(exc, ("inputs",))) from exc
    # The model's lax coercions (true -> 1.0, "2" -> 2.0) are not what the schema
    # publishes; the schema wins.
    mismatches = schema_errors(definition.inputs_schema, raw)
    if mismatches:
        raise InvalidInputs(mismatches)
    return inputs
