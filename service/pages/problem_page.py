"""A problem document as a page, for a client that asked for HTML.

``service.errors`` (the one place exceptions become HTTP) builds every problem as
``application/problem+json``; :func:`as_page_if_asked` re-renders it as the problem
page when the request negotiated HTML (a browser on a missing job, a bad filter, a
form posted from elsewhere).  Status and headers (``Allow``, ``Retry-After``) stay.
"""

from __future__ import annotations

import json
import logging
from typing import Any

from fastapi import Request
from starlette.responses import Response

from service.pages.negotiation import wants_html
from service.pages.renderer import Pages

__all__ = ["as_page_if_asked"]

log = logging.getLogger("dexlab.service")

_OWN_HEADERS = frozenset({"content-type", "content-length"})


def as_page_if_asked(request: Request, response: Response) -> Response:
    """``response`` (a problem document) as the problem page when the client asked
    for HTML; otherwise unchanged."""
    pages: Pages | None = getattr(request.app.state, "pages", None)
    if pages is None or not wants_html(request):
        return response
    try:
        problem: dict[str, Any] = json.loads(bytes(response.body))
    except ValueError:  # pragma: no cover - problem responses are always JSON
        return response
    headers = {k: v for k, v in response.headers.items() if k.lower() not in _OWN_HEADERS}
    try:
        return pages.render(
            request,
            "problem.html",
            {"problem": problem},
            status_code=response.status_code,
            headers=headers,
        )
    except Exception:  # a page that cannot be drawn must not hide the problem
        log.exception("the problem page for %s could not be rendered", request.url.path)
        return response
