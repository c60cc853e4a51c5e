"""The one gate every HTTP request passes: who is asking, and may they be here.

A pure ASGI middleware, before routing, so no route can be forgotten:

- With no API key in the store the service is open: every request is the anonymous
  operator (owner ``""``), as before keys existed.
- With keys, the public routes (:mod:`service.auth.public_routes`: health, the API
  description and docs, the landing pages, the process list and descriptions, the
  methods, problem types, the OGC landing, conformance and processes, ``/metrics``,
  static files and the login page) answer anyone, from the keys as last read (they
  never wait for the store, so they answer while it is down); every other route needs
  ``Authorization: Bearer <secret>`` or a session cookie, and answers 401
  ``/problems/unauthorized`` with ``WWW-Authenticate: Bearer`` without one.  A wrong
  or revoked key is 401 wherever it is sent to a protected route.
- A session cookie reads (GET, HEAD) and posts the pages' forms (``/pages/...``,
  ``/logout``, which check its CSRF token); other writes (``POST .../execution``,
  ``DELETE /v1/jobs/...``) need the Bearer header, so no other site can make a
  browser write through the JSON API.

The identity goes into the request's state (:data:`service.auth.IdentityDep`).
"""

from __future__ import annotations

from typing import Any

from starlette.datastructures import Headers
from starlette.requests import Request
from starlette.types import ASGIApp, Receive, Scope, Send

from service.auth.authenticator import Authenticator
from service.auth.errors import Unauthenticated
from service.auth.identity import Identity
from service.auth.public_routes import ANONYMOUS_PREFIXES, is_public, session_may
from service.auth.sessions import COOKIE_NAME
from service.errors import dexlab_problem
from service.pages.problem_page import as_page_if_asked
from worker.errors import DexlabError, StoreUnavailable

__all__ = ["AuthGate"]

_NOBODY = Identity(name="", admin=False, keys_on=True, via="none")


class AuthGate:
    """See the module docstring."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        method, path = scope["method"], str(scope["path"])
        try:
            identity = await self._identity(scope, method, path)
        except DexlabError as exc:
            request = Request(scope, receive)
            response = as_page_if_asked(request, dexlab_problem(request, exc))
            await response(scope, receive, send)
            return
        scope.setdefault("state", {})["identity"] = identity
        await self.app(scope, receive, send)

    async def _identity(self, scope: Scope, method: str, path: str) -> Identity:
        """The caller, or the exception that refuses the request."""
        public = is_public(method, path)
        if public and path.startswith(ANONYMOUS_PREFIXES):
            return _NOBODY
        auth: Any = getattr(scope["app"].state, "auth", None)
        if not isinstance(auth, Authenticator):
            raise StoreUnavailable("The service is starting or stopping; try again.")
        headers = Headers(scope=scope)
        if public:  # answers anyone, whatever came with it, and never waits for the store
            try:
                return auth.identify_now(headers)
            except (Unauthenticated, StoreUnavailable):
                return _NOBODY
        identity = await auth.identify(headers)
        if identity.via in ("open", "bearer"):
            return identity
        if identity.via == "session":
            if session_may(method, path):
                return identity
            raise Unauthenticated(
                "A browser session reads and posts the pages' forms; this request needs "
                "the key itself: send 'Authorization: Bearer <secret>'."
            )
        if f"{COOKIE_NAME}=" in headers.get("cookie", ""):
            raise Unauthenticated(
                "Your session has ended (it expired, or its key was "
                "revoked); log in again at /login."
            )
        raise Unauthenticated()
