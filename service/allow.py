"""Which methods a path accepts, across every route that matches it (``Allow``).

Starlette answers 405 with the methods of the first route whose path matches, so
``/v1/jobs/{id}`` (a GET route and a DELETE route) would say ``Allow: GET``.  This
looks at all of them.
"""

from __future__ import annotations

from collections.abc import Iterable

from starlette.routing import BaseRoute, Match
from starlette.types import Scope

__all__ = ["allow_header", "allowed_methods"]


_METHODS = ("GET", "HEAD", "POST", "PUT", "PATCH", "DELETE")


def allowed_methods(routes: Iterable[BaseRoute], scope: Scope) -> frozenset[str]:
    """Every method some route accepts for the request's path (empty: no such path).

    Each route is asked whether it fully matches the path with each method (included
    routers answer for their own routes); any known path accepts OPTIONS."""
    routes = list(routes)
    methods = {
        method
        for method in _METHODS
        if any(route.matches({**scope, "method": method})[0] is Match.FULL for route in routes)
    }
    if not methods:
        return frozenset()
    methods.add("OPTIONS")
    return frozenset(methods)


def allow_header(methods: Iterable[str]) -> str:
    """The ``Allow`` header value, in a stable order."""
    order = ["GET", "HEAD", "POST", "PUT", "PATCH", "DELETE", "OPTIONS"]
    return ", ".join(sorted(set(methods), key=lambda m: (order.index(m) if m in order else 99, m)))
