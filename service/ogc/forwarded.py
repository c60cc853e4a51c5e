"""The public URL of the service behind a reverse proxy (``X-Forwarded-*``).

A proxy in front of dexlab tells it how clients reached it: ``X-Forwarded-Proto``
(http or https), ``X-Forwarded-Host`` (host[:port]), ``X-Forwarded-Prefix`` (a path
the proxy mounts the service under) and ``X-Forwarded-For`` (the client's address).
These headers are believed only from the proxies named in the ``forwarded_allow_ips``
setting (default: this machine), since any client can send them.  The
:class:`ForwardedHeaders` middleware applies them once per request (scheme and client
address in the ASGI scope, as uvicorn would; the host and prefix kept for
:func:`public_base_url`), so every absolute link and ``Location`` the API sends
points where the client can follow it.
"""

from __future__ import annotations

import ipaddress
import re
from collections.abc import Sequence

from starlette.datastructures import Headers
from starlette.requests import Request
from starlette.types import ASGIApp, Receive, Scope, Send

__all__ = ["ForwardedHeaders", "parse_trusted", "public_base_url"]

Network = ipaddress.IPv4Network | ipaddress.IPv6Network

_HOST = re.compile(
    r"(?:[A-Za-z0-9](?:[A-Za-z0-9.-]{0,251}[A-Za-z0-9])?|\[[0-9A-Fa-f:.]+\])"
    r"(?::[0-9]{1,5})?"
)
_PREFIX = re.compile(r"(?:/[A-Za-z0-9._~!$&'()*+,;=:@%-]+)*/?")
_SCOPE_KEY = "dexlab.forwarded"


def parse_trusted(value: str) -> tuple[Network, ...] | None:
    """The trusted proxies of a ``forwarded_allow_ips`` value: networks, or None for
    '*' (any).  Raises ValueError naming a bad entry."""
    entries = [e.strip() for e in value.split(",") if e.strip()]
    if "*" in entries:
        return None
    networks = []
    for entry in entries:
        try:
            networks.append(ipaddress.ip_network(entry, strict=False))
        except ValueError:
            raise ValueError(
                "The 'forwarded_allow_ips' setting must list IP addresses or networks "
                f"(CIDR) separated by commas, or '*'. Got {entry!r} instead."
            ) from None
    return tuple(networks)


def _trusted(peer: str | None, networks: Sequence[Network] | None) -> bool:
    if networks is None:
        return True
    if peer is None:
        return False
    try:
        address = ipaddress.ip_address(peer)
    except ValueError:
        return False
    return any(address in network for network in networks)


def _first(headers: Headers, name: str) -> str | None:
    """The first (client-most) value of a forwarded header, or None."""
    value = headers.get(name)
    if value is None:
        return None
    return value.split(",")[0].strip() or None


def _client(forwarded_for: str, networks: Sequence[Network] | None) -> str | None:
    """The client's address from X-Forwarded-For: the last hop not a trusted proxy."""
    hops = [h.strip() for h in forwarded_for.split(",") if h.strip()]
    for hop in reversed(hops):
        if not _trusted(hop, networks):
            return hop
    return hops[0] if hops else None


class ForwardedHeaders:
    """Apply a trusted proxy's ``X-Forwarded-*`` headers (outermost middleware)."""

    def __init__(self, app: ASGIApp, *, trusted: str) -> None:
        self.app = app
        self.networks = parse_trusted(trusted)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http":
            client = scope.get("client")
            if _trusted(client[0] if client else None, self.networks):
                self._apply(scope)
        await self.app(scope, receive, send)

    def _apply(self, scope: Scope) -> None:
        headers = Headers(scope=scope)
        proto = (_first(headers, "x-forwarded-proto") or "").lower()
        if proto in ("http", "https"):
            scope["scheme"] = proto
        forwarded_for = headers.get("x-forwarded-for")
        client = _client(forwarded_for, self.networks) if forwarded_for else None
        if client:
            scope["client"] = (client, 0)
        host = _first(headers, "x-forwarded-host")
        prefix = _first(headers, "x-forwarded-prefix")
        scope[_SCOPE_KEY] = {
            "host": host if host and _HOST.fullmatch(host) else None,
            "prefix": prefix.rstrip("/") if prefix and _PREFIX.fullmatch(prefix) else "",
        }


def public_base_url(request: Request) -> str:
    """``scheme://host[:port][/prefix]``: where clients reach this service."""
    forwarded = request.scope.get(_SCOPE_KEY) or {}
    host = forwarded.get("host") or request.headers.get("host", "")
    if not _HOST.fullmatch(host):  # no usable Host header: the address it was sent to
        name, port = request.scope.get("server") or ("localhost", None)
        name = f"[{name}]" if ":" in name else name
        host = name if port in (None, 80, 443) else f"{name}:{port}"
    return f"{request.url.scheme}://{host}{forwarded.get('prefix', '')}"
