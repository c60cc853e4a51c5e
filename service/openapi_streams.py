"""The OpenAPI description of the responses that are not JSON documents: an artifact's
bytes and a job's progress stream (Server-Sent Events).  :mod:`service.openapi` puts
them on their operations."""

from __future__ import annotations

from typing import Any

__all__ = ["ARTIFACT_MEDIA_TYPES", "artifact_responses", "event_stream_response"]

#: What an artifact download can be (the process description lists each job's).
ARTIFACT_MEDIA_TYPES = ("image/png", "image/svg+xml", "text/csv", "application/x-npz")


def artifact_responses(responses: dict[str, Any]) -> None:
    """An artifact download's 200 (its media types, its ETag) and 304."""
    binary = {"schema": {"type": "string", "format": "binary"}}
    responses["200"] = {
        "description": "The artifact's bytes (strong ETag; CSV and NPZ as attachments).",
        "content": {media: binary for media in ARTIFACT_MEDIA_TYPES},
        "headers": {"ETag": {"schema": {"type": "string"}, "description": "SHA-256 of the bytes."}},
    }
    responses["304"] = {"description": "Not modified (If-None-Match matched the ETag)."}


#: The events of a job's progress stream: Server-Sent Events, whose each event is
#: described under ``x-itemSchema`` (OpenAPI 3.2's ``itemSchema``, which 3.1 lacks).
_PROGRESS_EVENT = {
    "type": "object",
    "required": ["event", "data"],
    "properties": {
        "event": {"const": "progress"},
        "data": {
            "type": "string",
            "contentMediaType": "application/json",
            "contentSchema": {"$ref": "#/components/schemas/ProgressEvent"},
        },
    },
}
_RETRY_HINT = {
    "type": "object",
    "required": ["retry"],
    "properties": {"retry": {"type": "integer", "minimum": 0, "description": "Milliseconds."}},
}
_STREAM_EXAMPLE = (
    "retry: 2000\n\n"
    'event: progress\ndata: {"status":"running","progress":50,"message":"plots"}\n\n'
    ": still running\n\n"
    'event: progress\ndata: {"status":"successful","progress":100,"message":"done"}\n\n'
)


def event_stream_response(responses: dict[str, Any]) -> None:
    """The progress stream's 200: the stream, and each event's shape."""
    responses["200"]["content"] = {
        "text/event-stream": {
            "schema": {
                "type": "string",
                "description": "Server-Sent Events: a `retry` hint (milliseconds) first, "
                "then a `progress` event whose `data` is a `ProgressEvent` JSON document, "
                "at once and at every change until the job ends; a `: still running` "
                "comment line every 15 s on a quiet stream.",
            },
            "x-itemSchema": {"oneOf": [_RETRY_HINT, _PROGRESS_EVENT]},
            "example": _STREAM_EXAMPLE,
        }
    }
