"""``GET /queue``: the queue as a page (linked as "Queue" in the pages' navigation).

What waits and runs per process, the workers and recent throughput
(:mod:`service.pages.queue_view` says who sees what).  A page only, not in the OpenAPI
document: programs read ``/metrics`` and ``/v1/jobs?status=...``.
"""

from __future__ import annotations

from fastapi import APIRouter, Request
from fastapi.responses import Response

from service.deps import ApiDep
from service.pages.queue_view import queue_context

__all__ = ["router"]

router = APIRouter(include_in_schema=False)


@router.get("/queue")
def queue_page(request: Request, api: ApiDep) -> Response:
    context = queue_context(
        api.store, api.registry, owner=api.identity.owner_scope, admin=api.identity.admin,
        live_within_s=3 * api.settings.heartbeat_seconds + 1.0,
    )  # fmt: skip
    response = api.pages.render(request, "queue.html", context)
    response.headers["Cache-Control"] = "no-store"
    return response
