"""A truthful OpenAPI document: every status a route can answer, with its schema.

FastAPI documents a route's success response (its ``response_model``: the documents'
schemas come from the routes themselves) and, for routes with parameters, a 422 in its
own validation-error shape.  dexlab answers every error as an RFC 9457 problem
document, so this rewrites the generated document once (cached) after FastAPI builds
it: each operation lists the problem statuses it can give (:data:`ROUTE_PROBLEMS` for
the routes whose behaviour is known exactly; a conservative default for any other),
every one with the ``ProblemDocument`` schema under ``application/problem+json``;
the artifact download lists its media types and 304, the progress stream its events.
"""

from __future__ import annotations

import re
from typing import Any

from fastapi import FastAPI
from fastapi.openapi.utils import get_openapi
from pydantic import BaseModel
from pydantic.json_schema import models_json_schema

from service.auth.public_routes import is_public
from service.ogc.schemas import OGC_ROUTE_PROBLEMS, document_process_ids
from service.ogc.vocabulary import is_ogc_path
from service.openapi_streams import artifact_responses, event_stream_response
from service.problems import PROBLEM_TYPES
from service.schemas import RETENTION, REUSE, SHARE, stream_document_schemas
from worker.processes import ProcessRegistry

__all__ = ["PROBLEM_SCHEMA", "install_openapi"]

PROBLEM_JSON = "application/problem+json"

#: RFC 9457, with the members dexlab adds (``errors`` of a 422, ``jobID`` of a failed job).
PROBLEM_SCHEMA: dict[str, Any] = {
    "title": "ProblemDocument",
    "type": "object",
    "required": ["type", "title", "status", "detail"],
    "properties": {
        "type": {"type": "string", "description": "The problem type (dereferenceable)."},
        "title": {"type": "string"},
        "status": {"type": "integer", "minimum": 100, "maximum": 599},
        "detail": {"type": "string", "description": "What went wrong, for a person."},
        "instance": {"type": "string", "description": "The path the request went to."},
        "errors": {
            "type": "array",
            "description": "Each invalid field: its dotted path, a message and a type.",
            "items": {
                "type": "object",
                "required": ["field", "message"],
                "properties": {
                    "field": {"type": "string"},
                    "message": {"type": "string"},
                    "type": {"type": ["string", "null"]},
                },
            },
        },
        "jobID": {"type": ["string", "null"]},
    },
    "additionalProperties": True,
}

#: The problem statuses of the known routes: (method, path) -> statuses.  500 (an
#: unexpected error, always a problem document) is added to every operation.
ROUTE_PROBLEMS: dict[tuple[str, str], tuple[int, ...]] = {
    ("get", "/"): (422,),
    ("get", "/v1"): (422,),
    ("get", "/metrics"): (),
    ("get", "/problems/{slug}"): (404,),
    ("get", "/health/live"): (),
    ("get", "/health/ready"): (503,),
    ("get", "/v1/processes"): (422,),
    ("get", "/v1/processes/{process_id}"): (404, 422),
    ("post", "/v1/processes/{process_id}/execution"): (400, 404, 413, 422, 429, 503, 507),
    ("get", "/v1/jobs"): (403, 422, 503),
    # An expired job (its retention ended) is 410 for a while, then 404.
    ("get", "/v1/jobs/{job_id}"): (404, 410, 422, 503),
    ("get", "/v1/jobs/{job_id}/events"): (404, 410, 503),
    ("delete", "/v1/jobs/{job_id}"): (404, 410, 503),
    # A failed job's results answer its failure's problem (job-error, worker-lost,
    # time-limit-exceeded: 500; storage-full: 507; storage-error: 503).
    ("get", "/v1/jobs/{job_id}/results"): (404, 410, 422, 503, 507),
    # 422: an If-None-Match header longer than 1000 characters.
    ("get", "/v1/jobs/{job_id}/results/{name}"): (404, 410, 422, 503, 507),
    ("get", "/methods"): (),
    ("get", "/methods/{slug}"): (404,),
    ("delete", "/v1/reuse/{process_id}"): (403, 404, 422, 503),
}


class _RetentionMember(BaseModel):
    """The execute body's ``retention_s``, beside ``inputs``."""

    retention_s: float | None = RETENTION
    reuse: bool = REUSE
    share: bool = SHARE


#: A page, as the routes that negotiate (``?f=html``, ``Accept: text/html``) answer.
HTML_PAGE: dict[str, Any] = {"schema": {"type": "string"}}

_DESCRIPTIONS = {
    400: "Malformed request: the body is not UTF-8 JSON or nests too deeply.",
    401: "The service has API keys and the request brought no valid one "
    "(`WWW-Authenticate: Bearer`).",
    403: "Refused: a parameter only an admin key may use.",
    404: "No such process, job or artifact, or the result is not ready yet.",
    410: "The job was dismissed, or it expired (its retention ended): its results are gone.",
    429: "A quota of this API key: too many jobs queued or submissions this minute "
    "(`limit` names the setting; `Retry-After`).",
    413: "The request body is larger than the service accepts.",
    422: "Invalid inputs or parameters; `errors` names every bad field (a parameter as "
    "`query.<name>` or `path.<name>`).",
    500: "An unexpected error (logged), or the failure of the job whose results were asked.",
    503: "The job store is unavailable (see `Retry-After`), or the service is not ready.",
    507: "The job store's disk is full.",
}


def _default_statuses(method: str, operation: dict[str, Any]) -> tuple[int, ...]:
    """Statuses of a route not in the table, from what it takes."""
    statuses = {503}
    parameters = operation.get("parameters", [])
    if any(p.get("in") == "path" for p in parameters):
        statuses.add(404)
    if parameters or "requestBody" in operation:
        statuses.add(422)
    if method in ("post", "put", "patch"):
        statuses.update({400, 413})
    return tuple(sorted(statuses))


#: The 400 of an ``/ogc/`` operation: OGC's status for a bad parameter.
_OGC_400 = (
    "A query, path or header parameter has a value the API definition does not allow "
    "(`invalid-parameter-value`; `errors` names it as `query.<name>`), or the body is "
    "not UTF-8 JSON or nests too deeply."
)


def _problem_response(status: int, path: str = "") -> dict[str, Any]:
    titles = sorted({t for s, t, _ in PROBLEM_TYPES.values() if s == status})
    description = _DESCRIPTIONS.get(status, ", ".join(titles) or "A problem.")
    if status == 400 and is_ogc_path(path):
        description = _OGC_400
    return {
        "description": description,
        "content": {PROBLEM_JSON: {"schema": {"$ref": "#/components/schemas/ProblemDocument"}}},
    }


def _example_key(title: str, taken: set[str]) -> str:
    key = re.sub(r"[^A-Za-z0-9]+", "-", title).strip("-").lower()[:60] or "example"
    unique, n = key, 2
    while unique in taken:
        unique, n = f"{key}-{n}", n + 1
    taken.add(unique)
    return unique


def _process_bodies(
    document: dict[str, Any], registry: ProcessRegistry
) -> dict[tuple[str, str], tuple[int, ...]]:
    """Give each per-process execute operation its input model and worked examples;
    the problem statuses of those operations."""
    statuses: dict[tuple[str, str], tuple[int, ...]] = {}
    definitions = list(registry)
    refs, top = models_json_schema(
        [(d.inputs_model, "validation") for d in definitions],
        ref_template="#/components/schemas/{model}",
    )
    document["components"]["schemas"].update(top.get("$defs", {}))
    members = _RetentionMember.model_json_schema()["properties"]
    for definition in definitions:
        path = document["paths"].get(f"/v1/processes/{definition.id}/execution")
        if path is None or "post" not in path:
            continue
        taken: set[str] = set()
        family = registry.family(definition.id)
        paper = family.paper if family is not None else None
        examples = {
            _example_key(ex.title, taken): {
                "summary": f"{paper}: {ex.title}" if paper else ex.title,
                "description": ex.description,
                "value": {"inputs": dict(ex.inputs)},
            }
            for ex in definition.examples
        }
        schema = {
            "type": "object",
            "required": ["inputs"],
            "additionalProperties": False,
            "properties": {
                "inputs": refs[(definition.inputs_model, "validation")],
                "retention_s": members["retention_s"],
                "reuse": members["reuse"],
                "share": members["share"],
            },
        }
        content: dict[str, Any] = {"schema": schema}
        if examples:
            content["examples"] = examples
        path["post"]["requestBody"] = {
            "required": True,
            "content": {"application/json": content},
        }
        statuses[("post", f"/v1/processes/{definition.id}/execution")] = (
            400, 413, 422, 429, 503, 507,
        )  # fmt: skip
    return statuses


def _page_alternatives(document: dict[str, Any]) -> None:
    """Pages beside JSON: a GET route with the ``f`` parameter answers 200 with a page
    too, and any GET's problem is a page for a client that asks for HTML."""
    for item in document.get("paths", {}).values():
        operation = item.get("get")
        if not isinstance(operation, dict):
            continue
        for parameter in operation.get("parameters", []):
            if parameter.get("in") == "query" and parameter.get("name") == "f":
                parameter["schema"] = {"type": "string", "enum": ["json", "html"]}
                operation["responses"].setdefault("200", {"description": "OK"}).setdefault(
                    "content", {}
                )["text/html"] = HTML_PAGE
        for status, response in operation["responses"].items():
            content = response.get("content")
            if status[:1] in "45" and isinstance(content, dict) and PROBLEM_JSON in content:
                content["text/html"] = HTML_PAGE


#: The Bearer scheme of API keys (``dexlab keys create``).
SECURITY_SCHEMES: dict[str, Any] = {
    "apiKey": {
        "type": "http",
        "scheme": "bearer",
        "description": "An API key's secret.  Needed on every operation but the public "
        "ones once the service has any key; a service without keys is open "
        "(hence the empty alternative).",
    }
}


def _rewrite(
    document: dict[str, Any], known: dict[tuple[str, str], tuple[int, ...]]
) -> dict[str, Any]:
    document.setdefault("components", {})["securitySchemes"] = SECURITY_SCHEMES
    schemas = document.setdefault("components", {}).setdefault("schemas", {})
    schemas["ProblemDocument"] = PROBLEM_SCHEMA
    schemas.update(stream_document_schemas())
    schemas.pop("HTTPValidationError", None)
    schemas.pop("ValidationError", None)
    for path, item in document.get("paths", {}).items():
        for method, operation in item.items():
            if not isinstance(operation, dict) or "responses" not in operation:
                continue
            responses: dict[str, Any] = operation["responses"]
            statuses = known.get((method, path))
            if statuses is None:
                statuses = _default_statuses(method, operation)
            responses.pop("422", None)  # FastAPI's validation shape: replaced below
            if not is_public(method.upper(), path):
                statuses = (*statuses, 401)
                operation["security"] = [{"apiKey": []}, {}]
            for status in (*statuses, 500):
                responses[str(status)] = _problem_response(status, path)
            if (method, path) == ("get", "/v1/jobs/{job_id}/results/{name}"):
                artifact_responses(responses)
            if (method, path) == ("get", "/v1/jobs/{job_id}/events"):
                event_stream_response(responses)
    _page_alternatives(document)
    return document


def install_openapi(app: FastAPI, registry: ProcessRegistry) -> None:
    """Make ``app.openapi()`` (and ``/openapi.json``) return the rewritten document,
    with ``registry``'s processes' input schemas and worked examples."""

    def build() -> dict[str, Any]:
        if app.openapi_schema is None:
            document = get_openapi(
                title=app.title,
                version=app.version,
                openapi_version=app.openapi_version,
                description=app.description,
                routes=app.routes,
                tags=app.openapi_tags,
                servers=app.servers,
            )
            document.setdefault("components", {}).setdefault("schemas", {})
            known = {**ROUTE_PROBLEMS, **OGC_ROUTE_PROBLEMS, **_process_bodies(document, registry)}
            document_process_ids(document, registry.ids())
            app.openapi_schema = _rewrite(document, known)
        return app.openapi_schema

    app.openapi = build  # type: ignore[method-assign]
