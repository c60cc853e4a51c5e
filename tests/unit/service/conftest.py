"""What the service's unit tests share: anyio on asyncio, and the app in process."""

from __future__ import annotations

from collections.abc import AsyncIterator
from pathlib import Path

import httpx
import pytest

from tests.unit.service.asgi_app import asgi_client


@pytest.fixture
def anyio_backend() -> str:
    return "asyncio"


@pytest.fixture
async def client(tmp_path: Path) -> AsyncIterator[httpx.AsyncClient]:
    """The app on a fresh store in ``tmp_path``, over ASGI (no server, no port)."""
    async with asgi_client(tmp_path) as c:
        yield c
