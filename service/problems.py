"""RFC 9457 problem documents: the types dexlab serves (slug -> HTTP status, title,
description) and the factories that make every problem document it answers.

A bad query, path or header parameter is one shape per surface
(:func:`parameter_problem`): under ``/v1`` a 422 ``invalid-request``, under ``/ogc`` a
400 of OGC's ``invalid-parameter-value`` type (OWS ``InvalidParameterValue``); either
way ``errors`` names the parameter as ``query.<name>`` (``path.<name>``,
``header.<name>``).  A handler that finds a bad
parameter itself raises :func:`parameter_error`, so it takes the same path.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse

from service.ogc.vocabulary import exception_type, is_ogc_path

__all__ = [
    "PROBLEM_JSON",
    "PROBLEM_TYPES",
    "parameter_error",
    "parameter_problem",
    "problem_document",
    "problem_response",
    "problem_type_uri",
]

PROBLEM_JSON = "application/problem+json"

PROBLEM_TYPES: dict[str, tuple[int, str, str]] = {
    "invalid-inputs": (
        422,
        "Invalid inputs",
        "The process inputs failed validation; `errors` names every bad field.",
    ),
    "invalid-request": (
        422,
        "Invalid request",
        "The request body, a query parameter or a header is malformed; `errors` names it.",
    ),
    "invalid-parameter-value": (
        400,
        "Invalid parameter value",
        "Under /ogc/: a query, path or header parameter has a value the API definition "
        "does not allow (OGC's InvalidParameterValue); `errors` names it.",
    ),
    "malformed-request": (
        400,
        "Malformed request",
        "The request body is not valid UTF-8 JSON, or nests too deeply; `detail` says where.",
    ),
    "request-too-large": (
        413,
        "Request too large",
        "The request body is larger than the service accepts (`max_body_bytes`).",
    ),
    "cost-limit-exceeded": (
        422,
        "Cost limit exceeded",
        "The requested work exceeds the process's documented cost limit "
        "(see `limits` at GET /v1/processes/{processID}); nothing was queued.",
    ),
    "idempotency-conflict": (
        422,
        "Idempotency-Key reused",
        "The Idempotency-Key was used before with a different request body.",
    ),
    "no-such-process": (404, "No such process", "No process has this ID."),
    "no-such-job": (404, "No such job", "No job has this ID."),
    "no-such-artifact": (404, "No such artifact", "The job has no artifact with this name."),
    "result-not-ready": (
        404,
        "Result not ready",
        "The job has not finished yet; poll GET /v1/jobs/{jobID}.",
    ),
    "job-dismissed": (410, "Job dismissed", "The job was dismissed; its results are gone."),
    "job-expired": (
        410,
        "Job expired",
        "The job finished longer ago than it was kept (its `expires`: DEXLAB_RESULT_TTL_S "
        "or the request's `retention_s`), and it and its results were deleted.  An "
        "expired job answers this for as long as it was kept (at most a day), then 404.",
    ),
    "quota-exceeded": (
        429,
        "Quota exceeded",
        "This API key has as many jobs queued as it may (`limit` names the setting, "
        "`allowed` its value); submit again after `Retry-After` seconds, once one has "
        "started.",
    ),
    "rate-limited": (
        429,
        "Too many submissions",
        "This API key submitted as many jobs this minute as it may (`limit`: "
        "DEXLAB_SUBMIT_RATE_PER_MIN, `allowed`: its value); `Retry-After` says when the "
        "next is allowed.",
    ),
    "queue-full": (
        503,
        "Queue full",
        "The whole queue holds as many jobs as the service takes (`limit`: "
        "DEXLAB_MAX_QUEUED); submit again after `Retry-After` seconds.",
    ),
    "job-failed": (500, "Job failed", "The job failed; `detail` says why."),
    "job-error": (500, "The job raised an error", "The job's code raised an exception."),
    "time-limit-exceeded": (
        500,
        "Time limit exceeded",
        "The job ran longer than its time limit and was stopped.",
    ),
    "worker-lost": (
        500,
        "Worker lost",
        "The worker running the job died on every allowed attempt.",
    ),
    "store-unavailable": (
        503,
        "Job store unavailable",
        "The job store does not answer or stays locked; retry after `Retry-After` seconds.",
    ),
    "storage-full": (
        507,
        "Storage full",
        "The job store's disk is full: nothing more can be stored until space is freed.",
    ),
    "storage-error": (
        503,
        "Storage error",
        "The job store cannot read or write its files (corrupt, read-only or an I/O error).",
    ),
    "not-ready": (503, "Not ready", "The store or the worker pool is not up."),
    "not-found": (404, "Not found", "No resource at this path."),
    "unauthorized": (
        401,
        "Unauthorized",
        "This service has API keys and the request brought none that is valid: send "
        "`Authorization: Bearer <secret>` (a browser logs in at /login).  A wrong or "
        "revoked key, or an ended session, is refused the same way; `WWW-Authenticate` "
        "names the scheme.",
    ),
    "forbidden": (
        403,
        "Forbidden",
        "The request is refused: a page's form posted from another site (the service's "
        "own pages send a same-origin Origin or Sec-Fetch-Site) or without its session's "
        "CSRF token, or a parameter only an admin key may use (`owner`).",
    ),
    "method-not-allowed": (405, "Method not allowed", "This path does not accept this method."),
    "internal-error": (500, "Internal error", "An unexpected error; it was logged."),
}


def problem_type_uri(slug: str) -> str:
    """The problem type URI (relative, dereferenceable on this service)."""
    return f"/problems/{slug}"


def problem_document(
    slug: str,
    *,
    detail: str,
    instance: str | None = None,
    status: int | None = None,
    title: str | None = None,
    type_uri: str | None = None,
    **extra: Any,
) -> dict[str, Any]:
    """The problem document of a known problem type (under ``/ogc/``, with the exception
    type OGC API - Processes defines for it, where it defines one).  ``slug`` may also
    be a type URI a job recorded; the status and title of a type dexlab does not serve
    are ``internal-error``'s unless given.  ``type_uri`` overrides the type (a document
    sent elsewhere, e.g. a callback, names it absolutely)."""
    default_status, default_title, _ = PROBLEM_TYPES.get(slug, PROBLEM_TYPES["internal-error"])
    kind = slug if slug.startswith(("/", "http:", "https:")) else problem_type_uri(slug)
    body: dict[str, Any] = {
        "type": type_uri or exception_type(slug, instance) or kind,
        "title": title or default_title,
        "status": status or default_status,
        "detail": detail,
    }
    if instance:
        body["instance"] = instance
    body.update(extra)
    return body


def problem_response(
    slug: str,
    *,
    detail: str,
    instance: str | None = None,
    status: int | None = None,
    title: str | None = None,
    headers: dict[str, str] | None = None,
    **extra: Any,
) -> JSONResponse:
    """A problem+json response: :func:`problem_document` with its status."""
    body = problem_document(
        slug, detail=detail, instance=instance, status=status, title=title, **extra
    )
    return JSONResponse(body, status_code=body["status"], media_type=PROBLEM_JSON, headers=headers)


def field_errors(errors: Sequence[Any]) -> list[dict[str, Any]]:
    """Validation errors as ``{"field", "message", "type"}``: a field named by where it
    is (``query.limit``, ``path.job_id``, ``status[0]``; a body's fields without
    ``body.``)."""
    named = []
    for err in errors:
        loc = [str(p) for p in err.get("loc", ())]
        if loc and loc[0] == "body":
            loc = loc[1:] or ["body"]
        field = ""
        for part in loc:
            field += f"[{part}]" if part.isdigit() else (f".{part}" if field else part)
        named.append({"field": field, "message": err.get("msg", ""), "type": err.get("type")})
    return named


def parameter_error(where: str, name: str, message: str) -> RequestValidationError:
    """The error of a parameter a handler found bad itself (``where``: ``query``,
    ``path`` or ``header``): answered as any other bad parameter."""
    return RequestValidationError([{"loc": (where, name), "msg": message, "type": "value_error"}])


def parameter_problem(path: str, errors: Sequence[Any]) -> JSONResponse:
    """The problem document of a request that failed validation at ``path``: a bad
    parameter under ``/ogc/`` is a 400 ``invalid-parameter-value``; everything else (and all
    of ``/v1``) a 422 ``invalid-request``; a body that is not JSON a 400."""
    named = field_errors(errors)
    if any(e.get("type") == "json_invalid" for e in named):
        return problem_response(
            "malformed-request", detail="The request body is not valid JSON.", instance=path
        )
    in_body = any(tuple(err.get("loc", ()))[:1] == ("body",) for err in errors)
    slug = "invalid-parameter-value" if is_ogc_path(path) and not in_body else "invalid-request"
    first = named[0] if named else {"field": "body", "message": "invalid"}
    detail = f"Invalid value for '{first['field']}': {first['message']}"
    if len(named) > 1:
        detail += f" (and {len(named) - 1} more problem(s))"
    return problem_response(slug, detail=detail, instance=path, errors=named)
