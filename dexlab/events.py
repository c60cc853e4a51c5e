"""Reading ``GET /v1/jobs/{jobID}/events`` (Server-Sent Events), line by line.

The service sends a ``progress`` event (JSON ``{"status", "progress", "message"}``) at
once and at every change until the job ends, then closes the stream (or closes it after
its lifetime; the client then reads the status and opens a new one).  This is the
parser of the WHATWG event-stream format both clients feed; it does no I/O.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

__all__ = ["EventStreamParser", "ServerEvent", "progress_of"]


@dataclass(frozen=True)
class ServerEvent:
    """One dispatched event: its ``event`` name (``message`` by default) and ``data``."""

    event: str
    data: str


class EventStreamParser:
    """Feed it the stream's lines (without their line ends); it returns an event when a
    blank line completes one.  Comments (``: ...``) and ``retry:``/``id:`` are skipped."""

    def __init__(self) -> None:
        self._event = ""
        self._data: list[str] = []

    def feed(self, line: str) -> ServerEvent | None:
        if line == "":
            if not self._data:
                self._event = ""
                return None
            event = ServerEvent(self._event or "message", "\n".join(self._data))
            self._event, self._data = "", []
            return event
        if line.startswith(":"):
            return None
        name, _, value = line.partition(":")
        value = value.removeprefix(" ")
        if name == "event":
            self._event = value
        elif name == "data":
            self._data.append(value)
        return None


def progress_of(event: ServerEvent) -> dict[str, Any] | None:
    """The ``{status, progress, message}`` of a ``progress`` event; None for any other
    event or a payload that is not such an object."""
    if event.event != "progress":
        return None
    try:
        payload = json.loads(event.data)
    except ValueError:
        return None
    if not isinstance(payload, dict) or not isinstance(payload.get("status"), str):
        return None
    return payload
