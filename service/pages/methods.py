"""``/methods``: each family's method page (``docs/methods/<slug>.md``) as HTML.

The pages are for people (equations as MathML, the papers' errata, citations); a
process description links its page with ``rel: describedby``.
"""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import HTMLResponse
from starlette.exceptions import HTTPException

from service.deps import ApiDep
from service.pages import views

__all__ = ["router"]

router = APIRouter(prefix="/methods", tags=["meta"])

_HTML_PAGE: dict[int | str, dict[str, Any]] = {
    200: {"description": "The page.", "content": {"text/html": {"schema": {"type": "string"}}}}
}


@router.get(
    "",
    summary="The method pages (HTML)",
    response_class=HTMLResponse,
    responses=_HTML_PAGE,
)
def list_methods(request: Request, api: ApiDep) -> HTMLResponse:
    return views.method_list_page(request, api.pages, api.registry)


@router.get(
    "/{slug}",
    summary="One method: conventions, equations, errata, citation (HTML)",
    response_class=HTMLResponse,
    responses=_HTML_PAGE,
)
def method_page(slug: str, request: Request, api: ApiDep) -> HTMLResponse:
    page = views.method_page(request, api.pages, api.registry, slug)
    if page is None:
        available = ", ".join(api.pages.methods.slugs()) or "none"
        raise HTTPException(404, detail=f"No method page {slug!r}; available: {available}.")
    return page
