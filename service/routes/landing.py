"""``/`` and ``/v1``: where to go from here (JSON for clients, a page for people)."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request, Response
from fastapi.responses import HTMLResponse

from service.deps import RegistryDep
from service.pages import FormatQuery, wants_html
from service.pages.views import landing_page

__all__ = ["landing_document", "router"]

router = APIRouter(tags=["meta"])

JSON = "application/json"


def landing_document(openapi_version: str) -> dict[str, Any]:
    """The landing document: the processes, the jobs, the API's description and docs,
    the methods and the OGC API – Processes façade."""
    major_minor = ".".join(openapi_version.split(".")[:2])
    return {
        "title": "dexlab",
        "description": "Manipulator kinematic-design service",
        "links": [
            {"href": "/v1/processes", "rel": "processes", "type": JSON},
            {"href": "/v1/jobs", "rel": "jobs", "type": JSON},
            {"href": "/docs", "rel": "service-doc", "type": "text/html"},
            {"href": "/openapi.json", "rel": "service-desc",
             "type": f"application/vnd.oai.openapi+json;version={major_minor}"},
            {"href": "/methods", "rel": "describedby", "type": "text/html",
             "title": "The methods: equations, conventions, the papers' errata"},
            {"href": "/ogc/", "rel": "alternate", "type": JSON,
             "title": "OGC API – Processes – Part 1: Core"},
        ],
    }  # fmt: skip


def _landing(
    request: Request, response: Response, registry: RegistryDep
) -> dict[str, Any] | HTMLResponse:
    response.headers["Vary"] = "Accept"
    if wants_html(request):
        return landing_page(request, request.app.state.pages, registry)
    return landing_document(request.app.openapi_version)


@router.get("/", summary="Landing page", response_model=None)
def landing(
    request: Request, response: Response, registry: RegistryDep, f: FormatQuery = None
) -> dict[str, Any] | HTMLResponse:
    return _landing(request, response, registry)


@router.get("/v1", summary="Landing page of the v1 API (the same as /)", response_model=None)
def landing_v1(
    request: Request, response: Response, registry: RegistryDep, f: FormatQuery = None
) -> dict[str, Any] | HTMLResponse:
    return _landing(request, response, registry)
