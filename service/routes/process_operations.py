"""One execute operation per registered process, so the API docs describe each one.

``POST /v1/processes/{processID}/execution`` (the generic route) takes any process
and stays for processes added at run time.  For every process the registry holds when
the app is built, this adds the same operation at its own path, tagged with its
family; :mod:`service.openapi` gives it the process's input schema and worked
examples.  Both routes run the same handler, so they answer identically.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from typing import Any

from fastapi import APIRouter, Request, Response
from fastapi.responses import JSONResponse

from service.deps import ApiDep
from service.parameters import CacheControlHeader, IdempotencyKey, PreferHeader
from service.routes.processes import EXECUTE_RESPONSES, ExecuteRequest, execute
from service.schemas import StatusDocument
from worker.processes import ProcessDefinition, ProcessRegistry

__all__ = [
    "execution_router",
    "family_of",
    "family_tag",
    "family_tag_documents",
    "family_tags",
]


def family_of(registry: ProcessRegistry, definition: ProcessDefinition) -> str:
    """The name of the family a process belongs to (its package under
    ``worker/families``, as the registry says), or "other"."""
    family = registry.family(definition.id)
    return family.name if family is not None else "other"


def family_tags(registry: ProcessRegistry) -> dict[str, tuple[str, str]]:
    """The families by name: (tag, description), in the registry's order."""
    return {f.name: (f.tag, f.description) for f in registry.families()}


def family_tag_documents(registry: ProcessRegistry) -> list[dict[str, Any]]:
    """The OpenAPI tags of the families, each linking its method page (Markdown)."""
    tags = []
    for family in registry.families():
        docs = {d.method_doc for d in registry if registry.family(d.id) == family and d.method_doc}
        links = " ".join(f"[The method: equations, errata](/methods/{doc})." for doc in docs)
        tags.append({"name": family.tag, "description": f"{family.description} {links}".strip()})
    return tags


def family_tag(registry: ProcessRegistry, definition: ProcessDefinition) -> str:
    """The OpenAPI tag a process's execute operation is listed under."""
    family = registry.family(definition.id)
    return family.tag if family is not None else "processes"


def operation_id(process_id: str) -> str:
    return "execute_" + process_id.replace("-", "_")


def _bound(process_id: str) -> Callable[..., Awaitable[StatusDocument | JSONResponse]]:
    async def run_process(
        body: ExecuteRequest,
        request: Request,
        response: Response,
        api: ApiDep,
        idempotency_key: IdempotencyKey = None,
        prefer: PreferHeader = None,
        cache_control: CacheControlHeader = None,
    ) -> StatusDocument | JSONResponse:
        return await execute(
            process_id, body, request, response, api, idempotency_key, prefer, cache_control
        )

    return run_process


def execution_router(registry: ProcessRegistry) -> APIRouter:
    """The per-process execute routes (include it before the generic one)."""
    router = APIRouter(prefix="/v1/processes")
    for definition in registry:
        router.add_api_route(
            f"/{definition.id}/execution",
            _bound(definition.id),
            methods=["POST"],
            status_code=201,
            response_model=StatusDocument,
            response_model_exclude_unset=True,
            responses=EXECUTE_RESPONSES,
            tags=[family_tag(registry, definition)],
            summary=f"Run {definition.id}: {definition.title}",
            description=(
                f"{definition.description}\n\nQueues a job (201 with `Location`); with "
                "`Prefer: wait=N` and a request within the process's `sync_cost_limit`, "
                "answers 200 with the result document if it finishes within N seconds."
            ),
            operation_id=operation_id(definition.id),
            response_description="The job's status document (201) or its results (200).",
        )
    return router
