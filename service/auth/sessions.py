"""Browser sessions and CSRF tokens: HMAC-SHA256 over a secret every replica shares.

A session token names the key it was opened with (its ``key_id``, which changes when
the key's secret is replaced) and when it ends, with a random nonce, signed::

    v1.<key_id>.<expires, epoch s>.<nonce>.<signature>

It lives in an HttpOnly, ``SameSite=Strict`` cookie.  It holds nothing secret; what
makes it trustworthy is the signature, and what ends it early is the key: every
request looks its ``key_id`` up among the live keys, so revoking a key (or replacing
its secret) ends its sessions within a second.

A page form's CSRF token is the HMAC of the session token under the same secret: a
form rendered for one session is refused under any other, and a site that cannot read
the page cannot know it.
"""

from __future__ import annotations

import base64
import hashlib
import hmac
import secrets
import time
from collections.abc import Callable

__all__ = ["COOKIE_NAME", "CSRF_FIELD", "SessionSigner"]

#: The session cookie.
COOKIE_NAME = "dexlab_session"
#: The hidden form field carrying the CSRF token.
CSRF_FIELD = "csrf_token"

_VERSION = "v1"


def _b64(data: bytes) -> str:
    return base64.urlsafe_b64encode(data).decode("ascii").rstrip("=")


def _same(given: str, expected: str) -> bool:
    """Constant-time equality of a client's string (any characters) and ours."""
    return hmac.compare_digest(given.encode("utf-8", "backslashreplace"), expected.encode())


class SessionSigner:
    """Issues and checks session tokens and their CSRF tokens.

    ``secret`` (at least 32 bytes) signs; ``lifetime_s`` is how long a session lasts;
    ``clock`` gives epoch seconds (tests move it)."""

    def __init__(
        self, secret: bytes, lifetime_s: float, clock: Callable[[], float] = time.time
    ) -> None:
        if len(secret) < 32:
            raise ValueError(
                f"The session secret must be at least 32 bytes. Got {len(secret)} instead."
            )
        self._secret = secret
        self.lifetime_s = lifetime_s
        self._clock = clock

    def _sign(self, purpose: str, message: str) -> str:
        mac = hmac.new(self._secret, f"{purpose}:{message}".encode(), hashlib.sha256)
        return _b64(mac.digest())

    def issue(self, key_id: str) -> str:
        """A new session token for the key ``key_id``."""
        if not key_id or "." in key_id:
            raise ValueError(f"A key_id must be non-empty and dot-free. Got {key_id!r} instead.")
        expires = int(self._clock() + self.lifetime_s)
        body = f"{_VERSION}.{key_id}.{expires}.{secrets.token_urlsafe(12)}"
        return f"{body}.{self._sign('session', body)}"

    def key_id_of(self, token: str) -> str | None:
        """The key a valid, unexpired token names; None for anything else."""
        body, _, signature = token.rpartition(".")
        parts = body.split(".")
        if len(parts) != 4 or parts[0] != _VERSION or not parts[2].isdigit():
            return None
        if not _same(signature, self._sign("session", body)):
            return None
        if int(parts[2]) <= self._clock():
            return None
        return parts[1]

    def csrf_token(self, session: str) -> str:
        """The CSRF token of every form rendered for this session."""
        return self._sign("csrf", session)

    def csrf_matches(self, session: str, token: str) -> bool:
        """Whether ``token`` is this session's CSRF token (constant time)."""
        return _same(token, self.csrf_token(session))
