"""Fixtures that run the real service: the ASGI app with its pool, or `dexlab serve`."""

from __future__ import annotations

from collections.abc import AsyncIterator, Iterator
from pathlib import Path

import httpx
import pytest

from service.app import create_app
from service.config import ServiceSettings
from tests.integration.servers import Server, start_server, stop_server


@pytest.fixture
def anyio_backend() -> str:
    return "asyncio"


@pytest.fixture
async def asgi_client(tmp_path: Path) -> AsyncIterator[httpx.AsyncClient]:
    """The real app (lifespan, SQLite store, a one-process pool) over httpx's ASGI transport."""
    settings = ServiceSettings(data_dir=tmp_path, workers=1, heartbeat_seconds=0.5)
    app = create_app(settings)
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://dexlab.test") as c:
            yield c


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    """`dexlab serve` with a two-process pool, shared by a test module."""
    srv = start_server(tmp_path_factory.mktemp("dexlab"), workers=2)
    yield srv
    stop_server(srv)
