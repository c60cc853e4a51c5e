"""The pages' forms: reading a posted form, and refusing cross-site posts.

A page action changes state (it queues or dismisses a job), so a form posted from
another site must not work: the request must come from this service's own pages —
``Sec-Fetch-Site: same-origin`` where the browser sends it, else an ``Origin`` header
naming this host.  Anything else is 403.

With API keys, a browser is signed in by a session cookie, and every form also carries
that session's CSRF token (:mod:`service.auth.sessions`): :func:`form_protection`
writes it into each form (the templates render it), :func:`check_csrf` refuses a form
without it (403).  A request signed with a Bearer key, or an open service, has no
cookie a forged form could ride on, and needs none.
"""

from __future__ import annotations

from urllib.parse import parse_qsl, urlsplit

from fastapi import Request
from markupsafe import escape
from starlette.exceptions import HTTPException

from service.auth.identity import Identity
from service.auth.sessions import CSRF_FIELD, SessionSigner

__all__ = ["FORM_MEDIA_TYPE", "check_csrf", "check_form_origin", "form_protection", "read_form"]

FORM_MEDIA_TYPE = "application/x-www-form-urlencoded"

#: At most this many fields in a posted form.
_MAX_FIELDS = 20


def _session(request: Request) -> tuple[str, SessionSigner | None] | None:
    """``(session token, signer)`` when the request came with a browser session."""
    identity = getattr(request.state, "identity", None)
    if not isinstance(identity, Identity) or identity.session is None:
        return None
    auth = getattr(request.app.state, "auth", None)
    return identity.session, getattr(auth, "signer", None)


def form_protection(request: Request) -> str:
    """The hidden fields every form carries (HTML): the session's CSRF token, when
    the page was drawn for a browser session (none otherwise)."""
    session = _session(request)
    if session is None:
        return ""
    token, signer = session
    if signer is None:
        return ""
    return f'<input type="hidden" name="{CSRF_FIELD}" value="{escape(signer.csrf_token(token))}">'


def check_csrf(request: Request, form: dict[str, str]) -> None:
    """Raise 403 unless ``form`` carries the CSRF token of the request's session
    (nothing to check without a session)."""
    session = _session(request)
    if session is None:
        return
    token, signer = session
    given = form.get(CSRF_FIELD, "")
    if not given or signer is None:
        raise _forbidden(
            "This form has no CSRF token: post it from a page of this service (reload the "
            "page if it was drawn before you logged in)."
        )
    if not signer.csrf_matches(token, given):
        raise _forbidden(
            "This form's CSRF token is not your session's: reload the page and post it again."
        )


def _forbidden(detail: str) -> HTTPException:
    return HTTPException(status_code=403, detail=detail)


def check_form_origin(request: Request) -> None:
    """Raise 403 unless the request comes from a page of this service.

    ``Sec-Fetch-Site`` (which a page cannot forge) decides where a browser sends it;
    otherwise ``Origin`` must name the host the request was sent to."""
    site = request.headers.get("sec-fetch-site")
    if site is not None:
        if site == "same-origin":
            return
        raise _forbidden(
            f"A form must be posted from this service's own pages; this one is {site}."
        )
    origin = request.headers.get("origin")
    if origin is None:
        raise _forbidden(
            "A form must be posted from this service's own pages: the request has no "
            "Origin header (nor Sec-Fetch-Site: same-origin)."
        )
    host = request.headers.get("host", "")
    parts = urlsplit(origin)
    if origin == "null" or not parts.netloc or parts.netloc.lower() != host.lower():
        raise _forbidden(
            f"A form must be posted from this service's own pages; it came from {origin!r}."
        )


async def read_form(request: Request, *, max_fields: int = _MAX_FIELDS) -> dict[str, str]:
    """The fields of a URL-encoded form (a field given twice: its last value; an empty
    body: no fields).  400 for another body type, a body that is not UTF-8, or more than
    ``max_fields`` fields."""
    body = await request.body()
    if not body:  # a form without fields
        return {}
    media = request.headers.get("content-type", "").split(";")[0].strip().lower()
    if media != FORM_MEDIA_TYPE:
        raise HTTPException(400, detail=f"A page action takes a form ({FORM_MEDIA_TYPE}).")
    try:
        text = body.decode("utf-8")
        pairs = parse_qsl(
            text, keep_blank_values=True, strict_parsing=False, max_num_fields=max_fields
        )
    except UnicodeDecodeError as exc:
        raise HTTPException(400, detail=f"The form is not valid UTF-8: {exc.reason}.") from exc
    except ValueError as exc:
        raise HTTPException(400, detail=f"The form has more than {max_fields} fields.") from exc
    return dict(pairs)
