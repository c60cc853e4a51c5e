"""Who is asking: the identity every request carries once :mod:`service.auth.gate`
has let it through."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Literal

from fastapi import Depends, Request

from service.auth.errors import Forbidden, Unauthenticated

__all__ = ["ANONYMOUS_OPERATOR", "Identity", "IdentityDep", "get_identity"]

#: How a request proved who it is.
Via = Literal["open", "bearer", "session", "none"]


@dataclass(frozen=True)
class Identity:
    """The caller.  ``name`` is the owner its jobs get ('' = anonymous).

    With no key configured (``keys_on`` false) everyone is the one anonymous owner and
    the operator (``admin``), as before keys existed.  With keys, a request came with a
    Bearer key or a session cookie (``via``); ``via == "none"`` only reaches public
    routes."""

    name: str
    admin: bool
    keys_on: bool
    via: Via
    key_id: str | None = None
    #: The session token the request came with (CSRF tokens are derived from it).
    session: str | None = None

    @property
    def owner_scope(self) -> str | None:
        """The owner whose jobs this caller may see (None: every owner's)."""
        return None if self.admin else self.name

    @property
    def signed_in(self) -> bool:
        return self.via in ("bearer", "session")

    @property
    def sees_workers(self) -> bool:
        """Whether status documents show ``worker_id`` (host:pid): admins only."""
        return self.admin

    @property
    def sees_owners(self) -> bool:
        """Whether status documents name each job's ``owner``: admins, with keys on."""
        return self.admin and self.keys_on

    def owner_filter(self, requested: str | None) -> str | None:
        """The owner a job listing selects: the caller's own jobs, or for an admin the
        ``requested`` owner's (None: every owner's).  A non-admin naming an owner is
        refused (403), even its own name: the parameter is an admin's."""
        if requested is None:
            return self.owner_scope
        if not self.admin:
            raise Forbidden(
                "Only an admin key may list jobs by owner ('owner'); without it, the "
                "list holds this key's jobs."
            )
        return requested


ANONYMOUS_OPERATOR = Identity(name="", admin=True, keys_on=False, via="open")


def get_identity(request: Request) -> Identity:
    """The identity the gate attached; none attached (a request that bypassed the
    gate) is refused, never taken for the operator."""
    identity = getattr(request.state, "identity", None)
    if not isinstance(identity, Identity):
        raise Unauthenticated("The request was not authenticated.")
    return identity


async def _identity_dependency(request: Request) -> Identity:
    """:func:`get_identity` as a coroutine (no threadpool hop; see :mod:`service.deps`)."""
    return get_identity(request)


IdentityDep = Annotated[Identity, Depends(_identity_dependency)]
