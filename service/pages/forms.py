"""The pages' forms: reading a posted form, and refusing cross-site posts.

A page action changes state (it queues or dismisses a job), so a form posted from
another site must not work: the request must come from this service's own pages —
``Sec-Fetch-Site: same-origin`` where the browser sends it, else an ``Origin`` header
naming this host.  Anything else is 403.

Both halves live here so a later CSRF token (with login sessions) is added in one
place: :func:`form_protection` writes what every form carries (rendered into each
form by the templates), :func:`check_form_origin` checks it.
"""

from __future__ import annotations

from urllib.parse import parse_qsl, urlsplit

from fastapi import Request
from starlette.exceptions import HTTPException

__all__ = ["FORM_MEDIA_TYPE", "check_form_origin", "form_protection", "read_form"]

FORM_MEDIA_TYPE = "application/x-www-form-urlencoded"

#: At most this many fields in a posted form.
_MAX_FIELDS = 20


def form_protection(request: Request) -> str:
    """The hidden fields every form carries (HTML).  Today none: the origin check
    needs nothing from the form; a CSRF token will be written here."""
    return ""


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


async def read_form(request: Request) -> dict[str, str]:
    """The fields of a URL-encoded form (a field given twice: its last value; an empty
    body: no fields).  400 for another body type, a body that is not UTF-8, or too many
    fields."""
    body = await request.body()
    if not body:  # a form without fields
        return {}
    media = request.headers.get("content-type", "").split(";")[0].strip().lower()
    if media != FORM_MEDIA_TYPE:
        raise HTTPException(400, detail=f"A page action takes a form ({FORM_MEDIA_TYPE}).")
    try:
        text = body.decode("utf-8")
        pairs = parse_qsl(
            text, keep_blank_values=True, strict_parsing=False, max_num_fields=_MAX_FIELDS
        )
    except UnicodeDecodeError as exc:
        raise HTTPException(400, detail=f"The form is not valid UTF-8: {exc.reason}.") from exc
    except ValueError as exc:
        raise HTTPException(400, detail=f"The form has more than {_MAX_FIELDS} fields.") from exc
    return dict(pairs)
