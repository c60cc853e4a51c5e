"""HTTP request latency by route template, method and status (a pure ASGI middleware).

The route is the template the request matched (``/v1/jobs/{job_id}``), never the raw
path, so the label's values are bounded by the app's routes; a request no route takes
is ``unmatched``, a method outside HTTP's usual ones ``other``.  These figures belong
to this API process (each replica exports its own; Prometheus adds them up).
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Iterable, Iterator
from typing import Any

from prometheus_client import CollectorRegistry, Histogram
from starlette.routing import BaseRoute
from starlette.types import ASGIApp, Message, Receive, Scope, Send

__all__ = ["HttpLatency", "http_latency_histogram", "route_template"]

_METHODS = frozenset({"GET", "HEAD", "POST", "PUT", "PATCH", "DELETE", "OPTIONS"})
UNMATCHED = "unmatched"


def http_latency_histogram(registry: CollectorRegistry) -> Histogram:
    """``dexlab_http_request_duration_seconds{route, method, status}`` on ``registry``."""
    return Histogram(
        "dexlab_http_request_duration_seconds",
        "Time to answer an HTTP request (to the end of its body), by route template, "
        "method and status.",
        labelnames=("route", "method", "status"),
        registry=registry,
    )


def _template(route: object) -> str | None:
    template = getattr(route, "path_format", None)  # a Mount's ends in /{path}
    return template if isinstance(template, str) else None


def _templates(routes: Iterable[Any]) -> Iterator[tuple[re.Pattern[str], str]]:
    """``(regex, template)`` of every route, those of included routers too."""
    for route in routes:
        contexts = getattr(route, "effective_route_contexts", None)  # FastAPI's included
        if callable(contexts):
            yield from _templates(contexts())
            continue
        regex, template = getattr(route, "path_regex", None), _template(route)
        if isinstance(regex, re.Pattern) and template is not None:
            yield regex, template


def _route_path(scope: Scope) -> str:
    """The path the routes see: without the root path a proxy mounted the app at."""
    path, root = str(scope["path"]), str(scope.get("root_path", ""))
    if root and path.startswith(root) and path[len(root) : len(root) + 1] in ("", "/"):
        return path[len(root) :] or "/"
    return path


def route_template(scope: Scope, routes: Iterable[BaseRoute]) -> str:
    """The template of the route that took the request; for a request answered before
    routing (``OPTIONS``, a refused body, a missing key), the first route whose path
    matches; :data:`UNMATCHED` if none."""
    taken = _template(scope.get("route"))
    if taken is not None:
        return taken
    path = _route_path(scope)
    for regex, template in _templates(routes):
        if regex.match(path):
            return template
    return UNMATCHED


class HttpLatency:
    """Observes every HTTP request in ``histogram`` (see the module docstring)."""

    def __init__(
        self, app: ASGIApp, *, histogram: Histogram, routes: Callable[[], Iterable[BaseRoute]]
    ) -> None:
        self.app = app
        self.histogram = histogram
        self.routes = routes

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = time.perf_counter()
        status = 500  # no response started: the server answers 500 or drops it

        async def send_noting_status(message: Message) -> None:
            nonlocal status
            if message["type"] == "http.response.start":
                status = int(message["status"])
            await send(message)

        try:
            await self.app(scope, receive, send_noting_status)
        finally:
            method = scope["method"] if scope["method"] in _METHODS else "other"
            self.histogram.labels(
                route_template(scope, self.routes()), method, str(status)
            ).observe(time.perf_counter() - started)
