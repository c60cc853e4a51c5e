"""The queue page over the real app (ASGI, embedded, no workers so jobs stay queued):
totals for everyone, each job and worker for an admin, only one's own jobs otherwise;
the navigation links it."""

from __future__ import annotations

import re
from collections.abc import AsyncIterator
from pathlib import Path

import httpx
import pytest

from service.app import create_app
from service.config import Settings

pytestmark = [pytest.mark.integration, pytest.mark.anyio]

ALICE, BOB, ROOT = (
    "alice-queue-secret-1f2e3d",
    "bob-queue-secret-4c5b6a",
    "root-queue-secret-998877",
)
FOURBAR = {"inputs": {"lengths": [2, 7, 9, 6], "ground": 1}}
CHAINS = {"inputs": {"chains": [{"links": 4, "joints": 4}]}}


@pytest.fixture
def anyio_backend() -> str:
    return "asyncio"


@pytest.fixture
async def client(tmp_path: Path) -> AsyncIterator[httpx.AsyncClient]:
    settings = Settings(data_dir=tmp_path, workers=0,
                        api_keys=f"alice:{ALICE},bob:{BOB},root:{ROOT}:admin")  # fmt: skip
    app = create_app(settings)
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://dexlab.test") as c:
            yield c


def as_(key: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {key}"}


async def submit(client: httpx.AsyncClient, key: str, process: str = "fourbar-grashof") -> str:
    r = await client.post(f"/v1/processes/{process}/execution", json=FOURBAR, headers=as_(key))
    assert r.status_code == 201, r.text
    return str(r.json()["jobID"])


async def test_each_key_sees_the_totals_and_its_own_jobs(client: httpx.AsyncClient) -> None:
    alices = [await submit(client, ALICE), await submit(client, ALICE)]
    bobs = await submit(client, BOB)
    page = (await client.get("/queue", headers=as_(ALICE))).text
    totals = re.search(r'<p id="queue-totals">(.*?)</p>', page, re.S)
    assert totals and "<strong>3</strong> queued and <strong>0</strong> running" in totals.group(1)
    row = re.search(r'<tr><th scope="row"><a href="/v1/processes/fourbar-grashof">.*?</tr>', page)
    assert row and [int(n) for n in re.findall(r'<td class="num">(\d+)</td>', row.group(0))] == [
        3, 0, 2, 0,
    ]  # fmt: skip
    assert all(f'href="/v1/jobs/{j}"' in page for j in alices) and bobs not in page
    assert "Your queued and running jobs" in page
    assert '<table class="workers">' not in page and "an admin key sees each" in page
    assert re.search(r'<p id="throughput">In the last 1 h 00 min: <strong>0</strong> jobs', page)
    admin = (await client.get("/queue", headers=as_(ROOT))).text
    assert all(f'href="/v1/jobs/{j}"' in admin for j in [*alices, bobs])
    assert "Yours queued" not in admin and "No worker has beaten" in admin
    assert 'href="/queue" aria-current="page">Queue</a>' in admin
    landing = (await client.get("/", headers={**as_(ALICE), "Accept": "text/html"})).text
    assert '<a href="/queue">Queue</a>' in landing
    assert (await client.get("/queue")).status_code == 401  # keys on: a key is needed
