"""Which routes answer without an API key (every other one needs a key once any exists).

Public: health, the API description and its docs, the landing pages, the process
list and each process's description (not its execution), the methods, the problem
types, the OGC landing page, conformance and processes, ``/metrics`` (counts only),
static files, the login page and logout; ``OPTIONS`` anywhere (a path's ``Allow``, a
CORS preflight).  A session cookie (not a Bearer key) may read and post the pages'
forms, nothing else.
"""

from __future__ import annotations

import re

__all__ = ["ANONYMOUS_PREFIXES", "is_public", "session_may"]

_PUBLIC_PATHS = frozenset(
    {
        "/",
        "/v1",
        "/v1/processes",
        "/docs",
        "/redoc",
        "/openapi.json",
        "/favicon.ico",
        "/metrics",
        "/methods",
        "/ogc",
        "/ogc/",
        "/ogc/conformance",
        "/ogc/processes",
        "/login",
    }
)
_PUBLIC_PREFIXES = ("/health/", "/static/", "/methods/", "/problems/", "/docs/")
#: A process description (not its execution).
_PUBLIC_PATTERNS = (re.compile(r"/v1/processes/[^/]+"), re.compile(r"/ogc/processes/[^/]+"))
#: Public routes that never show who is asking: no need to look at keys at all.
ANONYMOUS_PREFIXES = ("/health/", "/static/", "/metrics", "/openapi.json", "/favicon.ico")
#: Forms a session may post (each checks its CSRF token).
_FORM_POSTS = frozenset({"/login", "/logout"})
_READS = frozenset({"GET", "HEAD"})


def is_public(method: str, path: str) -> bool:
    """Whether ``method path`` answers without a key (a concrete path, or an OpenAPI
    path template: a ``{parameter}`` stands for one segment)."""
    if method == "OPTIONS":  # the Allow of a path, or a CORS preflight
        return True
    if method == "POST":
        return path in _FORM_POSTS
    if method not in _READS:
        return False
    return (
        path in _PUBLIC_PATHS
        or path.startswith(_PUBLIC_PREFIXES)
        or any(p.fullmatch(path) for p in _PUBLIC_PATTERNS)
    )


def session_may(method: str, path: str) -> bool:
    """Whether a session cookie (not a Bearer key) may make this request."""
    return method in _READS or path.startswith("/pages/") or path in _FORM_POSTS
