"""The service's own refusals, beside the job runtime's tree (:mod:`worker.errors`)::

    DexlabError (worker.errors)
    ├── Unauthenticated    no key, a wrong or revoked key, an ended session (401)
    └── Forbidden          known, but not allowed this: an admin-only parameter, a
                           page form without its CSRF token (403)

Each class's docstring is its default message; :mod:`service.errors` maps them to
``/problems/unauthorized`` and ``/problems/forbidden``.
"""

from __future__ import annotations

from typing import Any

from worker.errors import DexlabError

__all__ = ["Forbidden", "Unauthenticated"]


class Unauthenticated(DexlabError):
    """This service needs an API key: send `Authorization: Bearer <secret>`."""

    def __init__(self, detail: str | None = None, *, invalid: bool = False, **extra: Any) -> None:
        super().__init__(detail, **extra)
        #: The ``WWW-Authenticate`` challenge (RFC 6750: ``invalid_token`` when a key
        #: was sent and is wrong or revoked).
        self.challenge = 'Bearer realm="dexlab"' + (', error="invalid_token"' if invalid else "")


class Forbidden(DexlabError):
    """This request is not allowed for this key."""
