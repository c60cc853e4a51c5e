"""``/`` and ``/v1``: where to go from here (the page for people: service.pages.routes)."""

from __future__ import annotations

from fastapi import APIRouter, Request, Response

from service.pages import FormatQuery
from service.schemas import Landing, Link

__all__ = ["landing_document", "router"]

router = APIRouter(tags=["meta"])

JSON = "application/json"


def landing_document(openapi_version: str) -> Landing:
    """The landing document: the processes, the jobs, the API's description and docs,
    the methods and the OGC API – Processes façade."""
    major_minor = ".".join(openapi_version.split(".")[:2])
    return Landing(
        title="dexlab",
        description="Manipulator kinematic-design service",
        links=[
            Link(href="/v1/processes", rel="processes", type=JSON),
            Link(href="/v1/jobs", rel="jobs", type=JSON),
            Link(href="/docs", rel="service-doc", type="text/html"),
            Link(href="/openapi.json", rel="service-desc",
                 type=f"application/vnd.oai.openapi+json;version={major_minor}"),
            Link(href="/methods", rel="describedby", type="text/html",
                 title="The methods: equations, conventions, the papers' errata"),
            Link(href="/ogc/", rel="alternate", type=JSON,
                 title="OGC API – Processes – Part 1: Core"),
        ],
    )  # fmt: skip


@router.get("/", summary="Landing page", response_model=Landing, response_model_exclude_unset=True)
def landing(request: Request, response: Response, f: FormatQuery = None) -> Landing:
    response.headers["Vary"] = "Accept"
    return landing_document(request.app.openapi_version)


@router.get(
    "/v1",
    summary="Landing page of the v1 API (the same as /)",
    response_model=Landing,
    response_model_exclude_unset=True,
)
def landing_v1(request: Request, response: Response, f: FormatQuery = None) -> Landing:
    response.headers["Vary"] = "Accept"
    return landing_document(request.app.openapi_version)
