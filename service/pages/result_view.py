"""A result document as tables a person can read.

:func:`result_view` turns the JSON a job stored into a tree of :class:`ResultNode`
the job page's template draws: scalars as key/value rows, lists of records as tables
(one column per key), short lists inline, long numeric arrays summarised (count, min,
max, mean, the first values), small matrices as grids, nested objects as nested
tables.  Numbers are shown to 6 significant digits, with the exact value on hover;
the full document stays one click away (the JSON results and the data files).

Where the process declares what a number is (``result_paths``), ``quantities`` tells
the view, by the number's place in the result (keys, None for a list element): its
symbol beside the key or column, its unit beside the value or in the column's head,
its meaning on hover (:func:`service.pages.quantities.job_quantities`).
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

__all__ = ["Quantities", "Quantity", "ResultNode", "format_scalar", "result_view"]

#: Lists up to this long are shown whole, inline.
INLINE_ITEMS = 12
#: Rows of a record table or matrix shown before "... more".
MAX_ROWS = 40
#: Columns of a matrix shown as a grid.
MAX_COLUMNS = 12
#: Nesting shown as tables; deeper values are shown as JSON text.
MAX_DEPTH = 6


@dataclass(frozen=True)
class Quantity:
    """What a number is, as a page shows it: its symbol (plain text, "" for none), its
    unit ("" for a pure number) and what it means."""

    symbol: str
    unit: str
    description: str


#: The quantity at a place of the result (keys, None for a list element), if known.
Quantities = Callable[[tuple[str | None, ...]], Quantity | None]
Steps = tuple[str | None, ...]


def _nothing_known(steps: Steps) -> Quantity | None:
    return None


@dataclass(frozen=True)
class ResultNode:
    """One value of a result, as drawn.

    ``kind`` is one of ``scalar`` (``text``, exact value in ``title``), ``inline``
    (a short list, ``text``), ``summary`` (a long numeric array, ``text``),
    ``object`` (``entries``: key -> node), ``records`` (``columns``, ``rows`` of
    nodes), ``matrix`` (``rows`` of nodes), ``list`` (``items``), ``json`` (``text``).
    ``hidden`` counts the rows or items left out.  ``quantity``: what the numbers of a
    scalar, list or matrix are; ``column_quantities``: of each column of records.
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
    quantity: Quantity | None = None
    column_quantities: tuple[Quantity | None, ...] = ()


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


def _leaf_steps(value: Any, steps: Steps) -> Steps | None:
    """The place of the numbers in ``value`` at ``steps``: a number's own, a list's
    elements' (``[]`` per level, read off its first element); None if no numbers."""
    while isinstance(value, list):
        steps = (*steps, None)
        value = next((v for v in value if v is not None), None)
        if value is None:
            return steps
    return steps if _is_number(value) else None


class _Viewer:
    """Builds the tree, asking ``quantities`` what each number is."""

    def __init__(self, quantities: Quantities) -> None:
        self.quantities = quantities

    def quantity(self, value: Any, steps: Steps) -> Quantity | None:
        leaf = _leaf_steps(value, steps)
        return None if leaf is None else self.quantities(leaf)

    def records(self, values: Sequence[Mapping[str, Any]], depth: int, steps: Steps) -> ResultNode:
        columns: dict[str, None] = {}
        for record in values:
            columns.update(dict.fromkeys(str(k) for k in record))
        shown = values[:MAX_ROWS]
        rows = tuple(
            tuple(
                self.node(record[c], depth + 1, (*steps, None, c))
                if c in record
                else ResultNode("scalar", text="")
                for c in columns
            )
            for record in shown
        )
        quantities = tuple(
            self.quantity(next((r[c] for r in values if r.get(c) is not None), None),
                          (*steps, None, c))
            for c in columns
        )  # fmt: skip
        hidden = len(values) - len(shown)
        return ResultNode("records", columns=tuple(columns), rows=rows, hidden=hidden,
                          column_quantities=quantities)  # fmt: skip

    def list(self, values: Sequence[Any], depth: int, steps: Steps) -> ResultNode:
        quantity = self.quantity(list(values), steps)
        if all(_is_scalar(v) for v in values):
            if len(values) <= INLINE_ITEMS or not all(_is_number(v) for v in values):
                node = _inline(values) if len(values) <= INLINE_ITEMS else _summary(values)
            else:
                node = _summary(values)
            return replace(node, quantity=quantity)
        if all(isinstance(v, Mapping) for v in values):
            if all(_flat(record) for record in values):
                return self.records(values, depth, steps)
            shown = values[:MAX_ROWS]  # records holding tables: one table each
            return ResultNode(
                "list",
                items=tuple(self.node(v, depth + 1, (*steps, None)) for v in shown),
                hidden=len(values) - len(shown),
            )
        if all(
            isinstance(v, list) and 0 < len(v) <= MAX_COLUMNS and all(_is_scalar(x) for x in v)
            for v in values
        ):
            return replace(_matrix(values), quantity=quantity)
        if all(isinstance(v, list) for v in values) and len(values) > MAX_ROWS:
            sizes = [len(v) for v in values]
            return ResultNode(
                "summary",
                text=f"{len(values)} lists of {min(sizes)}–{max(sizes)} values each",
                quantity=quantity,
            )
        shown = values[:MAX_ROWS]
        return ResultNode(
            "list",
            items=tuple(self.node(v, depth + 1, (*steps, None)) for v in shown),
            hidden=len(values) - len(shown),
        )

    def node(self, value: Any, depth: int, steps: Steps) -> ResultNode:
        if _is_scalar(value):
            node = _scalar(value)
            return replace(node, quantity=self.quantity(value, steps)) if node.numeric else node
        if depth >= MAX_DEPTH:
            return ResultNode("json", text=json.dumps(value))
        if isinstance(value, Mapping):
            return ResultNode(
                "object",
                entries=tuple(
                    (str(k), self.node(v, depth + 1, (*steps, str(k)))) for k, v in value.items()
                ),
            )
        if isinstance(value, list | tuple):
            if not value:
                return ResultNode("inline", text="[]")
            return self.list(value, depth, steps)
        return ResultNode("json", text=json.dumps(value, default=str))


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


def result_view(
    result: Mapping[str, Any],
    *,
    leave_out: Sequence[str] = (),
    quantities: Quantities = _nothing_known,
) -> ResultNode:
    """The tree of a result document, without the keys in ``leave_out`` (the page
    shows the notes on their own); ``quantities`` says what its numbers are."""
    shown = {k: v for k, v in result.items() if k not in leave_out}
    return _Viewer(quantities).node(shown, 0, ())
