"""Fixtures that run the real service, on each backend.

Every integration test runs once per backend: the embedded default (SQLite + local
pool) and PostgreSQL + Celery with a real broker (Redis, RabbitMQ).  Where PostgreSQL
or a broker is not reachable those runs skip, or fail under DEXLAB_REQUIRE_SERVICES.
"""

from __future__ import annotations

from collections.abc import AsyncIterator, Iterator
from contextlib import ExitStack
from pathlib import Path
from typing import Any

import httpx
import pytest

from service.app import create_app
from service.config import Settings
from tests.browser import chromium, screenshot_dir
from tests.integration.servers import BACKENDS, Deployment, backend_env, deployment

pytestmark = pytest.mark.integration


@pytest.fixture
def anyio_backend() -> str:
    return "asyncio"


@pytest.fixture(params=BACKENDS)
def backend(request: pytest.FixtureRequest) -> str:
    return str(request.param)


@pytest.fixture
async def asgi_client(backend: str, tmp_path: Path) -> AsyncIterator[httpx.AsyncClient]:
    """The real app over httpx's ASGI transport: with its one-process pool (embedded),
    or as the API of a Celery deployment with one `dexlab worker` process."""
    with ExitStack() as stack:
        env = backend_env(backend, stack)
        settings = Settings(
            data_dir=tmp_path,
            workers=1,
            heartbeat_seconds=0.5,
            store_url=env.get("DEXLAB_STORE_URL"),
            broker_url=env.get("DEXLAB_BROKER_URL"),
            queue=env.get("DEXLAB_QUEUE", "dexlab"),
        )
        if backend != "embedded":
            workers = Deployment(backend, tmp_path, env)
            stack.callback(workers.stop)
            workers.start_worker(1)
        app = create_app(settings)
        async with app.router.lifespan_context(app):
            transport = httpx.ASGITransport(app=app)
            async with httpx.AsyncClient(transport=transport, base_url="http://dexlab.test") as c:
                yield c


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    """A headless Chromium for the module's browser tests (skips where there is none)."""
    with chromium() as b:
        yield b


@pytest.fixture(scope="module")
def shots(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Where the module's screenshots go (kept for the docs when asked)."""
    module = request.module.__name__.rsplit(".", 1)[-1].removeprefix("test_")
    return screenshot_dir(tmp_path_factory.mktemp(f"{module}-shots"))


@pytest.fixture(scope="module", params=BACKENDS)
def server(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Deployment]:
    """A deployment with two worker processes, shared by a test module."""
    with deployment(str(request.param), tmp_path_factory.mktemp("dexlab")) as dep:
        yield dep


#: Modules whose tests measure time (leases, outages, latencies) or kill processes on
#: purpose: under pytest-xdist they run one after another on one process, beside the
#: other modules (see `pytest_xdist_make_scheduler`).
TIMED_MODULES = frozenset(
    {
        "test_faults",
        "test_server",
        "test_fairness",
        "test_pages_events",
        "test_frozen_workers",
        "test_store_outage",
    }
)
TIMED = "timed"


def xdist_scope(nodeid: str) -> str:
    """The unit of work one xdist process takes whole: the test's module (so its
    module-scoped servers start once), or :data:`TIMED` for the timed modules."""
    module = nodeid.split("::", 1)[0]
    return TIMED if Path(module).stem in TIMED_MODULES else module


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log: Any) -> Any:
    """Whole modules per process, the timed ones as one unit handed out first (it is
    the longest).  (xdist's `loadgroup` would do it with markers, but it renames node
    IDs in a way pytest 9 no longer sees.)"""
    from xdist.scheduler import LoadScopeScheduling

    class ModuleScheduling(LoadScopeScheduling):  # type: ignore[misc]
        def _split_scope(self, nodeid: str) -> str:
            return xdist_scope(nodeid)

        def _assign_work_unit(self, node: Any) -> None:
            if TIMED in self.workqueue:
                self.workqueue.move_to_end(TIMED, last=False)
            super()._assign_work_unit(node)

    return ModuleScheduling(config, log)
