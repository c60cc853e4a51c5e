"""The digest of what a job computed, ``result_hash``: equal on every machine that
computes the same numbers to 12 significant digits.

A number is reduced to its 12 significant digits as an integer significand and a
decimal exponent (``1.5`` -> ``(150000000000, -11)``), magnitudes below
:data:`ZERO_BELOW` count as 0, and ``-0`` is 0; integers and integral floats are one
value.  The digest covers the result document's values of every type, leaving out
execution metadata (:data:`EXECUTION_KEYS`: IDs, timings, the provenance and the hash
themselves), plus each NPZ file's data arrays (their names, shapes, kinds and values;
not the archive's description entries nor its compressed bytes).

Rounding has edges: two values a hair either side of a 12-digit rounding boundary
(``1.0000000000005 +- 1e-16``) round apart, so two machines can disagree there.
"""

from __future__ import annotations

import hashlib
import io
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from worker.request_hash import canonical_json

__all__ = [
    "EXECUTION_KEYS",
    "SIGNIFICANT_DIGITS",
    "ZERO_BELOW",
    "array_digest",
    "canonical_number",
    "canonical_values",
    "npz_arrays_digest",
    "result_hash",
    "significands",
]

SIGNIFICANT_DIGITS = 12
#: Magnitudes below this count as 0 (round-off around a zero differs between machines).
ZERO_BELOW = 1e-12
#: Result members that describe the execution, not its outcome, left out at every depth.
EXECUTION_KEYS = frozenset(
    {"provenance", "result_hash", "reused_from", "job_id", "jobID", "missing_chunks"}
)
#: The exponent codes of non-finite values (their significand is 0).
_NAN, _POS_INF, _NEG_INF = 32767, 32766, 32765
_TOP = 10**SIGNIFICANT_DIGITS
_BOTTOM = 10 ** (SIGNIFICANT_DIGITS - 1)


def _scaled(values: NDArray[np.float64], shift: NDArray[np.int64]) -> NDArray[np.float64]:
    """``values * 10**shift`` with an exact power of ten (one rounding, the product's)."""
    up = np.where(shift >= 0, shift, 0)
    down = np.where(shift < 0, -shift, 0)
    return values * (10.0**up) / (10.0**down)


def significands(values: NDArray[Any]) -> tuple[NDArray[np.int64], NDArray[np.int16]]:
    """Each value as ``significand * 10**exponent`` with a 12-digit significand.

    ``values``: a float array of any shape ``(...)``; returns the significands
    ``(...)`` int64 (``10**11 <= |s| < 10**12``, or 0) and the exponents ``(...)``
    int16.  Zero, magnitudes below :data:`ZERO_BELOW` and non-finite values have
    significand 0 (NaN and +-inf their own exponent codes).
    """
    x = np.asarray(values, dtype=np.float64)
    finite = np.isfinite(x)
    small = ~finite | (np.abs(x) < ZERO_BELOW)
    safe = np.where(small, 1.0, x)
    exponent = np.floor(np.log10(np.abs(safe))).astype(np.int64) - (SIGNIFICANT_DIGITS - 1)
    mantissa = np.rint(_scaled(safe, -exponent))
    # log10 may be off by one at a power of ten, and rounding may carry to 10**12.
    for _ in range(2):
        over = np.abs(mantissa) >= _TOP
        under = np.abs(mantissa) < _BOTTOM
        exponent = exponent + over - under
        mantissa = np.rint(_scaled(safe, -exponent))
    significand = np.where(small, 0, mantissa).astype(np.int64)
    codes = np.where(np.isnan(x), _NAN, np.where(x > 0, _POS_INF, _NEG_INF))
    exponents = np.where(finite, np.where(small, 0, exponent), codes).astype(np.int16)
    return significand, exponents


def canonical_number(value: float) -> str:
    """One number's canonical text: ``"<significand>e<exponent>"`` (``"0e0"`` for 0)."""
    significand, exponent = significands(np.asarray([value]))
    return f"{int(significand[0])}e{int(exponent[0])}"


def canonical_values(value: Any) -> Any:
    """``value`` (a JSON-able result) with every number canonical and the execution
    metadata (:data:`EXECUTION_KEYS`) left out; mappings keep their keys (sorted when
    serialised), sequences their order."""
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return value
    if isinstance(value, int | float):
        return canonical_number(float(value))
    if isinstance(value, Mapping):
        return {
            str(k): canonical_values(v) for k, v in value.items() if str(k) not in EXECUTION_KEYS
        }
    if isinstance(value, list | tuple):
        return [canonical_values(v) for v in value]
    return str(value)


def array_digest(array: NDArray[Any]) -> str:
    """SHA-256 of one array: its kind, shape and values (floats to 12 digits)."""
    a = np.asarray(array)
    digest = hashlib.sha256(f"{a.dtype.kind}:{list(a.shape)}".encode())
    if a.dtype.kind == "c":
        a = np.stack([a.real, a.imag], axis=-1)
    if a.dtype.kind in "fc":
        significand, exponent = significands(a)
        digest.update(significand.astype("<i8").tobytes())
        digest.update(exponent.astype("<i2").tobytes())
    elif a.dtype.kind in "iub":
        digest.update(a.astype("<i8").tobytes())
    else:  # strings and the like: their text
        digest.update("\x1f".join(str(v) for v in a.ravel().tolist()).encode())
    return digest.hexdigest()


def npz_arrays_digest(data: bytes, description_entries: Iterable[str]) -> dict[str, str]:
    """The :func:`array_digest` of every data array of an NPZ file's ``data`` (bytes),
    by name, leaving out its ``description_entries`` (``axes``, ``units``, ...)."""
    skipped = set(description_entries)
    with np.load(io.BytesIO(data), allow_pickle=False) as archive:
        return {
            name: array_digest(archive[name])
            for name in sorted(archive.files)
            if name not in skipped
        }


def result_hash(result: Mapping[str, Any], files: Mapping[str, Mapping[str, str]]) -> str:
    """SHA-256 of the canonical ``result`` values and the ``files``' array digests
    (file name -> array name -> :func:`array_digest`)."""
    document = {"result": canonical_values(result), "files": {k: dict(v) for k, v in files.items()}}
    return hashlib.sha256(canonical_json(document).encode()).hexdigest()
