"""``DELETE /v1/reuse/{process_id}``: an admin stops stored results from being reused.

The jobs stay, with their results and files; only new submissions compute afresh (and
become reusable in turn).  ``?key=`` narrows the invalidation to one result key (the
``provenance.result_key`` of a result).
"""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Query
from fastapi.concurrency import run_in_threadpool
from pydantic import BaseModel, ConfigDict, Field

from service.auth.errors import Forbidden
from service.deps import ApiDep

__all__ = ["ReuseInvalidation", "router"]

router = APIRouter(prefix="/v1/reuse", tags=["reuse"])


class ReuseInvalidation(BaseModel):
    """What an invalidation did."""

    model_config = ConfigDict(extra="forbid")

    processID: str
    result_key: str | None = Field(description="The one result key invalidated; null: all.")
    invalidated: int = Field(ge=0, description="Stored results that were reusable and are no more.")


@router.delete(
    "/{process_id}",
    summary="Stop the stored results of a process (or of one result key) being reused",
    response_model=ReuseInvalidation,
)
async def invalidate(
    process_id: str,
    api: ApiDep,
    key: Annotated[
        str | None,
        Query(min_length=1, max_length=128, description="Only this result key's results."),
    ] = None,
) -> ReuseInvalidation:
    """Admins only (on a service without keys, its operator).  Deletes no job."""
    if not api.identity.admin:
        raise Forbidden("Only an admin key may invalidate stored results.")
    api.registry.require(process_id)
    count = await run_in_threadpool(api.store.invalidate_reuse, process_id, key)
    return ReuseInvalidation(processID=process_id, result_key=key, invalidated=count)
