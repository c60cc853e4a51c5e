"""The outer boundary every HTTP request crosses (a pure ASGI middleware).

- Any exception a handler lets escape becomes an ``internal-error`` problem document
  here, and is not re-raised: the server keeps the keep-alive connection usable
  (Starlette's own last-resort handler re-raises, and uvicorn then drops it).
- Request bodies are bounded: a declared or streamed body above ``max_body_bytes`` is
  answered 413 ``request-too-large`` as soon as the limit is passed, without reading
  the rest, so large uploads cost no memory.
- JSON bodies are checked once before any handler sees them: invalid UTF-8, invalid
  JSON (``NaN`` and ``Infinity`` included: they are not JSON) or nesting deeper than
  ``max_json_depth`` are 400 ``malformed-request``.
- ``OPTIONS`` answers 204 with the ``Allow`` of every route on the path.
- Every response carries ``X-Content-Type-Options: nosniff``.
"""

from __future__ import annotations

import json
import logging
from collections.abc import Callable, Iterable
from typing import Any

from starlette.datastructures import Headers
from starlette.responses import Response
from starlette.routing import BaseRoute
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from service.allow import allow_header, allowed_methods
from service.problems import problem_response

__all__ = ["RequestGuard", "json_depth"]

log = logging.getLogger("dexlab.service")

_BODY_METHODS = frozenset({"POST", "PUT", "PATCH"})


class _Malformed(Exception):
    """The body is not what the request says it is; the message says how."""


def json_depth(value: Any) -> int:
    """How deeply arrays and objects nest in a parsed JSON value (a scalar: 0)."""
    deepest = 0
    stack: list[tuple[Any, int]] = [(value, 0)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, dict):
            stack.extend((v, depth + 1) for v in item.values())
            deepest = max(deepest, depth + 1)
        elif isinstance(item, list):
            stack.extend((v, depth + 1) for v in item)
            deepest = max(deepest, depth + 1)
    return deepest


def _refuse_constant(name: str) -> Any:
    raise _Malformed(f"the request body is not valid JSON: {name} is not a JSON number")


def _check_json(body: bytes, max_depth: int) -> None:
    """Raise :class:`_Malformed` unless ``body`` is UTF-8 JSON nested at most
    ``max_depth`` deep."""
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise _Malformed(
            f"the request body is not valid UTF-8 (byte {exc.start}: {exc.reason})"
        ) from None
    try:
        value = json.loads(text, parse_constant=_refuse_constant)
    except json.JSONDecodeError as exc:
        raise _Malformed(
            f"the request body is not valid JSON: {exc.msg} at line {exc.lineno} column {exc.colno}"
        ) from None
    except RecursionError:
        raise _Malformed(f"the request body nests deeper than {max_depth} levels") from None
    if json_depth(value) > max_depth:
        raise _Malformed(f"the request body nests deeper than {max_depth} levels")


def _is_json(headers: Headers) -> bool:
    media = headers.get("content-type", "").split(";")[0].strip().lower()
    return media in ("", "application/json") or media.endswith("+json")


def _replay(body: bytes, receive: Receive) -> Receive:
    """A ``receive`` that hands the app the body already read, then the real channel
    (so the app still hears of a client's disconnect)."""
    sent = False

    async def replayed() -> Message:
        nonlocal sent
        if not sent:
            sent = True
            return {"type": "http.request", "body": body, "more_body": False}
        return await receive()

    return replayed


class RequestGuard:
    """See the module docstring; ``routes`` gives the app's routes (for ``Allow``)."""

    def __init__(
        self,
        app: ASGIApp,
        *,
        routes: Callable[[], Iterable[BaseRoute]],
        max_body_bytes: int,
        max_json_depth: int,
    ) -> None:
        self.app = app
        self.routes = routes
        self.max_body_bytes = max_body_bytes
        self.max_json_depth = max_json_depth

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = False

        async def send_nosniff(message: Message) -> None:
            nonlocal started
            if message["type"] == "http.response.start":
                started = True
                headers = [
                    (k, v) for k, v in message.get("headers", [])
                    if k.lower() != b"x-content-type-options"
                ]  # fmt: skip
                headers.append((b"x-content-type-options", b"nosniff"))
                message = {**message, "headers": headers}
            await send(message)

        try:
            if scope["method"] == "OPTIONS":
                await self._options(scope)(scope, receive, send_nosniff)
                return
            if scope["method"] in _BODY_METHODS:
                screened = await self._read_body(scope, receive)
                if screened is None:  # the client went away mid-body
                    return
                if isinstance(screened, Response):
                    await screened(scope, receive, send_nosniff)
                    return
                receive = _replay(screened, receive)
            await self.app(scope, receive, send_nosniff)
        except Exception as exc:
            log.exception("unhandled error on %s %s", scope["method"], scope.get("path"))
            if started:  # too late for a problem document: the connection must go
                raise
            response = problem_response(
                "internal-error",
                detail=f"An unexpected error occurred ({type(exc).__name__}); it was logged.",
                instance=str(scope.get("path", "")),
            )
            await response(scope, receive, send_nosniff)

    def _options(self, scope: Scope) -> Response:
        methods = allowed_methods(self.routes(), scope)
        if not methods:
            return problem_response(
                "not-found", detail="Not Found", instance=str(scope.get("path", ""))
            )
        return Response(status_code=204, headers={"Allow": allow_header(methods)})

    async def _read_body(self, scope: Scope, receive: Receive) -> bytes | Response | None:
        """The whole body, a problem response (413 or 400), or None on disconnect."""
        headers = Headers(scope=scope)
        path = str(scope.get("path", ""))
        declared = headers.get("content-length")
        if declared is not None and declared.isdigit() and int(declared) > self.max_body_bytes:
            return self._too_large(path)
        chunks: list[bytes] = []
        size = 0
        while True:
            message = await receive()
            if message["type"] == "http.disconnect":
                return None
            chunk = message.get("body", b"")
            size += len(chunk)
            if size > self.max_body_bytes:
                return self._too_large(path)
            chunks.append(chunk)
            if not message.get("more_body", False):
                break
        body = b"".join(chunks)
        if body and _is_json(headers):
            try:
                _check_json(body, self.max_json_depth)
            except _Malformed as exc:
                return problem_response("malformed-request", detail=str(exc), instance=path)
        return body

    def _too_large(self, path: str) -> Response:
        return problem_response(
            "request-too-large",
            detail=f"The request body is larger than {self.max_body_bytes} bytes "
            "(DEXLAB_MAX_BODY_BYTES).",
            instance=path,
            headers={"Connection": "close"},
            max_body_bytes=self.max_body_bytes,
        )
