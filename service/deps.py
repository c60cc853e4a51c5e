"""FastAPI dependencies: the resources the lifespan built, handed to route handlers.

Each is a coroutine: FastAPI runs a plain ``def`` dependency in the threadpool, so a
route that needs no store would otherwise wait for a thread while every thread waits
on a store in trouble."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends, Request

from service.config import ServiceSettings
from worker.dispatch import Dispatcher
from worker.pool import WorkerPool
from worker.processes import ProcessRegistry
from worker.store.base import JobStore

__all__ = ["DispatcherDep", "PoolDep", "RegistryDep", "SettingsDep", "StoreDep"]


async def get_store(request: Request) -> JobStore:
    store: JobStore = request.app.state.store
    return store


async def get_registry(request: Request) -> ProcessRegistry:
    registry: ProcessRegistry = request.app.state.registry
    return registry


async def get_settings(request: Request) -> ServiceSettings:
    settings: ServiceSettings = request.app.state.settings
    return settings


async def get_pool(request: Request) -> WorkerPool | None:
    pool: WorkerPool | None = request.app.state.pool
    return pool


async def get_dispatcher(request: Request) -> Dispatcher:
    dispatcher: Dispatcher = request.app.state.dispatcher
    return dispatcher


StoreDep = Annotated[JobStore, Depends(get_store)]
RegistryDep = Annotated[ProcessRegistry, Depends(get_registry)]
SettingsDep = Annotated[ServiceSettings, Depends(get_settings)]
PoolDep = Annotated[WorkerPool | None, Depends(get_pool)]
DispatcherDep = Annotated[Dispatcher, Depends(get_dispatcher)]
