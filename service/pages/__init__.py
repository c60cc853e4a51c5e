"""Pages for people: the landing page, processes, jobs and methods as HTML.

The room of every page.  :mod:`service.pages.routes` answers the JSON API's GET URLs
with a page when the client asks for HTML (:mod:`service.pages.negotiation`,
:mod:`service.pages.html_route`); :mod:`service.pages.methods` serves the method pages,
:mod:`service.pages.actions` the forms' posts, :mod:`service.pages.login` signing in
and out.  :class:`Pages` (templates, method pages, the family catalogue) is built by
``create_app`` and kept on ``app.state.pages``; :mod:`service.pages.views` gives each
template its context.  (The façade's pages are :mod:`service.ogc.page_routes`.)
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
