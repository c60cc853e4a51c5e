"""The façade's router: every ``/ogc`` route, and the callback sender's lifespan."""

from __future__ import annotations

from collections.abc import AsyncIterator
from contextlib import asynccontextmanager

from fastapi import APIRouter, FastAPI

from service.ogc.callbacks import CallbackSender
from service.ogc.execution import outbound_policy
from service.ogc.jobs.routes import router as job_router
from service.ogc.page_routes import router as page_router
from service.ogc.routes import router as process_router

__all__ = ["ogc_router"]


@asynccontextmanager
async def _callbacks(app: FastAPI) -> AsyncIterator[None]:
    """While callbacks are on, send them (runs inside the app's lifespan: the store is
    open)."""
    settings = app.state.settings
    policy = outbound_policy(settings)
    sender = None
    if policy.enabled:
        sender = CallbackSender(
            app.state.store, app.state.registry, policy, settings.callback_max_attempts
        )
        sender.start()
    try:
        yield
    finally:
        if sender is not None:
            await sender.stop()


def ogc_router() -> APIRouter:
    """Every ``/ogc`` route, and the callback sender's lifespan.  The pages come first:
    each matches only a request that asks for HTML (:mod:`service.pages.html_route`)."""
    router = APIRouter(lifespan=_callbacks)
    router.include_router(page_router)
    router.include_router(process_router)
    router.include_router(job_router)
    return router
