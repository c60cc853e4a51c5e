"""The login page: a browser turns an API key into a session cookie.

- ``GET /login``: the form (or who is signed in, or that the service has no keys);
- ``POST /login``: the form field ``key``; a live key sets the session cookie
  (HttpOnly, ``SameSite=Strict``, ``Secure`` over https) and sends the browser on to
  ``next`` (a path on this service) with 303; a wrong one redraws the form, 401;
- ``POST /logout``: clears the cookie (the form carries the session's CSRF token).

Both posts refuse a form from another site (:mod:`service.pages.forms`).  Pages, not
API operations: left out of the OpenAPI document.
"""

from __future__ import annotations

import logging
from typing import Annotated, Any

from fastapi import APIRouter, Query, Request
from fastapi.responses import HTMLResponse, RedirectResponse
from starlette.responses import Response

from service.auth.authenticator import Authenticator
from service.auth.identity import IdentityDep
from service.auth.sessions import COOKIE_NAME
from service.deps import ApiDep
from service.pages.forms import check_csrf, check_form_origin, read_form
from service.pages.renderer import Pages
from service.problems import problem_document

__all__ = ["router"]

log = logging.getLogger("dexlab.service")

router = APIRouter(include_in_schema=False)

_MAX_TARGET = 2000


def _local(target: str) -> str:
    """``target`` if it is a path on this service (never another site), else ``/``."""
    if (
        target.startswith("/")
        and not target.startswith(("//", "/login", "/logout"))
        and "\\" not in target
        and len(target) <= _MAX_TARGET
        and target.isprintable()
    ):
        return target
    return "/"


def _auth(request: Request) -> Authenticator:
    auth: Authenticator = request.app.state.auth
    return auth


def _page(
    request: Request,
    pages: Pages,
    *,
    keys_on: bool,
    next_path: str,
    session_s: float,
    problem: dict[str, Any] | None = None,
) -> HTMLResponse:
    status = 200 if problem is None else 401
    headers = {"WWW-Authenticate": 'Bearer realm="dexlab"'} if problem is not None else None
    return pages.render(
        request,
        "login.html",
        {
            "keys_on": keys_on,
            "next": next_path,
            "session_hours": f"{session_s / 3600:g}",
            "problem": problem,
        },
        status_code=status,
        headers=headers,
    )


@router.get("/login")
async def login_page(
    request: Request, api: ApiDep, next: Annotated[str, Query(max_length=_MAX_TARGET)] = "/"
) -> HTMLResponse:
    table = await _auth(request).table()
    return _page(
        request,
        api.pages,
        keys_on=table.configured,
        next_path=_local(next),
        session_s=api.settings.session_seconds,
    )


@router.post("/login")
async def log_in(request: Request, api: ApiDep) -> Response:
    check_form_origin(request)
    form = await read_form(request)
    target = _local(form.get("next", "/"))
    auth = _auth(request)
    table = await auth.table()
    if not table.configured:
        return RedirectResponse(target, status_code=303)
    key = await auth.live_key(form.get("key", "").strip())
    if key is None:
        problem = problem_document(
            "unauthorized",
            detail="This is not a live API key (unknown, or revoked). Check it and try again.",
        )
        return _page(
            request, api.pages, keys_on=True, next_path=target,
            session_s=api.settings.session_seconds, problem=problem,
        )  # fmt: skip
    response = RedirectResponse(target, status_code=303)
    response.set_cookie(
        COOKIE_NAME,
        auth.signer.issue(key.key_id),
        max_age=int(auth.signer.lifetime_s),
        path="/",
        secure=request.url.scheme == "https",
        httponly=True,
        samesite="strict",
    )
    log.info("browser session opened for key %r", key.name)
    return response


@router.post("/logout")
async def log_out(request: Request, identity: IdentityDep) -> Response:
    check_form_origin(request)
    form = await read_form(request)
    check_csrf(request, form)
    response = RedirectResponse("/", status_code=303)
    response.delete_cookie(
        COOKIE_NAME,
        path="/",
        secure=request.url.scheme == "https",
        httponly=True,
        samesite="strict",
    )
    if identity.via == "session":
        log.info("browser session of key %r closed", identity.name)
    return response
