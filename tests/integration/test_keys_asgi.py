"""Keys, sessions and CORS over the real app (ASGI, embedded, no workers): what a
browser's cookie may do, where login sends it, https cookies, CORS headers, and the
warning of an open service listening beyond this machine."""

from __future__ import annotations

import logging
from collections.abc import AsyncIterator
from pathlib import Path

import httpx
import pytest

from service.app import create_app
from service.auth.sessions import COOKIE_NAME, SessionSigner
from service.config import Settings

pytestmark = [pytest.mark.integration, pytest.mark.anyio]

ALICE = "alice-asgi-secret-77e1c0"
SAME_ORIGIN = {"Origin": "http://dexlab.test"}
FOURBAR = {"inputs": {"lengths": [2, 7, 9, 6], "ground": 1}}
SESSION_SECRET = "session-secret-for-tests-0123456789abcdef"


@pytest.fixture
def anyio_backend() -> str:
    return "asyncio"


@pytest.fixture
async def client(tmp_path: Path) -> AsyncIterator[httpx.AsyncClient]:
    settings = Settings(
        data_dir=tmp_path,
        workers=0,
        api_keys=f"alice:{ALICE}",
        session_secret=SESSION_SECRET,
        cors_origins="https://app.example",
    )
    app = create_app(settings)
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://dexlab.test") as c:
            yield c


async def log_in(client: httpx.AsyncClient, **headers: str) -> httpx.Response:
    return await client.post(
        "/login", data={"key": ALICE, "next": "/v1/jobs"}, headers={**SAME_ORIGIN, **headers}
    )


async def test_login_sets_a_strict_http_only_cookie_and_refuses_a_wrong_key(
    client: httpx.AsyncClient,
) -> None:
    wrong = await client.post("/login", data={"key": "nope"}, headers=SAME_ORIGIN)
    assert wrong.status_code == 401 and "not a live API key" in wrong.text
    assert wrong.headers["www-authenticate"].startswith("Bearer") and COOKIE_NAME not in (
        wrong.headers.get("set-cookie", "")
    )
    elsewhere = await client.post(
        "/login", data={"key": ALICE}, headers={"Origin": "https://evil.example"}
    )
    assert elsewhere.status_code == 403  # login CSRF: only this service's own form
    r = await log_in(client)
    assert r.status_code == 303 and r.headers["location"] == "/v1/jobs"
    cookie = r.headers["set-cookie"]
    assert cookie.startswith(f"{COOKIE_NAME}=") and "HttpOnly" in cookie
    assert "SameSite=strict" in cookie and "Secure" not in cookie and ALICE not in cookie
    page = await client.get("/v1/jobs", headers={"Accept": "text/html"})
    assert page.status_code == 200 and "Signed in as" in page.text


async def test_over_https_the_cookie_is_secure(client: httpx.AsyncClient) -> None:
    # From the trusted proxy (127.0.0.1, the default), X-Forwarded-Proto is believed.
    r = await log_in(client, **{"X-Forwarded-Proto": "https", "Origin": "https://dexlab.test"})
    assert r.status_code == 303 and "Secure" in r.headers["set-cookie"]


@pytest.mark.parametrize(
    "target", ["//evil.example/x", "https://evil.example/", "/\\evil.example", "/logout"]
)
async def test_login_sends_the_browser_only_to_this_service(
    client: httpx.AsyncClient, target: str
) -> None:
    r = await client.post("/login", data={"key": ALICE, "next": target}, headers=SAME_ORIGIN)
    assert r.status_code == 303 and r.headers["location"] == "/"


async def test_a_session_reads_but_the_json_api_writes_need_the_key(
    client: httpx.AsyncClient,
) -> None:
    await log_in(client)
    assert (await client.get("/v1/jobs")).status_code == 200
    refused = await client.post("/v1/processes/fourbar-grashof/execution", json=FOURBAR)
    assert refused.status_code == 401 and "Bearer" in refused.json()["detail"]
    keyed = await client.post(
        "/v1/processes/fourbar-grashof/execution",
        json=FOURBAR,
        headers={"Authorization": f"Bearer {ALICE}"},
    )
    assert keyed.status_code == 201
    assert (await client.delete(f"/v1/jobs/{keyed.json()['jobID']}")).status_code == 401


async def test_an_expired_or_forged_session_is_401(client: httpx.AsyncClient) -> None:
    signer = SessionSigner(SESSION_SECRET.encode(), lifetime_s=-1)  # already over
    r = await log_in(client)
    token = r.cookies[COOKIE_NAME]
    key_id = token.split(".")[1]
    for value in (signer.issue(key_id), token[:-3] + "abc"):
        client.cookies.set(COOKIE_NAME, value)
        ended = await client.get("/v1/jobs")
        assert ended.status_code == 401 and "session has ended" in ended.json()["detail"]
    client.cookies.set(COOKIE_NAME, token)
    assert (await client.get("/v1/jobs")).status_code == 200


async def test_logout_needs_its_csrf_token_and_clears_the_cookie(
    client: httpx.AsyncClient,
) -> None:
    await log_in(client)
    assert (await client.post("/logout", headers=SAME_ORIGIN)).status_code == 403
    page = (await client.get("/login")).text
    token = page.split('name="csrf_token" value="', 1)[1].split('"', 1)[0]
    r = await client.post("/logout", data={"csrf_token": token}, headers=SAME_ORIGIN)
    assert r.status_code == 303 and f'{COOKIE_NAME}=""' in r.headers["set-cookie"]
    client.cookies.clear()
    assert (await client.get("/v1/jobs")).status_code == 401


async def test_cors_lets_listed_origins_send_the_authorization_header(
    client: httpx.AsyncClient,
) -> None:
    preflight = await client.options(
        "/v1/jobs",
        headers={
            "Origin": "https://app.example",
            "Access-Control-Request-Method": "GET",
            "Access-Control-Request-Headers": "authorization",
        },
    )
    assert preflight.status_code == 200
    assert preflight.headers["access-control-allow-origin"] == "https://app.example"
    assert "authorization" in preflight.headers["access-control-allow-headers"].lower()
    listed = await client.get(
        "/v1/jobs", headers={"Origin": "https://app.example", "Authorization": f"Bearer {ALICE}"}
    )
    assert listed.status_code == 200
    assert listed.headers["access-control-allow-origin"] == "https://app.example"
    assert "access-control-allow-credentials" not in listed.headers
    refused = await client.get("/v1/jobs", headers={"Origin": "https://app.example"})
    assert refused.status_code == 401  # readable by the page: it carries the CORS header
    assert refused.headers["access-control-allow-origin"] == "https://app.example"
    other = await client.get("/v1/processes", headers={"Origin": "https://other.example"})
    assert "access-control-allow-origin" not in other.headers


async def test_an_open_service_on_a_public_address_warns(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    for host, warned in (("127.0.0.1", False), ("0.0.0.0", True)):
        caplog.clear()
        app = create_app(Settings(data_dir=tmp_path / host, workers=0, host=host))
        with caplog.at_level(logging.INFO, logger="dexlab.service"):
            async with app.router.lifespan_context(app):
                transport = httpx.ASGITransport(app=app)
                async with httpx.AsyncClient(transport=transport, base_url="http://t") as c:
                    doc = (await c.post("/v1/processes/fourbar-grashof/execution",
                                        json=FOURBAR)).json()  # fmt: skip
                    assert "worker_id" in doc and "owner" not in doc  # today's documents
        warnings = [r for r in caplog.records if r.levelno == logging.WARNING]
        assert bool([r for r in warnings if "no API keys" in r.getMessage()]) == warned
