"""A validation error located at one field, raised by a model's cross-field check.

A ``model_validator`` raising ``ValueError`` is reported at the model itself
(``inputs`` or ``inputs.grid``); raising :func:`field_error` instead names the field
whose value is out of range (``inputs.grid.bounds``, ``inputs.delta_step``), which is
what the service's 422 shows the client; :func:`fields_error` names each of several
fields that conflict (one error per field, the same message).
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ValidationError
from pydantic_core import InitErrorDetails, PydanticCustomError

__all__ = ["field_error", "fields_error"]


def field_error(
    model: BaseModel | type[BaseModel],
    field: str | tuple[str | int, ...],
    message: str,
    value: Any,
) -> ValidationError:
    """A ValidationError at ``field`` (a name or a path inside ``model``) saying
    ``message`` about ``value``; raise it from a validator of ``model`` (the model
    itself, or its class in a field validator, where ``field`` is inside that field)."""
    loc = (field,) if isinstance(field, str) else field
    detail = InitErrorDetails(
        type=PydanticCustomError("value_error", "Value error, {reason}", {"reason": message}),
        loc=loc,
        input=value,
    )
    title = model.__name__ if isinstance(model, type) else type(model).__name__
    return ValidationError.from_exception_data(title, [detail])


def fields_error(model: BaseModel, values: dict[str, Any], message: str) -> ValidationError:
    """A ValidationError at each field of ``values`` (name -> the value given), all
    saying ``message``: inputs that may not be given together."""
    details = [
        InitErrorDetails(
            type=PydanticCustomError("value_error", "Value error, {reason}", {"reason": message}),
            loc=(name,),
            input=value,
        )
        for name, value in values.items()
    ]
    return ValidationError.from_exception_data(type(model).__name__, details)
