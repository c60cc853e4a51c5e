"""Pages for people: the landing page, processes, jobs and methods as HTML.

The JSON API's GET routes answer with a page when the client asks for HTML
(:mod:`service.pages.negotiation`); :class:`Pages` (templates, method pages, the family
catalogue) is built by ``create_app`` and kept on ``app.state.pages``;
:mod:`service.pages.views` gives each template its context.
"""

from __future__ import annotations

from service.pages.negotiation import FormatQuery, prefers_html, wants_html
from service.pages.renderer import STATIC_DIR, STATIC_PREFIX, Pages, PagesDep
from service.pages.settings import PageSettings

__all__ = [
    "STATIC_DIR",
    "STATIC_PREFIX",
    "FormatQuery",
    "PageSettings",
    "Pages",
    "PagesDep",
    "prefers_html",
    "wants_html",
]
