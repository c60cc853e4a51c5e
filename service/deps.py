"""FastAPI dependencies: the resources the lifespan built, handed to route handlers.

A handler that needs several of them takes one :data:`ApiDep`: the frozen :class:`Api`
holding the store, the registry, the settings, the dispatcher, the pages, the local
worker pool and the caller's identity.  A handler that needs the registry or the
settings alone (the process list and descriptions, the conformance declaration) takes
:data:`RegistryDep` or :data:`SettingsDep`.

Each is a coroutine: FastAPI runs a plain ``def`` dependency in the threadpool, so a
route that needs no store would otherwise wait for a thread while every thread waits
on a store in trouble.  None of them touches the store: they hand over what the
lifespan put on ``app.state``."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated

from fastapi import Depends, Request

from service.auth.identity import Identity, get_identity
from service.config import ServiceSettings
from service.pages.renderer import Pages
from worker.dispatch import Dispatcher
from worker.pool import WorkerPool
from worker.processes import ProcessRegistry
from worker.store.base import JobStore

__all__ = ["Api", "ApiDep", "RegistryDep", "SettingsDep"]


@dataclass(frozen=True, slots=True)
class Api:
    """What a route handler works with: the app's resources and who is asking."""

    store: JobStore
    registry: ProcessRegistry
    settings: ServiceSettings
    dispatcher: Dispatcher
    pages: Pages
    identity: Identity
    pool: WorkerPool | None


async def get_api(request: Request) -> Api:
    state = request.app.state
    return Api(
        store=state.store,
        registry=state.registry,
        settings=state.settings,
        dispatcher=state.dispatcher,
        pages=state.pages,
        identity=get_identity(request),
        pool=state.pool,
    )


async def get_registry(request: Request) -> ProcessRegistry:
    registry: ProcessRegistry = request.app.state.registry
    return registry


async def get_settings(request: Request) -> ServiceSettings:
    settings: ServiceSettings = request.app.state.settings
    return settings


ApiDep = Annotated[Api, Depends(get_api)]
RegistryDep = Annotated[ProcessRegistry, Depends(get_registry)]
SettingsDep = Annotated[ServiceSettings, Depends(get_settings)]
