"""Answering a preview request: validate as a submission does, price, evaluate.

Nothing is stored and nothing is queued: the caller (the HTTP layer) runs
:func:`preview` in a thread of its own and applies the submit rate limit of the
caller's API key before calling it.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from worker.errors import CostLimitExceeded, InvalidInputs, NoPreview
from worker.input_validation import validate_inputs
from worker.processes import ProcessDefinition, ProcessRegistry

__all__ = ["preview", "preview_definition"]


def preview_definition(registry: ProcessRegistry, process_id: str) -> ProcessDefinition:
    """The definition of ``process_id`` if it has a preview: :class:`NoSuchProcess` for
    an unknown ID, :class:`NoPreview` for a process without one."""
    definition = registry.require(process_id)
    if definition.preview is None:
        with_preview = [d.id for d in registry if d.preview is not None]
        raise NoPreview(
            f"Process {process_id!r} has no preview (no live explorer); submit it as a job. "
            f"Processes with a preview: {', '.join(with_preview)}."
        )
    return definition


def preview(
    registry: ProcessRegistry, process_id: str, raw_inputs: Mapping[str, Any]
) -> dict[str, Any]:
    """The preview of ``raw_inputs``: validated as a submission's (the same 422 naming
    each field, the process's precheck included), refused with
    :class:`CostLimitExceeded` above the preview's cost limit (never above what the
    process publishes), then computed.  Answers the family's plain values (see
    :mod:`worker.previews`) with ``cost``, ``cost_limit`` and ``cost_unit``."""
    definition = preview_definition(registry, process_id)
    spec = definition.preview
    assert spec is not None  # preview_definition checked it
    inputs = validate_inputs(definition, raw_inputs)
    cost = definition.cost(inputs)
    limit = min(spec.cost_limit, definition.cost_limit)
    if cost > limit:
        raise CostLimitExceeded(
            f"This preview costs {cost:,} {definition.cost_unit}, above the preview limit "
            f"of {limit:,} for {process_id}; use a coarser grid, or run it as a job.",
            cost=cost,
            cost_limit=limit,
            cost_unit=definition.cost_unit,
        )
    if definition.precheck is not None:
        problems = definition.precheck(inputs)
        if problems:
            raise InvalidInputs(problems)
    answer = dict(spec.compute(inputs))
    answer.update(cost=cost, cost_limit=limit, cost_unit=definition.cost_unit)
    return answer
