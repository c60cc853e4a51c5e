"""One execute operation per registered process, so the API docs describe each one.

``POST /v1/processes/{processID}/execution`` (the generic route) takes any process
and stays for processes added at run time.  For every process the registry holds when
the app is built, this adds the same operation at its own path, tagged with its
family; :mod:`service.openapi` gives it the process's input schema and worked
examples.  Both routes run the same handler, so they answer identically.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from typing import Annotated, Any

from fastapi import APIRouter, Header, Request, Response

from service.deps import DispatcherDep, RegistryDep, SettingsDep, StoreDep
from service.routes.processes import ExecuteRequest, execute
from worker.processes import ProcessDefinition, ProcessRegistry

__all__ = [
    "FAMILY_PAPERS",
    "FAMILY_TAGS",
    "execution_router",
    "family_of",
    "family_tag",
    "family_tag_documents",
]

#: The paper each family reproduces, as example summaries name it.
FAMILY_PAPERS: dict[str, str] = {
    "planar_serial": "Patel & Sobh 2012",
    "planar_parallel": "Huang et al. 2004",
    "spherical_parallel": "Bai 2010",
    "chains": "the parallelism paper",
}

#: The job families, by their package under ``worker/families``: (tag, description).
FAMILY_TAGS: dict[str, tuple[str, str]] = {
    "planar_serial": (
        "Three-link planar serial arms",
        "Patel & Sobh: synthesis from task points or a trajectory, dexterity maps, joint limits.",
    ),
    "planar_parallel": (
        "2-DOF planar parallel robots",
        "Huang et al. 2004: conditioning and pressure-angle maps, the workspace bounded "
        "by a conditioning limit, the largest rectangle, η, the optimum.",
    ),
    "spherical_parallel": (
        "Spherical parallel manipulators",
        "Bai 2010: kinematics, conditioning over an orientation workspace, the design "
        "space and the optimum design.",
    ),
    "chains": (
        "Kinematic chains",
        "Parallelism measures P and Q; Grashof classification of four-bars.",
    ),
}


def family_of(definition: ProcessDefinition) -> str:
    """The family package a process belongs to (``worker.families.<family>``), read off
    its ``run`` function's module (the service imports no family)."""
    parts = definition.run.__module__.split(".")
    return parts[2] if len(parts) > 2 and parts[:2] == ["worker", "families"] else "other"


def family_tag_documents(registry: ProcessRegistry) -> list[dict[str, Any]]:
    """The OpenAPI tags of the families, each linking its method page (Markdown)."""
    tags = []
    for family, (tag, text) in FAMILY_TAGS.items():
        docs = {d.method_doc for d in registry if family_of(d) == family and d.method_doc}
        links = " ".join(f"[The method: equations, errata](/methods/{doc})." for doc in docs)
        tags.append({"name": tag, "description": f"{text} {links}".strip()})
    return tags


def family_tag(definition: ProcessDefinition) -> str:
    family = family_of(definition)
    return FAMILY_TAGS[family][0] if family in FAMILY_TAGS else "processes"


def operation_id(process_id: str) -> str:
    return "execute_" + process_id.replace("-", "_")


def _bound(process_id: str) -> Callable[..., Awaitable[Any]]:
    async def run_process(
        body: ExecuteRequest,
        request: Request,
        response: Response,
        store: StoreDep,
        registry: RegistryDep,
        settings: SettingsDep,
        dispatcher: DispatcherDep,
        idempotency_key: Annotated[
            str | None, Header(alias="Idempotency-Key", min_length=1, max_length=255)
        ] = None,
        prefer: Annotated[str | None, Header(max_length=255)] = None,
    ) -> Any:
        return await execute(
            process_id, body, request, response, store, registry, settings, dispatcher,
            idempotency_key, prefer,
        )  # fmt: skip

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
            tags=[family_tag(definition)],
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
