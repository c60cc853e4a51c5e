"""Liveness and readiness probes."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter

from service.deps import PoolDep, SettingsDep, StoreDep
from service.problems import problem_response
from worker.errors import StorageError, StorageFull, StoreUnavailable

__all__ = ["router"]

router = APIRouter(prefix="/health", tags=["health"])


@router.get("/live", summary="The process answers")
async def live() -> dict[str, Any]:
    return {"status": "live"}


@router.get(
    "/ready",
    summary="The store answers and can be written, and at least one worker is up",
)
def ready(store: StoreDep, settings: SettingsDep, pool: PoolDep) -> Any:
    """200 when the store takes a write and a worker is up; else 503 ``not-ready``.  The
    store is tried once (no retry window), so a probe learns of an outage at once."""
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
    workers = store.live_workers(within_s=3 * settings.heartbeat_seconds + 1.0)
    pool_alive = pool.alive() if pool is not None else None
    local_pool = None if pool is None else {"size": pool.size, "alive": pool_alive}
    if not workers or (pool is not None and not pool_alive):
        return problem_response(
            "not-ready",
            detail="No worker process is up yet (the pool may still be starting).",
            store="ok",
            live_workers=len(workers),
            local_pool=local_pool,
        )
    return {
        "status": "ready",
        "store": "ok",
        "live_workers": len(workers),
        "local_pool": local_pool,
    }
