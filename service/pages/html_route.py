"""The route class of a page that shares its URL with a JSON document.

A page handler is registered for the same path as its JSON route, on a router with
``route_class=HtmlRoute`` that the app includes before the JSON routers.  The route
matches only a request that wants HTML (:func:`~service.pages.negotiation.wants_html`:
``?f=html``, or an ``Accept`` preferring ``text/html``); any other request passes on to
the JSON route.  So the JSON handlers answer JSON only, each with its response model,
and the page handlers answer pages only.  Page routes stay out of the OpenAPI document
(``include_in_schema=False``): the JSON route's ``f`` parameter documents the page.
"""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter
from fastapi.routing import APIRoute
from starlette.requests import Request
from starlette.routing import Match
from starlette.types import Scope

from service.pages.negotiation import wants_html

__all__ = ["HtmlRoute", "page_router"]


class HtmlRoute(APIRoute):
    """An :class:`APIRoute` that matches only requests asking for HTML."""

    def matches(self, scope: Scope) -> tuple[Match, Scope]:
        if scope["type"] != "http" or not wants_html(Request(scope)):
            return Match.NONE, {}
        return super().matches(scope)


def page_router(**kwargs: Any) -> APIRouter:
    """A router of pages: every route an :class:`HtmlRoute`, none in the OpenAPI
    document."""
    return APIRouter(route_class=HtmlRoute, include_in_schema=False, **kwargs)
