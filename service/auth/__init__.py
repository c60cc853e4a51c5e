"""Who may use the service: API keys, browser sessions, job ownership.

- :mod:`service.auth.gate`: the middleware every request passes (public routes,
  Bearer keys, session cookies, 401);
- :mod:`service.auth.authenticator`: a request's key or session to an
  :class:`Identity`; :mod:`service.auth.key_cache`: the store's keys, at most a second
  old; :mod:`service.auth.sessions`: signed session and CSRF tokens;
  :mod:`service.auth.seeding`: ``DEXLAB_API_KEYS`` at start-up.

Route handlers take :data:`IdentityDep`; its ``owner_scope`` is what they pass to the
store's ``owner`` filters (None for an admin: every owner).
"""

from __future__ import annotations

from service.auth.errors import Forbidden, Unauthenticated
from service.auth.identity import ANONYMOUS_OPERATOR, Identity, IdentityDep, get_identity

__all__ = [
    "ANONYMOUS_OPERATOR",
    "Forbidden",
    "Identity",
    "IdentityDep",
    "Unauthenticated",
    "get_identity",
]
