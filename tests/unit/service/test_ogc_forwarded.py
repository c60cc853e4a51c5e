"""X-Forwarded-* from trusted proxies only, and the public base URL built from them."""

from __future__ import annotations

from typing import Any

import httpx
import pytest
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import JSONResponse
from starlette.routing import Route

from service.ogc.forwarded import ForwardedHeaders, parse_trusted, public_base_url

pytestmark = pytest.mark.anyio

PROXY_HEADERS = {
    "X-Forwarded-Proto": "https",
    "X-Forwarded-Host": "dexlab.example.org",
    "X-Forwarded-Prefix": "/kinematics/",
    "X-Forwarded-For": "203.0.113.7, 10.0.0.2",
}


def echo(request: Request) -> JSONResponse:
    client = request.client
    return JSONResponse(
        {"base": public_base_url(request), "client": client.host if client else None}
    )


async def seen(
    trusted: str, peer: str, headers: dict[str, str], host: str = "internal:8000"
) -> dict[str, Any]:
    app = ForwardedHeaders(Starlette(routes=[Route("/", echo)]), trusted=trusted)
    transport = httpx.ASGITransport(app=app, client=(peer, 5555))
    async with httpx.AsyncClient(transport=transport, base_url=f"http://{host}") as client:
        answer: dict[str, Any] = (await client.get("/", headers=headers)).json()
        return answer


async def test_a_trusted_proxy_sets_scheme_host_prefix_and_client() -> None:
    got = await seen("127.0.0.1,::1", "127.0.0.1", PROXY_HEADERS)
    assert got == {"base": "https://dexlab.example.org/kinematics", "client": "10.0.0.2"}


async def test_a_network_of_proxies_is_trusted_and_skipped_in_the_client_chain() -> None:
    got = await seen("10.0.0.0/8", "10.1.2.3", PROXY_HEADERS)
    # 10.0.0.2 is a trusted proxy too: the client is the hop before it.
    assert got == {"base": "https://dexlab.example.org/kinematics", "client": "203.0.113.7"}


async def test_an_untrusted_peer_cannot_change_the_links() -> None:
    got = await seen("127.0.0.1", "198.51.100.9", PROXY_HEADERS)
    assert got == {"base": "http://internal:8000", "client": "198.51.100.9"}


async def test_any_peer_with_a_star() -> None:
    got = await seen("*", "198.51.100.9", {"X-Forwarded-Host": "public.example:8443"})
    assert got["base"] == "http://public.example:8443"


async def test_malformed_forwarded_values_are_ignored() -> None:
    headers = {
        "X-Forwarded-Proto": "gopher",
        "X-Forwarded-Host": 'evil.example"><script>',
        "X-Forwarded-Prefix": "/a b",
    }
    got = await seen("127.0.0.1", "127.0.0.1", headers)
    assert got["base"] == "http://internal:8000"


async def test_the_first_of_several_forwarded_values_is_the_clients() -> None:
    headers = {
        "X-Forwarded-Host": "outer.example, inner.example",
        "X-Forwarded-Proto": "https, http",
    }
    got = await seen("127.0.0.1", "127.0.0.1", headers)
    assert got["base"] == "https://outer.example"


def test_trusted_setting() -> None:
    assert parse_trusted("*") is None
    networks = parse_trusted("127.0.0.1, ::1, 10.0.0.0/8")
    assert networks is not None and len(networks) == 3
    with pytest.raises(ValueError, match="'forwarded_allow_ips' setting"):
        parse_trusted("proxy.internal")
