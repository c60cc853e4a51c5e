"""``DEXLAB_API_KEYS``: keys a deployment declares, made in the store at start-up.

The value is ``name:secret`` entries separated by commas; ``name:secret:admin`` makes
an admin.  Seeding is idempotent: a key already stored with the same secret is left
as it is (a key revoked with ``dexlab keys revoke`` stays revoked: give it a new
secret to bring it back); a changed secret replaces the stored one, which then stops
working, with its sessions; the admin flag follows the declaration.  Keys made by
``dexlab keys create`` and not declared are left alone.

Errors name the entry by its position and name, never its secret.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

from worker.store.api_keys import MIN_SECRET_LENGTH, check_key_name, hash_secret
from worker.store.base import KeysPort

__all__ = ["DeclaredKey", "parse_api_keys", "seed_keys"]

log = logging.getLogger("dexlab.service")

_ADMIN = ":admin"


@dataclass(frozen=True)
class DeclaredKey:
    """One entry of ``DEXLAB_API_KEYS`` (its secret is left out of the repr)."""

    name: str
    secret: str = field(repr=False)
    admin: bool = False


def _entry(position: int, text: str) -> DeclaredKey:
    name, colon, rest = text.partition(":")
    where = f"entry {position} of DEXLAB_API_KEYS"
    if not colon:
        raise ValueError(f"The {where} must be 'name:secret' (or 'name:secret:admin').")
    try:
        check_key_name(name)
    except ValueError as exc:
        raise ValueError(f"The {where}: {exc}") from None
    admin = rest.endswith(_ADMIN)
    secret = rest[: -len(_ADMIN)] if admin else rest
    if len(secret) < MIN_SECRET_LENGTH or any(c.isspace() for c in secret):
        raise ValueError(
            f"The secret of key {name!r} ({where}) must be at least {MIN_SECRET_LENGTH} "
            "characters without spaces (make one with 'dexlab keys create' or "
            "'openssl rand -base64 32')."
        )
    return DeclaredKey(name, secret, admin)


def parse_api_keys(value: str) -> list[DeclaredKey]:
    """The keys ``value`` declares (see the module docstring); ValueError naming the
    first bad entry."""
    keys = [
        _entry(position, text.strip())
        for position, text in enumerate(value.split(","), start=1)
        if text.strip()
    ]
    names: set[str] = set()
    secrets: set[str] = set()
    for key in keys:
        if key.name in names:
            raise ValueError(f"DEXLAB_API_KEYS names the key {key.name!r} twice.")
        if key.secret in secrets:
            raise ValueError(f"DEXLAB_API_KEYS gives key {key.name!r} another key's secret.")
        names.add(key.name)
        secrets.add(key.secret)
    return keys


def seed_keys(store: KeysPort, value: str) -> None:
    """Make the keys ``value`` declares in ``store``, logging each outcome by name."""
    for key in parse_api_keys(value):
        outcome = store.seed_key(key.name, hash_secret(key.secret), key.admin)
        role = "admin key" if key.admin else "key"
        log.info("DEXLAB_API_KEYS: %s %r %s", role, key.name, outcome)
