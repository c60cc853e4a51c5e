"""The API docs pages, served from the installed package: no request leaves the host.

FastAPI's own ``/docs`` and ``/redoc`` load Swagger UI and ReDoc from a CDN and ReDoc's
fonts from Google Fonts, so they are blank without internet.  These are the same pages
(FastAPI's :func:`get_swagger_ui_html` and :func:`get_redoc_html`) pointing at the
copies vendored under ``service/static/vendor`` (``scripts/vendor-api-docs`` writes
them; its README names the versions), which are mounted at ``/static/vendor``:

- ``/docs``: Swagger UI, deep links on, tags in the order the document defines them
  (each process family's execute operations under its own tag), "Try it out" starting
  from the operation's first worked example, no call to the online validator;
- ``/docs/oauth2-redirect``: Swagger UI's OAuth2 redirect page;
- ``/redoc``: ReDoc with its Roboto and Montserrat faces from ``fonts/fonts.css``;
- ``/favicon.ico``: Swagger UI's icon.

URLs are prefixed with the ASGI ``root_path``, so the pages work behind a proxy that
mounts the service under a path.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from fastapi import FastAPI, Request
from fastapi.openapi.docs import (
    get_redoc_html,
    get_swagger_ui_html,
    get_swagger_ui_oauth2_redirect_html,
)
from fastapi.staticfiles import StaticFiles
from starlette.responses import FileResponse, HTMLResponse, Response
from starlette.types import Scope

__all__ = [
    "DOCS_ASSETS",
    "REDOC_ASSETS",
    "SWAGGER_UI_PARAMETERS",
    "VENDOR_DIR",
    "VENDOR_URL",
    "VendorFiles",
    "install_api_docs",
]

VENDOR_DIR = Path(__file__).parent / "static" / "vendor"
VENDOR_URL = "/static/vendor"

SWAGGER_JS = "swagger-ui/swagger-ui-bundle.js"
SWAGGER_CSS = "swagger-ui/swagger-ui.css"
FAVICON = "swagger-ui/favicon-32x32.png"
REDOC_JS = "redoc/redoc.standalone.js"
FONTS_CSS = "fonts/fonts.css"

#: The vendored files each page loads (paths under :data:`VENDOR_DIR`); the fonts are
#: loaded by ``fonts.css``.
DOCS_ASSETS = (SWAGGER_JS, SWAGGER_CSS, FAVICON)
REDOC_ASSETS = (REDOC_JS, FONTS_CSS, FAVICON)

#: Swagger UI's options on top of FastAPI's defaults (which keep deep linking on).
#: No ``tagsSorter`` or ``operationsSorter``: tags and operations keep the document's
#: order.  ``validatorUrl: null`` keeps the page from calling the online validator.
SWAGGER_UI_PARAMETERS: dict[str, Any] = {
    "deepLinking": True,
    "validatorUrl": None,
    "displayRequestDuration": True,
    "filter": True,
    "defaultModelsExpandDepth": 0,
}

#: Media types by suffix, so they do not depend on the host's ``/etc/mime.types``
#: (Python alone knows no ``.woff2``, and every response is ``nosniff``).
_MEDIA_TYPES = {
    ".js": "text/javascript; charset=utf-8",
    ".css": "text/css; charset=utf-8",
    ".woff2": "font/woff2",
    ".png": "image/png",
    ".md": "text/markdown; charset=utf-8",
    ".txt": "text/plain; charset=utf-8",
}


class VendorFiles(StaticFiles):
    """Static files with fixed media types, revalidated by ETag (``no-cache``): the
    URLs carry no version, so a browser must not keep an old copy after an update."""

    def file_response(
        self,
        full_path: str | os.PathLike[str],
        stat_result: os.stat_result,
        scope: Scope,
        status_code: int = 200,
    ) -> Response:
        response = super().file_response(full_path, stat_result, scope, status_code)
        media_type = _MEDIA_TYPES.get(Path(full_path).suffix, "text/plain; charset=utf-8")
        if response.status_code != 304:
            response.headers["content-type"] = media_type
        response.headers["cache-control"] = "no-cache"
        return response


def _root(request: Request) -> str:
    return str(request.scope.get("root_path", "")).rstrip("/")


def _asset(request: Request, name: str) -> str:
    return f"{_root(request)}{VENDOR_URL}/{name}"


def install_api_docs(app: FastAPI) -> None:
    """Add ``/docs``, ``/docs/oauth2-redirect``, ``/redoc``, ``/favicon.ico`` and the
    ``/static/vendor`` mount to ``app`` (built with ``docs_url=None, redoc_url=None``)."""
    app.mount(VENDOR_URL, VendorFiles(directory=VENDOR_DIR), name="vendor")
    openapi_url = app.openapi_url or "/openapi.json"
    oauth2_redirect_url = app.swagger_ui_oauth2_redirect_url or "/docs/oauth2-redirect"

    # Coroutines: pages built from strings, never waiting for a threadpool thread.
    @app.get("/docs", include_in_schema=False)
    async def swagger_ui(request: Request) -> HTMLResponse:
        return get_swagger_ui_html(
            openapi_url=_root(request) + openapi_url,
            title=f"{app.title} - Swagger UI",
            swagger_js_url=_asset(request, SWAGGER_JS),
            swagger_css_url=_asset(request, SWAGGER_CSS),
            swagger_favicon_url=_asset(request, FAVICON),
            oauth2_redirect_url=_root(request) + oauth2_redirect_url,
            swagger_ui_parameters=SWAGGER_UI_PARAMETERS,
        )

    @app.get(oauth2_redirect_url, include_in_schema=False)
    async def swagger_ui_oauth2_redirect() -> HTMLResponse:
        return get_swagger_ui_oauth2_redirect_html()

    @app.get("/redoc", include_in_schema=False)
    async def redoc(request: Request) -> HTMLResponse:
        page = get_redoc_html(
            openapi_url=_root(request) + openapi_url,
            title=f"{app.title} - ReDoc",
            redoc_js_url=_asset(request, REDOC_JS),
            redoc_favicon_url=_asset(request, FAVICON),
            with_google_fonts=False,
        )
        fonts = f'<link rel="stylesheet" href="{_asset(request, FONTS_CSS)}">\n</head>'
        html = bytes(page.body).decode("utf-8").replace("</head>", fonts, 1)
        return HTMLResponse(html)

    @app.get("/favicon.ico", include_in_schema=False)
    def favicon() -> FileResponse:
        return FileResponse(
            VENDOR_DIR / FAVICON, media_type="image/png", headers={"Cache-Control": "no-cache"}
        )
