"""Previews: a process's cheap, stored-nothing evaluation for the live explorer.

A process with a :class:`ProcessPreview` answers ``POST
/v1/processes/{processID}/preview``: the same inputs as an execution, validated the same
way (:func:`worker.submission.validate_inputs`), priced by the process's ``cost`` and
refused above :attr:`ProcessPreview.cost_limit`, then evaluated in the request by
:attr:`ProcessPreview.compute` (no job, no artifact, no plot).  ``compute`` answers
plain JSON values (lists, floats, strings; numpy stays in the family):

``{"maps": [{"title", "x", "y", "x_label", "y_label", "x_unit", "y_unit", "z",
"z_label", "z_unit"}, ...], "indices": [{"name", "label", "value", "unit"}, ...],
"notes": [...]}`` where ``z`` is ``len(y)`` rows of ``len(x)`` values (None: no value,
e.g. an unreachable point).

:class:`PreviewField` lists the design inputs the explorer shows as sliders; the
explorer starts from the process's worked example :attr:`ProcessPreview.start_example`
with :attr:`ProcessPreview.start_overrides` applied (a grid fit for a live view).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

__all__ = ["DataChart", "PreviewField", "ProcessPreview"]


@dataclass(frozen=True)
class PreviewField:
    """One slider of the explorer: the input at ``path`` (dotted, e.g. ``links.1`` for
    the second entry of ``links``), its label and unit, and the slider's range and step
    (in the input's own unit)."""

    path: str
    label: str
    unit: str
    low: float
    high: float
    step: float

    def describe(self) -> dict[str, Any]:
        return {"path": self.path, "label": self.label, "unit": self.unit,
                "low": self.low, "high": self.high, "step": self.step}  # fmt: skip


@dataclass(frozen=True)
class ProcessPreview:
    """How a process answers a preview (module docstring)."""

    compute: Callable[[Any], Mapping[str, Any]]
    #: Work units (the process's ``cost``) a preview may cost at most.
    cost_limit: int
    fields: tuple[PreviewField, ...]
    start_example: int = 0
    start_overrides: Mapping[str, Any] = field(default_factory=dict)

    def start_inputs(self, example_inputs: Mapping[str, Any]) -> dict[str, Any]:
        """The explorer's first inputs: the worked example's, overridden (top level)."""
        return {**example_inputs, **self.start_overrides}


@dataclass(frozen=True)
class DataChart:
    """A heat map a finished job's page draws in the browser from the job's own CSV
    file (one row per grid node; columns named ``"quantity [unit]"``), beside its PNG
    plots (which stay, and are all a page without JavaScript shows): ``z`` over ``x``
    and ``y``; values at or below ``blank_at_or_below`` are drawn as no value (a
    dexterity of 0: unreachable)."""

    file: str
    x: str
    y: str
    z: str
    title: str
    blank_at_or_below: float | None = None

    def describe(self) -> dict[str, Any]:
        return {"file": self.file, "x": self.x, "y": self.y, "z": self.z, "title": self.title,
                "blank_at_or_below": self.blank_at_or_below}  # fmt: skip
