"""The published input schema is the contract: a request it refuses is refused.

Pydantic's lax mode turns ``true`` into ``1.0`` and ``"1.5"`` into ``1.5``; the input
schema each process publishes (its model's JSON Schema) says a number is a number.
So that a client can trust the schema both ways, inputs the model accepted are also
checked against that schema, and a mismatch is a 422 naming the field, like any
other invalid input.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from jsonschema import Draft202012Validator
from jsonschema.exceptions import ValidationError

__all__ = ["schema_errors"]


def _field(path: Iterable[Any]) -> str:
    field = "inputs"
    for part in path:
        field += f"[{part}]" if isinstance(part, int) else f".{part}"
    return field


def _deepest(error: ValidationError) -> ValidationError:
    """For an ``anyOf``/``oneOf`` failure, the alternative's error that says most:
    the one deepest in the value (a branch that got further), and not a bare type
    mismatch with another alternative (``null``) where there is a choice."""
    while error.context:
        error = max(error.context, key=lambda e: (len(e.absolute_path), e.validator != "type"))
    return error


def _plain(value: Any) -> Any:
    """Mappings as dicts and sequences as lists, as JSON would have them."""
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    return value


def schema_errors(schema: Mapping[str, Any], raw: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Every place ``raw`` violates the JSON Schema ``schema``, as field errors
    (``{"field", "message", "type"}``, fields dotted from ``inputs``)."""
    validator = Draft202012Validator(schema)
    errors = []
    for error in sorted(validator.iter_errors(_plain(raw)), key=lambda e: list(map(str, e.path))):
        deepest = _deepest(error)
        errors.append(
            {
                "field": _field(deepest.absolute_path),
                "message": f"does not match the input schema: {deepest.message}",
                "type": f"schema_{deepest.validator}",
            }
        )
    return errors
