"""The canonical hash of an execution request, the identity behind ``Idempotency-Key``.

Two requests are the same when their validated inputs are the same: key order is
irrelevant and numbers are normalised (``2`` and ``2.0`` are one value), so the hash is
computed from the inputs as the process validated them, the very form the store keeps.
That lets a store recompute every stored hash when this definition changes.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from typing import Any

__all__ = ["canonical_json", "request_hash"]

_EXACT_INT = 2**53


def _normalised(value: Any) -> Any:
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return value
    if isinstance(value, int | float):
        number = float(value)
        if number.is_integer() and abs(number) < _EXACT_INT:
            return int(number)
        return number
    if isinstance(value, Mapping):
        return {str(k): _normalised(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_normalised(v) for v in value]
    return value


def canonical_json(value: Any) -> str:
    """``value`` as canonical JSON: sorted keys, no spaces, integral numbers as integers."""
    return json.dumps(_normalised(value), sort_keys=True, separators=(",", ":"), allow_nan=False)


def request_hash(process_id: str, inputs: Mapping[str, Any]) -> str:
    """SHA-256 of the process ID and its validated inputs in canonical form."""
    canonical = canonical_json({"process": process_id, "inputs": inputs})
    return hashlib.sha256(canonical.encode()).hexdigest()
