"""A result document as tables a person can read.

:func:`result_view` turns the JSON a job stored into a tree of :class:`ResultNode`
the job page's template draws: scalars as key/value rows, lists of records as tables
(one column per key), short lists inline, long numeric arrays summarised (count, min,
max, mean, the first values), small matrices as grids, nested objects as nested
tables.  Numbers are shown to 6 significant digits, with the exact value on hover;
the full document stays one click away (the JSON results and the data files).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

__all__ = ["ResultNode", "format_scalar", "result_view"]

#: Lists up to this long are shown whole, inline.
INLINE_ITEMS = 12
#: Rows of a record table or matrix shown before "... more".
MAX_ROWS = 40
#: Columns of a matrix shown as a grid.
MAX_COLUMNS = 12
#: Nesting shown as tables; deeper values are shown as JSON text.
MAX_DEPTH = 6


@dataclass(frozen=True)
class ResultNode:
    """One value of a result, as drawn.

    ``kind`` is one of ``scalar`` (``text``, exact value in ``title``), ``inline``
    (a short list, ``text``), ``summary`` (a long numeric array, ``text``),
    ``object`` (``entries``: key -> node), ``records`` (``columns``, ``rows`` of
    nodes), ``matrix`` (``rows`` of nodes), ``list`` (``items``), ``json`` (``text``).
    ``hidden`` counts the rows or items left out.
    """

    kind: str
    text: str = ""
    title: str = ""
    entries: tuple[tuple[str, ResultNode], ...] = ()
    columns: tuple[str, ...] = ()
    rows: tuple[tuple[ResultNode, ...], ...] = ()
    items: tuple[ResultNode, ...] = ()
    hidden: int = 0
    numeric: bool = field(default=False)


def format_scalar(value: Any) -> str:
    """A scalar as shown: 6 significant digits, ``true``/``false``, ``—`` for null."""
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            return str(value)
        if value.is_integer() and abs(value) < 1e15:
            return str(int(value))
        return f"{value:.6g}"
    return str(value)


def _is_scalar(value: Any) -> bool:
    return value is None or isinstance(value, str | int | float | bool)


def _is_number(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _scalar(value: Any) -> ResultNode:
    exact = json.dumps(value) if isinstance(value, float) else ""
    return ResultNode("scalar", text=format_scalar(value), title=exact, numeric=_is_number(value))


def _inline(values: Sequence[Any]) -> ResultNode:
    return ResultNode("inline", text="[" + ", ".join(format_scalar(v) for v in values) + "]")


def _summary(values: Sequence[Any]) -> ResultNode:
    numbers = [float(v) for v in values if _is_number(v) and math.isfinite(v)]
    parts = [f"{len(values)} values"]
    if numbers:
        mean = math.fsum(numbers) / len(numbers)
        parts.append(
            f"min {format_scalar(min(numbers))}, max {format_scalar(max(numbers))}, "
            f"mean {format_scalar(mean)}"
        )
    first = ", ".join(format_scalar(v) for v in values[:5])
    parts.append(f"first: {first}, …")
    return ResultNode("summary", text="; ".join(parts))


def _flat(record: Mapping[str, Any]) -> bool:
    """Whether a record fits a table row: scalars and short lists of scalars."""
    return all(
        _is_scalar(v)
        or (isinstance(v, list) and len(v) <= INLINE_ITEMS and all(_is_scalar(x) for x in v))
        for v in record.values()
    )


def _records(values: Sequence[Mapping[str, Any]], depth: int) -> ResultNode:
    columns: dict[str, None] = {}
    for record in values:
        columns.update(dict.fromkeys(str(k) for k in record))
    shown = values[:MAX_ROWS]
    rows = tuple(
        tuple(
            _node(record[c], depth + 1) if c in record else ResultNode("scalar", text="")
            for c in columns
        )
        for record in shown
    )
    return ResultNode("records", columns=tuple(columns), rows=rows, hidden=len(values) - len(shown))


def _matrix(values: Sequence[Sequence[Any]]) -> ResultNode:
    """Up to :data:`MAX_ROWS` rows as a grid; more as each column's range."""
    if len(values) <= MAX_ROWS:
        return ResultNode("matrix", rows=tuple(tuple(_scalar(v) for v in row) for row in values))
    width = max(len(row) for row in values)
    ranges = []
    for c in range(width):
        column = [r[c] for r in values if c < len(r) and _is_number(r[c]) and math.isfinite(r[c])]
        if column:
            ranges.append(f"[{format_scalar(min(column))}, {format_scalar(max(column))}]")
    text = f"{len(values)} rows of {width} values"
    if ranges:
        text += "; column ranges " + ", ".join(ranges)
    return ResultNode("summary", text=text)


def _list(values: Sequence[Any], depth: int) -> ResultNode:
    if all(_is_scalar(v) for v in values):
        if len(values) <= INLINE_ITEMS or not all(_is_number(v) for v in values):
            return _inline(values) if len(values) <= INLINE_ITEMS else _summary(values)
        return _summary(values)
    if all(isinstance(v, Mapping) for v in values):
        if all(_flat(record) for record in values):
            return _records(values, depth)
        shown = values[:MAX_ROWS]  # records holding tables: one table each
        return ResultNode(
            "list",
            items=tuple(_node(v, depth + 1) for v in shown),
            hidden=len(values) - len(shown),
        )
    if all(
        isinstance(v, list) and 0 < len(v) <= MAX_COLUMNS and all(_is_scalar(x) for x in v)
        for v in values
    ):
        return _matrix(values)
    if all(isinstance(v, list) for v in values) and len(values) > MAX_ROWS:
        sizes = [len(v) for v in values]
        return ResultNode(
            "summary", text=f"{len(values)} lists of {min(sizes)}–{max(sizes)} values each"
        )
    shown = values[:MAX_ROWS]
    return ResultNode(
        "list", items=tuple(_node(v, depth + 1) for v in shown), hidden=len(values) - len(shown)
    )


def _node(value: Any, depth: int) -> ResultNode:
    if _is_scalar(value):
        return _scalar(value)
    if depth >= MAX_DEPTH:
        return ResultNode("json", text=json.dumps(value))
    if isinstance(value, Mapping):
        return ResultNode(
            "object", entries=tuple((str(k), _node(v, depth + 1)) for k, v in value.items())
        )
    if isinstance(value, list | tuple):
        if not value:
            return ResultNode("inline", text="[]")
        return _list(value, depth)
    return ResultNode("json", text=json.dumps(value, default=str))


def result_view(result: Mapping[str, Any], *, leave_out: Sequence[str] = ()) -> ResultNode:
    """The tree of a result document, without the keys in ``leave_out`` (the page
    shows the notes on their own)."""
    return _node({k: v for k, v in result.items() if k not in leave_out}, 0)
