"""The façade's landing page and conformance declaration, as documents.

The JSON routes (:mod:`service.ogc.routes`) answer them; the page routes
(:mod:`service.ogc.page_routes`) draw them.
"""

from __future__ import annotations

from service.config import ServiceSettings
from service.ogc.execution import outbound_policy
from service.ogc.schemas import OgcConfClasses, OgcLandingPage, OgcLink
from service.ogc.urls import PublicUrls, self_and_alternate
from service.ogc.vocabulary import (
    JSON,
    REL_CONFORMANCE,
    REL_JOB_LIST,
    REL_PROCESSES,
    conformance_classes,
    openapi_media_type,
)

__all__ = ["conformance_document", "landing_document"]


def landing_document(urls: PublicUrls, openapi_version: str) -> OgcLandingPage:
    """``GET /ogc/``: the API definition and documentation, conformance, processes, jobs."""
    version = openapi_version
    return OgcLandingPage(
        title="dexlab: OGC API - Processes",
        description="Manipulator kinematic-design processes (dexterity maps, "
        "conditioning maps, optimum designs) as OGC API - Processes - Part 1: Core.",
        links=[
            *(OgcLink.model_validate(link)
              for link in self_and_alternate(f"{urls.ogc}/", "this document")),
            OgcLink(href=f"{urls.root}/openapi.json", rel="service-desc",
                    type=openapi_media_type(version),
                    title=f"the API definition (OpenAPI {version})"),
            OgcLink(href=f"{urls.root}/docs", rel="service-doc", type="text/html",
                    title="the API documentation"),
            OgcLink(href=f"{urls.ogc}/conformance", rel=REL_CONFORMANCE, type=JSON,
                    title="the conformance classes this server meets"),
            OgcLink(href=f"{urls.ogc}/processes", rel=REL_PROCESSES, type=JSON,
                    title="the processes"),
            OgcLink(href=f"{urls.ogc}/jobs", rel=REL_JOB_LIST, type=JSON, title="the jobs"),
        ],
    )  # fmt: skip


def conformance_document(settings: ServiceSettings, openapi_version: str) -> OgcConfClasses:
    """``GET /ogc/conformance``: the classes met (``callback`` while callbacks are on)."""
    callbacks = outbound_policy(settings).enabled
    return OgcConfClasses(conformsTo=conformance_classes(callbacks, openapi_version))
