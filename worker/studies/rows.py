"""A chunk's designs as arrays: what a chunk job stores and the assembly reads.

Per design: its objectives (NaN where none) and a reason code from a closed set,
:data:`REASON_CODES`: ``refused`` (the process refuses the design; ``reason_field``
names the first field it refuses, as a 422 would), ``no-value`` (some objective has
no value) or ``failed`` (the process raised); 0 for a feasible design.  The messages
are not kept per design: distinct messages are counted once (:class:`ReasonTally`).
A chunk writes its arrays to ``rows.npz`` (one of its artifacts) and the field names
and the tally to its result document, so the assembly reads a chunk at a time and
never a message per design.
"""

from __future__ import annotations

import io
from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "FAILED",
    "FEASIBLE",
    "NO_VALUE",
    "OTHER_MESSAGES",
    "REASON_CODES",
    "REFUSED",
    "ROWS_FILE",
    "ChunkRows",
    "ReasonTally",
]

FEASIBLE, REFUSED, NO_VALUE, FAILED = 0, 1, 2, 3
#: Reason codes by number, as the result and ``designs.npz`` spell them.
REASON_CODES = ("", "refused", "no-value", "failed")
#: The artifact of a chunk job holding its arrays.
ROWS_FILE = "rows.npz"
#: Distinct messages counted one by one (per chunk and in the assembly); the others
#: are counted together per code and field, under :data:`OTHER_MESSAGES`.
MAX_MESSAGES = 50
OTHER_MESSAGES = "(other messages)"


@dataclass
class ReasonTally:
    """Designs per (code, field, message), at most :data:`MAX_MESSAGES` messages kept
    apart (the least frequent fold into their code and field's other messages)."""

    counts: Counter[tuple[int, str, str]] = field(default_factory=Counter)

    def add(self, code: int, field_name: str, message: str, designs: int = 1) -> None:
        self.counts[(code, field_name, message)] += designs
        if len(self.counts) > 2 * MAX_MESSAGES:
            self._fold()

    def merge(self, other: ReasonTally) -> None:
        for (code, field_name, message), designs in other.counts.items():
            self.add(code, field_name, message, designs)

    def _fold(self) -> None:
        kept = dict(self.counts.most_common(MAX_MESSAGES))
        folded: Counter[tuple[int, str, str]] = Counter(kept)
        for (code, field_name, message), designs in self.counts.items():
            if (code, field_name, message) not in kept:
                folded[(code, field_name, OTHER_MESSAGES)] += designs
        self.counts = folded

    def most_common(self, count: int) -> list[dict[str, Any]]:
        """The ``count`` most frequent reasons, as the study's result lists them."""
        return [
            {"reason_code": REASON_CODES[code], "reason_field": field_name,
             "reason": message, "designs": designs}
            for (code, field_name, message), designs in self.counts.most_common(count)
        ]  # fmt: skip

    def as_json(self) -> list[list[Any]]:
        return [[code, f, m, n] for (code, f, m), n in self.counts.items()]

    @classmethod
    def from_json(cls, entries: Iterable[Sequence[Any]]) -> ReasonTally:
        tally = cls()
        for code, field_name, message, designs in entries:
            tally.add(int(code), str(field_name), str(message), int(designs))
        return tally


@dataclass(frozen=True)
class ChunkRows:
    """Designs ``start`` to ``stop`` of a study, evaluated: ``objectives`` (n, k), NaN
    where none; ``codes`` (n,) int8 reason codes; ``fields`` (n,) int16 indices into
    ``field_names`` (``field_names[0]`` is ``""``: no field); ``tally`` the messages."""

    start: int
    stop: int
    objectives: NDArray[np.float64]
    codes: NDArray[np.int8]
    fields: NDArray[np.int16]
    field_names: tuple[str, ...]
    tally: ReasonTally
    engine: str

    def artifact_bytes(self) -> bytes:
        """The arrays as an uncompressed NPZ (``rows.npz``)."""
        buffer = io.BytesIO()
        np.savez(buffer, allow_pickle=False, objectives=self.objectives,
                 reason_code=self.codes, reason_field=self.fields)  # fmt: skip
        return buffer.getvalue()

    def result(self) -> dict[str, Any]:
        """The chunk's result document (its arrays are in ``rows.npz``)."""
        return {
            "start": self.start,
            "stop": self.stop,
            "engine": self.engine,
            "rows": ROWS_FILE,
            "fields": list(self.field_names),
            "reasons": self.tally.as_json(),
        }

    @classmethod
    def stored(cls, result: Mapping[str, Any], data: bytes | None, k: int) -> ChunkRows:
        """A chunk as stored: its result document and its ``rows.npz`` (a result of an
        older chunk, with a ``rows`` list of designs, is read too)."""
        if not isinstance(result.get("rows"), str):
            return cls._listed(result, k)
        if data is None:
            raise ValueError(f"chunk [{result['start']}, {result['stop']}) has no {ROWS_FILE}")
        with np.load(io.BytesIO(data), allow_pickle=False) as arrays:
            objectives = np.asarray(arrays["objectives"], dtype=np.float64).reshape(-1, k)
            codes = np.asarray(arrays["reason_code"], dtype=np.int8)
            fields = np.asarray(arrays["reason_field"], dtype=np.int16)
        return cls(int(result["start"]), int(result["stop"]), objectives, codes, fields,
                   tuple(result["fields"]), ReasonTally.from_json(result["reasons"]),
                   str(result.get("engine", "per-design")))  # fmt: skip

    @classmethod
    def _listed(cls, result: Mapping[str, Any], k: int) -> ChunkRows:
        rows = list(result["rows"])
        objectives = np.array(
            [[np.nan if v is None else float(v) for v in row["objectives"]] for row in rows],
            dtype=np.float64,
        ).reshape(-1, k)
        tally = ReasonTally()
        codes = np.zeros(len(rows), dtype=np.int8)
        for n, row in enumerate(rows):
            reason = row["reason"]
            if reason is not None:
                code = REFUSED if reason.startswith("refused") else (
                    FAILED if reason.startswith("failed") else NO_VALUE)  # fmt: skip
                codes[n] = code
                tally.add(code, "", reason)
        return cls(int(result["start"]), int(result["stop"]), objectives, codes,
                   np.zeros(len(rows), dtype=np.int16), ("",), tally,
                   "per-design")  # fmt: skip
