"""``GET /queue``: the queue as a page (linked as "Queue" in the pages' navigation).

What waits and runs per process, the workers and recent throughput
(:mod:`service.pages.queue_view` says who sees what).  A page only, not in the OpenAPI
document: programs read ``/metrics`` and ``/v1/jobs?status=...``.
"""

from __future__ import annotations

from fastapi import APIRouter, Request
from fastapi.responses import HTMLResponse

from service.auth import IdentityDep
from service.deps import RegistryDep, SettingsDep, StoreDep
from service.pages import PagesDep
from service.pages.queue_view import queue_context

__all__ = ["router"]

router = APIRouter(include_in_schema=False)


@router.get("/queue", response_model=None)
def queue_page(
    request: Request,
    store: StoreDep,
    registry: RegistryDep,
    settings: SettingsDep,
    pages: PagesDep,
    identity: IdentityDep,
) -> HTMLResponse:
    context = queue_context(
        store, registry, owner=identity.owner_scope, admin=identity.admin,
        live_within_s=3 * settings.heartbeat_seconds + 1.0,
    )  # fmt: skip
    response = pages.render(request, "queue.html", context)
    response.headers["Cache-Control"] = "no-store"
    return response
