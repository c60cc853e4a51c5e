"""The ``Prefer`` request header (RFC 7240), as OGC API - Processes uses it."""

from __future__ import annotations

import math

__all__ = ["MAX_WAIT_S", "requested_wait"]

#: The longest a synchronous request is held open, whatever it asks for.
MAX_WAIT_S = 60.0


def requested_wait(prefer: str | None) -> float | None:
    """Seconds of ``wait=N`` in a Prefer header (capped at MAX_WAIT_S), or None when the
    client did not ask to wait, asked for ``respond-async``, or gave a non-finite or
    non-positive N (then the preference is ignored: no ``Preference-Applied``)."""
    if not prefer:
        return None
    wait: float | None = None
    for preference in prefer.split(","):
        token = preference.split(";")[0].strip().lower()
        if token == "respond-async":
            return None
        name, _, value = token.partition("=")
        if name.strip() == "wait":
            try:
                wait = float(value.strip().strip('"'))
            except ValueError:
                continue
    if wait is None or not math.isfinite(wait) or wait <= 0:
        return None
    return min(wait, MAX_WAIT_S)
