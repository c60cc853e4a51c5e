"""A finished design study's designs, as a table to page, sort, filter and plot.

Read from the study's ``designs.npz`` (:mod:`.files`), once per stored file
(:class:`DesignTables` keeps the last few by their SHA-256): ``GET
/v1/jobs/{jobID}/designs`` pages it (:func:`design_page`), ``.../designs/scatter``
plots two of its columns (:func:`design_scatter`, binned beyond
:data:`SCATTER_POINTS` designs).  Columns are named by keys (``links_0``,
``task_points_d_z_min``: the path with every run of other characters an underscore,
unique), each with its path, unit, symbol and goal.  Problems with a query are
:class:`DesignQueryError` naming the parameter.
"""

from __future__ import annotations

import base64
import hashlib
import io
import json
import re
import threading
from collections import OrderedDict
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "SCATTER_BINS",
    "SCATTER_POINTS",
    "DesignColumn",
    "DesignQuery",
    "DesignQueryError",
    "DesignTable",
    "DesignTables",
    "design_page",
    "design_scatter",
    "read_cursor",
]

#: Beyond this many designs the scatter is answered as 2-D bins (and the front).
SCATTER_POINTS = 10_000
#: Bins per axis of a binned scatter.
SCATTER_BINS = 100
_FIXED = ("index", "feasible", "pareto", "reason_code")


class DesignQueryError(ValueError):
    """A query the table cannot answer; ``parameter`` names the query parameter."""

    def __init__(self, parameter: str, message: str) -> None:
        super().__init__(message)
        self.parameter = parameter


@dataclass(frozen=True)
class DesignColumn:
    """One varied input or objective: its ``key`` in queries, the study's ``path``."""

    key: str
    path: str
    kind: Literal["parameter", "objective"]
    unit: str
    symbol: str = ""
    goal: str = ""


def _keys(names: Sequence[str]) -> list[str]:
    used: set[str] = set(_FIXED)
    keys = []
    for name in names:
        base = re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_") or "column"
        key, n = base, 2
        while key in used:
            key, n = f"{base}_{n}", n + 1
        used.add(key)
        keys.append(key)
    return keys


@dataclass(frozen=True, eq=False)
class DesignTable:
    """Every design of a study: ``values`` (n, p + o) the parameters then the
    objectives (NaN where a design has none), ``index`` (n,), ``feasible`` (n,),
    ``pareto`` (n,) (non-dominated), ``reason_code`` (n,) (an index into
    ``reason_codes``; 0 for a feasible design)."""

    columns: tuple[DesignColumn, ...]
    index: NDArray[np.int64]
    values: NDArray[np.float64]
    feasible: NDArray[np.bool_]
    pareto: NDArray[np.bool_]
    reason_code: NDArray[np.int64]
    reason_codes: tuple[str, ...]
    reason_field: NDArray[np.int64]
    reason_fields: tuple[str, ...]

    @classmethod
    def from_npz(cls, data: bytes) -> DesignTable:
        """The table of a ``designs.npz``'s bytes."""
        with np.load(io.BytesIO(data), allow_pickle=False) as z:
            names = [str(n) for n in z["parameter_names"]] + [str(n) for n in z["objective_names"]]
            units = [str(u) for u in z["parameter_units"]] + [str(u) for u in z["objective_units"]]
            p = len(z["parameter_names"])
            symbols = [""] * p + [str(s) for s in z["objective_symbols"]]
            goals = [""] * p + [str(g) for g in z["objective_goals"]]
            columns = tuple(
                DesignColumn(key, name, "parameter" if j < p else "objective", unit, sym, goal)
                for j, (key, name, unit, sym, goal) in enumerate(
                    zip(_keys(names), names, units, symbols, goals, strict=True)
                )
            )
            index = np.asarray(z["index"], dtype=np.int64)
            values = np.concatenate(
                [np.asarray(z["parameters"], float), np.asarray(z["objectives"], float)], axis=1
            )
            pareto = np.isin(index, np.asarray(z["pareto"], dtype=np.int64))
            return cls(columns, index, values, np.asarray(z["feasible"], dtype=bool), pareto,
                       np.asarray(z["reason_code"], dtype=np.int64),
                       tuple(str(c) for c in z["reason_codes"]),
                       np.asarray(z["reason_field"], dtype=np.int64),
                       tuple(str(f) for f in z["reason_fields"]))  # fmt: skip

    @property
    def count(self) -> int:
        return int(self.index.shape[0])

    def column(self, key: str, parameter: str) -> int:
        """The position of the column ``key`` in ``values``."""
        for j, col in enumerate(self.columns):
            if col.key == key:
                return j
        known = ", ".join(c.key for c in self.columns)
        raise DesignQueryError(parameter, f"no column {key!r}; the columns are {known}")


@dataclass(frozen=True)
class DesignQuery:
    """Which designs, in which order: ``sort`` a column key (``-`` first: descending;
    None: feasible first, then by index), ``feasible``/``pareto`` filters, ``ranges``
    (key, low, high) with None for an open end, ``reason`` a reason code."""

    sort: str | None = None
    feasible: bool | None = None
    pareto: bool | None = None
    ranges: tuple[tuple[str, float | None, float | None], ...] = ()
    reason: str | None = None

    def digest(self) -> str:
        text = json.dumps([self.sort, self.feasible, self.pareto, self.ranges, self.reason])
        return hashlib.sha256(text.encode()).hexdigest()[:16]


def _mask(table: DesignTable, query: DesignQuery) -> NDArray[np.bool_]:
    keep = np.ones(table.count, dtype=bool)
    if query.feasible is not None:
        keep &= table.feasible == query.feasible
    if query.pareto is not None:
        keep &= table.pareto == query.pareto
    if query.reason is not None:
        if query.reason not in table.reason_codes:
            raise DesignQueryError("reason", f"no reason code {query.reason!r}; the codes are "
                                   f"{', '.join(table.reason_codes[1:])}")  # fmt: skip
        keep &= table.reason_code == table.reason_codes.index(query.reason)
    for key, low, high in query.ranges:
        values = (table.index.astype(float) if key == "index"
                  else table.values[:, table.column(key, "range")])  # fmt: skip
        with np.errstate(invalid="ignore"):
            if low is not None:
                keep &= values >= low
            if high is not None:
                keep &= values <= high
    return keep


def _order(table: DesignTable, query: DesignQuery, rows: NDArray[np.intp]) -> NDArray[np.intp]:
    """``rows`` sorted: feasible first, then by the sort column (NaN last), then index."""
    keys: list[NDArray[Any]] = [table.index[rows]]
    if query.sort is not None:
        descending = query.sort.startswith("-")
        key = query.sort.removeprefix("-")
        if key in _FIXED:
            column = {"index": table.index, "feasible": table.feasible,
                      "pareto": table.pareto, "reason_code": table.reason_code}[key]  # fmt: skip
            values = np.asarray(column[rows], dtype=float)
        else:
            values = table.values[rows, table.column(key, "sort")]
        missing = np.isnan(values)
        keys += [np.where(missing, 0.0, -values if descending else values), missing]
    keys.append(~table.feasible[rows])
    return rows[np.lexsort(keys)]


def _cursor(offset: int, query: DesignQuery) -> str:
    raw = json.dumps({"o": offset, "q": query.digest()}).encode()
    return base64.urlsafe_b64encode(raw).decode().rstrip("=")


def read_cursor(cursor: str) -> tuple[int, str]:
    """(offset, query digest) of a cursor :func:`design_page` gave."""
    try:
        raw = base64.urlsafe_b64decode(cursor + "=" * (-len(cursor) % 4))
        state = json.loads(raw)
        return int(state["o"]), str(state["q"])
    except (ValueError, KeyError, TypeError) as exc:
        raise DesignQueryError("cursor", "not a cursor this service gave") from exc


def _offset(cursor: str | None, query: DesignQuery) -> int:
    if cursor is None:
        return 0
    offset, digest = read_cursor(cursor)
    if digest != query.digest() or offset < 0:
        raise DesignQueryError("cursor", "this cursor belongs to another sort or filter: "
                               "start again without it")  # fmt: skip
    return offset


def _number(value: float) -> float | None:
    return None if not np.isfinite(value) else float(value)


def design_page(
    table: DesignTable, query: DesignQuery, limit: int, cursor: str | None
) -> dict[str, Any]:
    """A page of designs: ``designs`` (each with ``index``, ``feasible``, ``pareto``,
    ``reason_code``, ``reason_field`` and ``values`` by column key), ``matched``,
    ``total`` and ``next_cursor`` (None on the last page)."""
    offset = _offset(cursor, query)
    rows = _order(table, query, np.flatnonzero(_mask(table, query)))
    page = rows[offset : offset + limit]
    designs = [
        {
            "index": int(table.index[r]),
            "feasible": bool(table.feasible[r]),
            "pareto": bool(table.pareto[r]),
            "reason_code": table.reason_codes[table.reason_code[r]] or None,
            "reason_field": table.reason_fields[table.reason_field[r]] or None,
            "values": {c.key: _number(table.values[r, j]) for j, c in enumerate(table.columns)},
        }
        for r in page
    ]
    more = offset + limit < rows.size
    return {"designs": designs, "matched": int(rows.size), "total": table.count,
            "next_cursor": _cursor(offset + limit, query) if more else None}  # fmt: skip


def design_scatter(table: DesignTable, x: str, y: str, query: DesignQuery) -> dict[str, Any]:
    """Columns ``x`` and ``y`` of the designs ``query`` keeps that have both values:
    every point (``index``, ``x``, ``y``, ``pareto``) up to :data:`SCATTER_POINTS`,
    else ``bins`` (edges and counts, (SCATTER_BINS, SCATTER_BINS) indexed [x][y]) and
    the Pareto designs as points."""
    jx, jy = table.column(x, "x"), table.column(y, "y")
    keep = _mask(table, query) & np.isfinite(table.values[:, jx]) & np.isfinite(table.values[:, jy])
    rows = np.flatnonzero(keep)

    def points(which: NDArray[np.intp]) -> dict[str, list[Any]]:
        return {"index": table.index[which].tolist(), "x": table.values[which, jx].tolist(),
                "y": table.values[which, jy].tolist(),
                "pareto": table.pareto[which].tolist()}  # fmt: skip

    answer: dict[str, Any] = {"x": x, "y": y, "matched": int(rows.size)}
    if rows.size <= SCATTER_POINTS:
        return {**answer, "points": points(rows), "bins": None}
    counts, x_edges, y_edges = np.histogram2d(
        table.values[rows, jx], table.values[rows, jy], bins=SCATTER_BINS
    )
    front = rows[table.pareto[rows]]
    bins = {"x_edges": x_edges.tolist(), "y_edges": y_edges.tolist(),
            "counts": counts.astype(np.int64).tolist()}  # fmt: skip
    return {**answer, "points": points(front), "bins": bins}


@dataclass
class DesignTables:
    """The last ``capacity`` tables read, by the SHA-256 of their file (a study's file
    shared by reused jobs is read once); safe across threads."""

    capacity: int = 4
    _tables: OrderedDict[str, DesignTable] = field(default_factory=OrderedDict)
    _lock: threading.Lock = field(default_factory=threading.Lock)

    def get(self, etag: str, read: Callable[[], bytes]) -> DesignTable:
        with self._lock:
            table = self._tables.get(etag)
            if table is not None:
                self._tables.move_to_end(etag)
                return table
        table = DesignTable.from_npz(read())
        with self._lock:
            self._tables[etag] = table
            while len(self._tables) > self.capacity:
                self._tables.popitem(last=False)
        return table
