"""Every request gets an ID: the client's ``X-Request-ID`` when it is a sane token, else
a new one.  It is echoed in the response's ``X-Request-ID`` and bound to every log line
made while the request is served (uvicorn's access line included), so one request's
lines can be found across the API's log (a pure ASGI middleware, the outermost)."""

from __future__ import annotations

import re
import uuid

from starlette.datastructures import Headers
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from worker.logs import log_context

__all__ = ["REQUEST_ID_HEADER", "RequestId", "request_id_for"]

REQUEST_ID_HEADER = "X-Request-ID"

#: What a client's ID may be: a proxy's or a tracer's token, not free text for the log.
_ACCEPTED = re.compile(r"[A-Za-z0-9][A-Za-z0-9._:/+=@-]{0,127}")


def request_id_for(headers: Headers) -> str:
    """The request's ID: the client's ``X-Request-ID`` if it is 1-128 characters of
    letters, digits and ``._:/+=@-``; otherwise a new one (32 hex digits)."""
    given = headers.get(REQUEST_ID_HEADER, "").strip()
    return given if _ACCEPTED.fullmatch(given) else uuid.uuid4().hex


class RequestId:
    """Gives each HTTP request its ID (see the module docstring)."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        request_id = request_id_for(Headers(scope=scope))
        header = (REQUEST_ID_HEADER.lower().encode(), request_id.encode())

        async def send_with_id(message: Message) -> None:
            if message["type"] == "http.response.start":
                headers = [(k, v) for k, v in message.get("headers", []) if k.lower() != header[0]]
                message = {**message, "headers": [*headers, header]}
            await send(message)

        with log_context(request_id=request_id):
            await self.app(scope, receive, send_with_id)
