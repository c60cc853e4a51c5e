"""Paths into a process's inputs and into its result document.

An **input path** names an input as the process takes it: ``alpha1_deg``,
``workspace.tilt_max_deg``, ``links[0]``, ``chains[0].lengths[2]``.  A **result path**
names a number in the result document, with ``[]`` for every element of a list and an
optional reduction of the values found: ``optimum.eta``, ``task_points[].d_z|min``,
``links|sum``.  Parsing raises ValueError with a sentence naming what is wrong; reading
a result never raises: a value that is absent, not a number or not finite is None.
"""

from __future__ import annotations

import copy
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

__all__ = [
    "REDUCTIONS",
    "InputPath",
    "ResultPath",
    "nearest_place",
    "parse_input_path",
    "parse_result_path",
    "read_result",
    "reported",
    "show_input_path",
    "varied_input_problem",
    "with_input",
]

#: One step of a path: a key and its list indices, e.g. ``lengths[2]`` or ``task_points[]``.
_STEP = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)((?:\[\d*\])*)$")
_INDEX = re.compile(r"\[(\d*)\]")
REDUCTIONS = ("min", "max", "mean", "sum")
Reduction = Literal["min", "max", "mean", "sum"]
#: A parsed input path: keys and list indices, e.g. ("chains", 0, "lengths", 2).
InputPath = tuple[str | int, ...]


def _steps(text: str, *, every: bool) -> tuple[str | int | None, ...]:
    if not isinstance(text, str) or not text or len(text) > 200:
        raise ValueError(f"{text!r} is not a path (a name like 'alpha1_deg' or 'links[0]')")
    steps: list[str | int | None] = []
    for part in text.split("."):
        match = _STEP.match(part)
        if match is None:
            raise ValueError(
                f"{text!r}: {part!r} is not a path step (a name, optionally followed by "
                f"[index]{' or []' if every else ''})"
            )
        steps.append(match.group(1))
        for index in _INDEX.findall(match.group(2)):
            if index == "" and not every:
                raise ValueError(f"{text!r}: '[]' (every element) is for result paths only")
            steps.append(None if index == "" else int(index))
    return tuple(steps)


def parse_input_path(text: str) -> InputPath:
    """``"chains[0].lengths[2]"`` -> ``("chains", 0, "lengths", 2)``."""
    return tuple(step for step in _steps(text, every=False) if step is not None)


def with_input(document: Mapping[str, Any], path: InputPath, value: Any) -> dict[str, Any]:
    """A copy of ``document`` with ``value`` at ``path``.

    A missing key is created (with a mapping on the way if needed); a list index must
    exist already, since the length of a list is part of the input (ValueError
    otherwise, saying what the fixed inputs lack).
    """
    root: dict[str, Any] = copy.deepcopy(dict(document))
    node: Any = root
    shown = ""  # the path so far, as the fixed inputs hold it
    created = False  # whether ``node`` was made here, on the way to a varied key
    for position, step in enumerate(path):
        problem = _missing_step(node, step, shown, created)
        if problem is not None:
            raise ValueError(problem)
        shown += f"[{step}]" if isinstance(step, int) else (f".{step}" if shown else step)
        if position == len(path) - 1:
            node[step] = value
        else:
            created = isinstance(step, str) and step not in node
            if created:
                node[step] = {}
            node = node[step]
    return root


def _kind(value: Any) -> str:
    if isinstance(value, Mapping):
        return "a mapping"
    if isinstance(value, list):
        return f"a list of {len(value)}"
    if isinstance(value, str):
        return "a text"
    if value is None or isinstance(value, bool):
        return "null" if value is None else "a flag"
    return f"the number {value!r}"


def _missing_step(node: Any, step: str | int, shown: str, created: bool) -> str | None:
    """Why ``node`` (at ``shown`` in the fixed inputs, or ``created`` on the way) has no
    place ``step``, or None."""
    if isinstance(step, str):
        if isinstance(node, Mapping):
            return None
        return f"'{shown}' in 'fixed' is {_kind(node)}, not a mapping with a key '{step}'"
    if isinstance(node, list) and step < len(node):
        return None
    if created:
        return (f"'fixed' has no list '{shown}': a varied list element must be in a list "
                "that 'fixed' gives whole (the list's length is part of the input)")  # fmt: skip
    if isinstance(node, list):
        return f"'{shown}' in 'fixed' is a list of {len(node)}: it has no element [{step}]"
    return f"'{shown}' in 'fixed' is {_kind(node)}, not a list with an element [{step}]"


def varied_input_problem(
    fixed: Mapping[str, Any], path: InputPath, earlier: Mapping[str, InputPath]
) -> str | None:
    """Why ``path`` cannot be varied in ``fixed`` beside the ``earlier`` varied paths
    (by name), or None: it names, holds or lies inside an input another path names; it
    names a key that ``fixed`` gives too (fix it or vary it, not both); or it leads
    where ``fixed`` has no place (:func:`with_input`)."""
    for name, other in earlier.items():
        if path == other:
            return f"names the same input as '{name}', also varied"
        if path[: len(other)] == other:
            return f"lies inside '{name}', also varied"
        if other[: len(path)] == path:
            return f"holds '{name}', also varied"
    parent = _place(fixed, path[:-1])
    if isinstance(path[-1], str) and isinstance(parent, Mapping) and path[-1] in parent:
        return "is both fixed and varied: give it in 'fixed' or vary it, not both"
    try:
        with_input(fixed, path, 0.0)
    except ValueError as exc:
        return str(exc)
    return None


def nearest_place(
    document: Mapping[str, Any], path: InputPath, *, missing: bool = False
) -> InputPath:
    """The part of ``path`` that ``document`` holds (with ``missing``, and the next
    step if it is a key the mapping there lacks): where a field error about ``path``
    is best shown (pydantic names a missing member itself)."""
    node: Any = document
    for depth, step in enumerate(path):
        if isinstance(step, int):
            if not isinstance(node, list) or step >= len(node):
                return path[:depth]
        elif not isinstance(node, Mapping):
            return path[:depth]
        elif step not in node:
            return path[: depth + int(missing)]
        node = node[step]
    return path


def show_input_path(path: InputPath) -> str:
    """``("chains", 0, "lengths", 2)`` -> ``"chains[0].lengths[2]"``."""
    text = ""
    for step in path:
        text += f"[{step}]" if isinstance(step, int) else (f".{step}" if text else step)
    return text


def _place(document: Any, path: InputPath) -> Any:
    """What ``document`` holds at ``path``, or None where it holds nothing."""
    node = document
    for step in path:
        if isinstance(step, int):
            if not isinstance(node, list) or step >= len(node):
                return None
        elif not isinstance(node, Mapping) or step not in node:
            return None
        node = node[step]
    return node


@dataclass(frozen=True)
class ResultPath:
    """A parsed result path: steps (None = every element) and an optional reduction."""

    text: str
    steps: tuple[str | int | None, ...]
    reduction: Reduction | None


def parse_result_path(text: str) -> ResultPath:
    """``"task_points[].d_z|min"`` -> steps ("task_points", None, "d_z"), reduction "min"."""
    body, bar, reduction = text.partition("|") if isinstance(text, str) else (text, "", "")
    if bar and reduction not in REDUCTIONS:
        raise ValueError(
            f"{text!r}: the reduction after '|' must be one of {', '.join(REDUCTIONS)}"
        )
    steps = _steps(body, every=True)
    if None in steps and not bar:
        raise ValueError(f"{text!r}: '[]' gives many values; reduce them with |min, |max, "
                         "|mean or |sum")  # fmt: skip
    return ResultPath(text, steps, reduction if bar else None)  # type: ignore[arg-type]


def _has(value: Any, step: str | int | None) -> bool:
    """Whether ``value[step]`` names something: an index of a list, a key of a mapping."""
    if isinstance(step, int):
        return isinstance(value, list) and step < len(value)
    return isinstance(step, str) and isinstance(value, Mapping) and step in value


def _walk(node: Any, steps: tuple[str | int | None, ...]) -> list[Any]:
    values = [node]
    for step in steps:
        found: list[Any] = []
        for value in values:
            if step is None and isinstance(value, list):
                found.extend(value)
            elif _has(value, step):
                found.append(value[step])
        values = found
    return values


def _number(value: Any) -> float | None:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    number = float(value)
    return number if math.isfinite(number) else None


def read_result(result: Mapping[str, Any], path: ResultPath) -> float | None:
    """The number at ``path`` in ``result``, reduced if asked; None if there is none.

    Without a reduction the path must lead to exactly one number.  With one, lists at
    the end are flattened one level and every value must be a number; an empty set of
    values has no minimum, maximum or mean (None) and sums to 0.
    """
    values = _walk(result, path.steps)
    if path.reduction is None:
        return _number(values[0]) if len(values) == 1 else None
    flat: list[Any] = []
    for value in values:
        flat.extend(value if isinstance(value, list) else [value])
    numbers = [_number(v) for v in flat]
    if any(n is None for n in numbers):
        return None
    present = [n for n in numbers if n is not None]
    if path.reduction == "sum":
        return math.fsum(present)
    if not present:
        return None
    if path.reduction == "min":
        return min(present)
    if path.reduction == "max":
        return max(present)
    return math.fsum(present) / len(present)


def reported(result: Mapping[str, Any], path: ResultPath) -> bool:
    """Whether ``result`` has the place ``path`` names, whatever its value there: every
    key present, every index in range; a null on the way may hide what is below it, and
    counts as present (a design may lack a value that other designs have)."""
    values: list[Any] = [result]
    for step in path.steps:
        found: list[Any] = []
        for value in values:
            if value is None:
                continue
            if step is None:
                if not isinstance(value, list):
                    return False
                found.extend(value)
            elif not _has(value, step):
                return False
            else:
                found.append(value[step])
        values = found
    return True
