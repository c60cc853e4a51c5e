"""The real app in process, for async tests: its lifespan entered, no worker pool,
reached through httpx's ASGI transport."""

from __future__ import annotations

from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from pathlib import Path

import httpx

from service.app import create_app
from service.config import Settings
from worker.processes import ProcessRegistry


@asynccontextmanager
async def asgi_client(
    data_dir: Path, registry: ProcessRegistry | None = None
) -> AsyncIterator[httpx.AsyncClient]:
    """An httpx client of the app serving ``registry`` (by default every process)."""
    app = create_app(Settings(data_dir=data_dir, workers=0), registry=registry)
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://dexlab.test") as c:
            yield c
