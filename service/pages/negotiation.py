"""Content negotiation: JSON for API clients, HTML for people (as pygeoapi does).

``?f=html`` or ``?f=json`` decides outright.  Otherwise the ``Accept`` header does: HTML
when it gives ``text/html`` a higher quality than ``application/json`` (RFC 9110
§12.5.1: each type takes the q of the most specific range that matches it).  A
browser's ``text/html,application/xhtml+xml,...,*/*;q=0.8`` asks for HTML; ``*/*``,
``application/json`` or no ``Accept`` at all get JSON, so API clients see no change.
"""

from __future__ import annotations

from typing import Annotated, Literal

from fastapi import Query, Request

__all__ = ["FORMAT_DESCRIPTION", "PAGE_ACTIONS", "FormatQuery", "prefers_html", "wants_html"]

FORMAT_DESCRIPTION = (
    "The representation: `json` (the default for API clients) or `html` (a page for a "
    "browser). Without it, an `Accept` header preferring `text/html` gets the page."
)

#: The ``f`` query parameter of every route that can answer with a page.
FormatQuery = Annotated[
    Literal["json", "html"] | None, Query(alias="f", description=FORMAT_DESCRIPTION)
]

_HTML = ("text", "html")
_JSON = ("application", "json")


def _ranges(accept: str) -> list[tuple[str, str, float]]:
    """``(type, subtype, q)`` of each media range of an Accept header; malformed
    ranges and q-values are skipped."""
    ranges = []
    for item in accept.split(","):
        media, *params = item.split(";")
        kind, _, subtype = media.strip().lower().partition("/")
        if not kind or not subtype:
            continue
        q = 1.0
        for param in params:
            name, _, value = param.strip().partition("=")
            if name.strip().lower() == "q":
                try:
                    q = float(value.strip())
                except ValueError:
                    q = -1.0
        if 0.0 <= q <= 1.0:
            ranges.append((kind, subtype, q))
    return ranges


def _quality(ranges: list[tuple[str, str, float]], media: tuple[str, str]) -> float:
    """The q the header gives ``media``: that of its most specific matching range."""
    best_specificity, best_q = -1, 0.0
    for kind, subtype, q in ranges:
        if (kind, subtype) == media:
            specificity = 2
        elif kind == media[0] and subtype == "*":
            specificity = 1
        elif (kind, subtype) == ("*", "*"):
            specificity = 0
        else:
            continue
        if specificity > best_specificity or (specificity == best_specificity and q > best_q):
            best_specificity, best_q = specificity, q
    return best_q


def prefers_html(accept: str | None) -> bool:
    """Whether an ``Accept`` header ranks ``text/html`` above ``application/json``."""
    if not accept:
        return False
    ranges = _ranges(accept)
    return _quality(ranges, _HTML) > _quality(ranges, _JSON)


#: Where the page actions live (forms post there); they always answer with pages.
PAGE_ACTIONS = "/pages/"
#: Page actions a page's script calls for JSON (the live explorer's preview): their
#: problems stay problem documents.
_JSON_ACTIONS = ("/preview",)


def wants_html(request: Request) -> bool:
    """Whether to answer this request (or its problem) with a page: a page action
    (but for the JSON ones a page's script calls);
    ``f=html``; or no ``f`` and an ``Accept`` preferring HTML.  Only GET and HEAD
    negotiate: the API's writes keep their JSON answers whatever the client accepts."""
    if request.url.path.startswith(PAGE_ACTIONS):
        return not request.url.path.endswith(_JSON_ACTIONS)
    if request.method not in ("GET", "HEAD"):
        return False
    f = request.query_params.get("f")
    if f is not None:
        return f == "html"
    return prefers_html(request.headers.get("accept"))
