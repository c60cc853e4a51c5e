"""Liveness and readiness probes."""

from __future__ import annotations

from fastapi import APIRouter, Response

from service.deps import ApiDep
from service.problems import problem_response
from service.schemas import Liveness, LocalPool, Readiness
from worker.errors import StorageError, StorageFull, StoreUnavailable

__all__ = ["router"]

router = APIRouter(prefix="/health", tags=["health"])


@router.get("/live", summary="The process answers", response_model=Liveness)
async def live() -> Liveness:
    return Liveness(status="live")


@router.get(
    "/ready",
    summary="The store answers and can be written, and at least one worker is up",
    response_model=Readiness,
)
def ready(api: ApiDep) -> Readiness | Response:
    """200 when the store takes a write and a worker is up; else 503 ``not-ready``.  The
    store is tried once (no retry window), so a probe learns of an outage at once."""
    store, pool = api.store, api.pool
    try:
        store.check_storage()  # answers, takes a write lock, has room for results
    except StoreUnavailable as exc:
        state = (
            "full"
            if isinstance(exc, StorageFull)
            else ("error" if isinstance(exc, StorageError) else "unavailable")
        )
        return problem_response(
            "not-ready", detail=exc.detail, store=state, headers={"Retry-After": "5"}
        )
    workers = store.live_workers(within_s=3 * api.settings.heartbeat_seconds + 1.0)
    local_pool = None if pool is None else LocalPool(size=pool.size, alive=pool.alive())
    if not workers or (local_pool is not None and not local_pool.alive):
        return problem_response(
            "not-ready",
            detail="No worker process is up yet (the pool may still be starting).",
            store="ok",
            live_workers=len(workers),
            local_pool=None if local_pool is None else local_pool.model_dump(),
        )
    return Readiness(status="ready", store="ok", live_workers=len(workers), local_pool=local_pool)
