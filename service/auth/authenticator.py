"""Turning what a request carries (a Bearer key, a session cookie) into an identity.

Built once per app in the lifespan (it needs the store) and kept on
``app.state.auth``; :mod:`service.auth.gate` asks it about every request.

When the key table must be read again, the requests that ask meanwhile share one read
(in a worker thread) and its outcome, its table or its ``StoreUnavailable``: with the
store down, they all get their 503 when that one read gives up, not one retry window
after another, and none of them holds a thread while it waits.  Routes that answer
anyone (:meth:`Authenticator.identify_now`) never wait for the store at all.
"""

from __future__ import annotations

import asyncio
import contextlib
import secrets

import anyio
from starlette.datastructures import Headers
from starlette.requests import cookie_parser

from service.auth.errors import Unauthenticated
from service.auth.identity import ANONYMOUS_OPERATOR, Identity
from service.auth.key_cache import KeyCache, KeyTable
from service.auth.sessions import COOKIE_NAME, SessionSigner
from worker.errors import StoreUnavailable
from worker.store.base import ApiKey, KeysPort

__all__ = ["SESSION_SECRET_NAME", "Authenticator", "session_signer"]

#: The name of the shared session-signing secret in the store.
SESSION_SECRET_NAME = "session-signing"


def session_signer(store: KeysPort, configured: str | None, lifetime_s: float) -> SessionSigner:
    """The signer of this deployment's sessions: ``DEXLAB_SESSION_SECRET`` when set,
    else a secret generated once and kept in the store, so every replica signs and
    checks with the same one."""
    secret = configured or store.shared_secret(
        SESSION_SECRET_NAME, lambda: secrets.token_urlsafe(48)
    )
    return SessionSigner(secret.encode("utf-8"), lifetime_s)


def _bearer(header: str) -> str:
    """The token of ``Authorization: Bearer <token>`` ('' for another scheme)."""
    scheme, _, token = header.strip().partition(" ")
    return token.strip() if scheme.lower() == "bearer" else ""


def _outcome_seen(read: asyncio.Task[KeyTable]) -> None:
    """Mark a shared read's failure as seen (its waiters, if any, got it too)."""
    if not read.cancelled():
        read.exception()


class Authenticator:
    """Who a request is (see :meth:`identify`)."""

    def __init__(self, keys: KeyCache, signer: SessionSigner) -> None:
        self.keys = keys
        self.signer = signer
        self._reading: asyncio.Task[KeyTable] | None = None

    async def table(self, max_age_s: float | None = None) -> KeyTable:
        """The key table: the cache's if younger than ``max_age_s`` (default: the
        cache's), else the outcome of the read in flight (one is started if none is).
        A caller that goes away does not stop the read.  Raises StoreUnavailable."""
        fresh = self.keys.fresh(max_age_s)
        if fresh is not None:
            return fresh
        return await asyncio.shield(self._shared_read())

    def _shared_read(self) -> asyncio.Task[KeyTable]:
        """The read of the key table in flight, or a new one."""
        read = self._reading
        if read is None or read.done():
            read = asyncio.ensure_future(anyio.to_thread.run_sync(self.keys.read))
            read.add_done_callback(_outcome_seen)
            self._reading = read
        return read

    async def aclose(self) -> None:
        """Wait for the read in flight, if any (the store closes after this)."""
        read = self._reading
        if read is not None and not read.done():
            with contextlib.suppress(Exception):
                await read

    async def live_key(self, secret: str) -> ApiKey | None:
        """The live key with this secret: from the cache, or (not found there) from a
        read at most ``recheck_s`` old, so a key made a moment ago is found."""
        if not secret:
            return None
        key = (await self.table()).by_secret(secret)
        if key is None:
            key = (await self.table(self.keys.recheck_s)).by_secret(secret)
        return key

    def _identity(self, key: ApiKey, via: str, session: str | None = None) -> Identity:
        self.keys.note_use(key)
        return Identity(
            name=key.name,
            admin=key.admin,
            keys_on=True,
            via="bearer" if via == "bearer" else "session",
            key_id=key.key_id,
            session=session,
        )

    async def identify(self, headers: Headers) -> Identity:
        """The caller.  With no key configured: the anonymous operator.  With keys: the
        key an ``Authorization: Bearer`` header names (a wrong or revoked one raises
        :class:`Unauthenticated`), else the key of a valid session cookie, else nobody
        (``via == "none"``).  Raises StoreUnavailable when the keys cannot be read."""
        table = await self.table()
        if not table.configured:
            return ANONYMOUS_OPERATOR
        authorization = headers.get("authorization")
        if authorization is not None:
            token = _bearer(authorization)
            return self._bearer(token, await self.live_key(token))
        return self._session(table, headers)

    def identify_now(self, headers: Headers) -> Identity:
        """:meth:`identify` without waiting, for the routes that answer anyone: from the
        last table read, however old (a read is started if it is older than the
        cache's ``max_age_s``, for the next requests).  A key not in that table raises
        :class:`Unauthenticated`; StoreUnavailable if no table was ever read."""
        table = self.keys.latest()
        if self.keys.fresh() is None:
            self._shared_read()
        if table is None:
            raise StoreUnavailable("The API keys have not been read yet; try again.")
        if not table.configured:
            return ANONYMOUS_OPERATOR
        authorization = headers.get("authorization")
        if authorization is not None:
            token = _bearer(authorization)
            return self._bearer(token, table.by_secret(token) if token else None)
        return self._session(table, headers)

    def _bearer(self, token: str, key: ApiKey | None) -> Identity:
        if key is None:
            raise Unauthenticated(
                "The API key sent is not valid: unknown or revoked."
                if token
                else "The Authorization header must be 'Bearer <secret>'.",
                invalid=True,
            )
        return self._identity(key, "bearer")

    def _session(self, table: KeyTable, headers: Headers) -> Identity:
        session = cookie_parser(headers.get("cookie", "")).get(COOKIE_NAME)
        if session:
            key_id = self.signer.key_id_of(session)
            key = table.by_id.get(key_id) if key_id else None
            if key is not None:
                return self._identity(key, "session", session)
        return Identity(name="", admin=False, keys_on=True, via="none")
