"""Turning what a request carries (a Bearer key, a session cookie) into an identity.

Built once per app in the lifespan (it needs the store) and kept on
``app.state.auth``; :mod:`service.auth.gate` asks it about every request.
"""

from __future__ import annotations

import secrets

import anyio
from starlette.datastructures import Headers
from starlette.requests import cookie_parser

from service.auth.errors import Unauthenticated
from service.auth.identity import ANONYMOUS_OPERATOR, Identity
from service.auth.key_cache import KeyCache, KeyTable
from service.auth.sessions import COOKIE_NAME, SessionSigner
from worker.store.base import ApiKey, JobStore

__all__ = ["SESSION_SECRET_NAME", "Authenticator", "session_signer"]

#: The name of the shared session-signing secret in the store.
SESSION_SECRET_NAME = "session-signing"


def session_signer(store: JobStore, configured: str | None, lifetime_s: float) -> SessionSigner:
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


class Authenticator:
    """Who a request is (see :meth:`identify`)."""

    def __init__(self, keys: KeyCache, signer: SessionSigner) -> None:
        self.keys = keys
        self.signer = signer

    async def table(self, max_age_s: float | None = None) -> KeyTable:
        """The key table, read in a worker thread when it is older than ``max_age_s``
        (default: the cache's)."""
        fresh = self.keys.fresh(max_age_s)
        if fresh is not None:
            return fresh
        return await anyio.to_thread.run_sync(self.keys.table, max_age_s)

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
            key = await self.live_key(token)
            if key is None:
                raise Unauthenticated(
                    "The API key sent is not valid: unknown or revoked."
                    if token
                    else "The Authorization header must be 'Bearer <secret>'.",
                    invalid=True,
                )
            return self._identity(key, "bearer")
        session = cookie_parser(headers.get("cookie", "")).get(COOKIE_NAME)
        if session:
            key_id = self.signer.key_id_of(session)
            key = table.by_id.get(key_id) if key_id else None
            if key is not None:
                return self._identity(key, "session", session)
        return Identity(name="", admin=False, keys_on=True, via="none")
