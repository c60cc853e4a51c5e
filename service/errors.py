"""The one place exceptions become HTTP responses: RFC 9457 problem documents."""

from __future__ import annotations

import logging
import math
from collections.abc import Awaitable, Callable
from typing import Any

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from starlette.exceptions import HTTPException as StarletteHTTPException
from starlette.responses import Response

from service.allow import allow_header, allowed_methods
from service.auth.errors import Forbidden, Unauthenticated
from service.ogc.execute_request import InvalidRequest
from service.pages.problem_page import as_page_if_asked
from service.problems import PROBLEM_TYPES, parameter_problem, problem_response
from worker.errors import (
    CostLimitExceeded,
    DexlabError,
    IdempotencyConflict,
    InvalidInputs,
    JobDismissed,
    JobExpired,
    JobFailed,
    NoSuchArtifact,
    NoSuchJob,
    NoSuchProcess,
    QueueFull,
    QuotaExceeded,
    RateLimited,
    ResultNotReady,
    StorageError,
    StorageFull,
    StoreUnavailable,
)

__all__ = ["dexlab_problem", "install_error_handlers"]

log = logging.getLogger("dexlab.service")

_SLUGS: dict[type[DexlabError], str] = {
    Unauthenticated: "unauthorized",
    Forbidden: "forbidden",
    InvalidRequest: "invalid-request",
    InvalidInputs: "invalid-inputs",
    CostLimitExceeded: "cost-limit-exceeded",
    IdempotencyConflict: "idempotency-conflict",
    NoSuchProcess: "no-such-process",
    NoSuchJob: "no-such-job",
    NoSuchArtifact: "no-such-artifact",
    ResultNotReady: "result-not-ready",
    JobDismissed: "job-dismissed",
    JobExpired: "job-expired",
    QuotaExceeded: "quota-exceeded",
    RateLimited: "rate-limited",
    QueueFull: "queue-full",
    JobFailed: "job-failed",
    StorageFull: "storage-full",
    StorageError: "storage-error",
    StoreUnavailable: "store-unavailable",
}


def _slug(exc: DexlabError) -> str:
    """The problem type of an exception: its class's, or its nearest base class's."""
    for cls in type(exc).__mro__:
        if cls in _SLUGS:
            return _SLUGS[cls]
    return "internal-error"


#: ``Retry-After`` of a full disk (seconds): space comes back when an operator frees it
#: or the retention sweep deletes expired jobs, not within a store's retry window.
STORAGE_FULL_RETRY_AFTER_S = 60


def _retry_headers(exc: DexlabError, extra: dict[str, Any]) -> dict[str, str] | None:
    """``Retry-After`` (whole seconds) for a store that is down or full for now and for
    a quota or a full queue (when a slot or a token is due); ``WWW-Authenticate`` for a
    request without a valid key."""
    hint = extra.pop("retry_after_s", None)
    if isinstance(exc, Unauthenticated):
        return {"WWW-Authenticate": exc.challenge}
    if not isinstance(exc, StoreUnavailable | QuotaExceeded | QueueFull):
        return None
    default = STORAGE_FULL_RETRY_AFTER_S if isinstance(exc, StorageFull) else 5
    seconds = hint if isinstance(hint, int | float) and hint > 0 else default
    return {"Retry-After": str(max(1, math.ceil(seconds)))}


_HTTP_SLUGS = {
    400: "malformed-request",
    401: "unauthorized",
    403: "forbidden",
    404: "not-found",
    405: "method-not-allowed",
    413: "request-too-large",
}


def _page_if_asked(handler: Callable[[Request, Any], Awaitable[Response]]) -> Any:
    """The handler, answering with the problem page when the client asked for HTML."""

    async def negotiated(request: Request, exc: Any) -> Response:
        return as_page_if_asked(request, await handler(request, exc))

    return negotiated


def dexlab_problem(request: Request, exc: DexlabError) -> JSONResponse:
    """The problem document of one of dexlab's exceptions (also used by the auth gate,
    a middleware that answers before any handler runs)."""
    slug = _slug(exc)
    extra: dict[str, Any] = dict(exc.extra)
    headers = _retry_headers(exc, extra)
    if isinstance(exc, InvalidInputs):
        extra["errors"] = exc.errors
    if isinstance(exc, JobFailed) and "error" in exc.extra:
        error = dict(exc.extra["error"])
        slug = str(error.get("type", "job-failed"))
        extra = {"jobID": exc.extra.get("jobID")}
        return problem_response(
            slug if slug in PROBLEM_TYPES else "job-failed",
            detail=str(error.get("detail", exc.detail)),
            title=error.get("title"),
            instance=str(request.url.path),
            **extra,
        )
    if isinstance(exc, StoreUnavailable):  # the cause names the store: logged, not shown
        log.warning("store trouble on %s: %s (%s)", request.url.path, exc.detail, exc.__cause__)
    return problem_response(
        slug, detail=exc.detail, instance=str(request.url.path), headers=headers, **extra
    )


def install_error_handlers(app: FastAPI) -> None:
    """Map every exception to a problem document (a page for a client asking for HTML)."""

    @app.exception_handler(DexlabError)
    @_page_if_asked
    async def _dexlab(request: Request, exc: DexlabError) -> JSONResponse:
        return dexlab_problem(request, exc)

    @app.exception_handler(RequestValidationError)
    @_page_if_asked
    async def _validation(request: Request, exc: RequestValidationError) -> JSONResponse:
        return parameter_problem(str(request.url.path), exc.errors())

    @app.exception_handler(StarletteHTTPException)
    @_page_if_asked
    async def _http(request: Request, exc: StarletteHTTPException) -> JSONResponse:
        slug = _HTTP_SLUGS.get(exc.status_code, "internal-error")
        headers = dict(exc.headers) if exc.headers else {}
        if exc.status_code == 405:
            headers["Allow"] = allow_header(allowed_methods(request.app.routes, request.scope))
        return problem_response(
            slug,
            detail=str(exc.detail),
            status=exc.status_code,
            instance=str(request.url.path),
            headers=headers or None,
        )

    @app.exception_handler(Exception)
    @_page_if_asked
    async def _unexpected(request: Request, exc: Exception) -> JSONResponse:
        log.exception("unhandled error on %s", request.url.path)
        return problem_response(
            "internal-error",
            detail=f"An unexpected error occurred ({type(exc).__name__}); it was logged.",
            instance=str(request.url.path),
        )
