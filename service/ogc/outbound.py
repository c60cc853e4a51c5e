"""The requests this service makes to other hosts, and the allow-list that bounds them.

OGC API - Processes has a server call out twice: to fetch an input given by reference
(``{"href": ...}``) and to POST a job's results to a ``subscriber`` URI.  Either is a
request the server makes on a client's word, so it goes only to the hosts the
``outbound_allow_hosts`` setting names (empty by default: none).  Every request has a
short timeout, follows no redirect (a redirect could leave the allow-list), and reads
a bounded body; the allow-list is checked again just before each request.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from typing import Any
from urllib.parse import urlsplit

import httpx

__all__ = ["OutboundPolicy"]

_USER_AGENT = "dexlab (OGC API - Processes)"
_HOST_NAME = re.compile(r"[a-z0-9](?:[a-z0-9.-]*[a-z0-9])?|[0-9a-f:.]+")


@dataclass(frozen=True)
class OutboundPolicy:
    """Allowed ``(host, port)`` pairs (port None: any) and the request timeout."""

    hosts: frozenset[tuple[str, int | None]]
    timeout_s: float = 5.0

    @classmethod
    def from_setting(cls, value: str, timeout_s: float = 5.0) -> OutboundPolicy:
        """From ``host[:port]`` entries separated by commas.  Raises ValueError naming
        a bad entry."""
        hosts: set[tuple[str, int | None]] = set()
        for entry in (e.strip() for e in value.split(",")):
            if not entry:
                continue
            parts = urlsplit(f"//{entry}")
            try:
                port = parts.port
            except ValueError:
                port = -1
            host = parts.hostname or ""
            if not _HOST_NAME.fullmatch(host) or port == -1 or parts.path or parts.username:
                raise ValueError(
                    "The 'outbound_allow_hosts' setting must list host names or host:port "
                    f"separated by commas. Got {entry!r} instead."
                )
            hosts.add((host, port))
        return cls(frozenset(hosts), timeout_s)

    @property
    def enabled(self) -> bool:
        return bool(self.hosts)

    def refusal(self, uri: str) -> str | None:
        """Why this service will not send a request to ``uri`` (None: it will)."""
        if not self.enabled:
            return (
                "this server sends no requests to other hosts (its DEXLAB_OUTBOUND_ALLOW_HOSTS "
                "setting is empty)"
            )
        try:
            parts = urlsplit(uri)
            port = parts.port
        except ValueError:
            return f"{uri!r} is not a valid URL"
        if parts.scheme not in ("http", "https") or not parts.hostname:
            return f"{uri!r} is not an absolute http or https URL"
        if parts.username or parts.password:
            return "a URL with credentials in it is not accepted"
        host = parts.hostname.lower()
        effective = port or (443 if parts.scheme == "https" else 80)
        if (host, None) in self.hosts or (host, effective) in self.hosts:
            return None
        return f"the host {host}:{effective} is not on this server's allow-list"

    def fetch_json(self, uri: str, max_bytes: int) -> Any:
        """GET ``uri`` and parse its JSON body (at most ``max_bytes``).  Raises
        ValueError saying what went wrong."""
        why = self.refusal(uri)
        if why is not None:
            raise ValueError(why)
        headers = {"Accept": "application/json", "User-Agent": _USER_AGENT}
        try:
            with (
                httpx.Client(timeout=self.timeout_s, follow_redirects=False) as client,
                client.stream("GET", uri, headers=headers) as response,
            ):
                if response.status_code != 200:
                    raise ValueError(f"GET {uri} answered {response.status_code}, not 200")
                body = bytearray()
                for chunk in response.iter_bytes():
                    body.extend(chunk)
                    if len(body) > max_bytes:
                        raise ValueError(f"GET {uri} sent more than {max_bytes} bytes")
        except httpx.HTTPError as exc:
            raise ValueError(f"GET {uri} failed: {type(exc).__name__}: {exc}") from None
        try:
            return json.loads(body.decode("utf-8"))
        except (UnicodeDecodeError, json.JSONDecodeError) as exc:
            raise ValueError(f"GET {uri} did not answer JSON ({exc})") from None
        except RecursionError:
            raise ValueError(f"GET {uri} answered JSON nested too deeply") from None

    async def post(self, client: httpx.AsyncClient, uri: str, body: bytes, media_type: str) -> bool:
        """POST ``body`` to ``uri`` (allow-list checked again first); True when it
        answered 2xx."""
        if self.refusal(uri) is not None:
            return False
        headers = {"Content-Type": media_type, "User-Agent": _USER_AGENT}
        try:
            response = await client.post(uri, content=body, headers=headers, timeout=self.timeout_s)
        except httpx.HTTPError:
            return False
        return 200 <= response.status_code < 300
