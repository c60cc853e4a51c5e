"""The execution mode of an OGC execute request (18-062r2, 7.11.2.3).

The ``Prefer`` header (RFC 7240) may ask for ``respond-async``, ``respond-sync`` or
``wait=N``.  A process that can run both ways runs synchronously unless the client
prefers ``respond-async``; one that can only run asynchronously (no ``sync-execute``
in its job control options, or a request above its ``sync_cost_limit``) always does.
A synchronous answer waits at most ``wait=N`` seconds, and never more than
:data:`service.preferences.MAX_WAIT_S`; a job not done by then is answered the
asynchronous way (``201`` and its status).  ``Preference-Applied`` names the
preferences the answer honoured.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from service.preferences import MAX_WAIT_S

__all__ = ["ExecutionMode", "Preferences", "execution_mode", "parse_prefer"]


@dataclass(frozen=True)
class Preferences:
    """What a ``Prefer`` header asks for."""

    respond_async: bool = False
    respond_sync: bool = False
    wait_s: float | None = None


@dataclass(frozen=True)
class ExecutionMode:
    """How to answer: synchronously (waiting at most ``wait_s``) or not, and the
    ``Preference-Applied`` value for each outcome (None: no header)."""

    synchronous: bool
    wait_s: float
    applied_if_sync: str | None
    applied_if_async: str | None


def parse_prefer(header: str | None) -> Preferences:
    """The preferences in a ``Prefer`` header; unknown ones, and a ``wait`` that is not
    a positive finite number, are ignored (RFC 7240: a preference is optional)."""
    respond_async = respond_sync = False
    wait: float | None = None
    for preference in (header or "").split(","):
        token = preference.split(";")[0].strip().lower()
        name, _, value = token.partition("=")
        name = name.strip()
        if name == "respond-async":
            respond_async = True
        elif name == "respond-sync":
            respond_sync = True
        elif name == "wait":
            try:
                seconds = float(value.strip().strip('"'))
            except ValueError:
                continue
            if math.isfinite(seconds) and seconds > 0:
                wait = seconds
    return Preferences(respond_async, respond_sync, wait)


def execution_mode(preferences: Preferences, can_run_sync: bool) -> ExecutionMode:
    """The mode the standard asks for, given what this request allows."""
    if preferences.respond_async:
        return ExecutionMode(False, 0.0, None, "respond-async")
    if not can_run_sync:
        return ExecutionMode(False, 0.0, None, None)
    wait = min(preferences.wait_s, MAX_WAIT_S) if preferences.wait_s else MAX_WAIT_S
    applied = []
    if preferences.respond_sync:
        applied.append("respond-sync")
    if preferences.wait_s:
        applied.append(f"wait={wait:g}")
    return ExecutionMode(True, wait, ", ".join(applied) or None, None)
