"""API keys in the job store: names, the SHA-256 of each secret, admin flags, revocation.

A key's secret is shown once, when it is made, and never stored: the store keeps
:func:`hash_secret` of it.  One SHA-256 (no salt, no slow KDF) is enough because the
secrets are not passwords: :func:`new_secret` draws 256 random bits, which no offline
guessing can reach, so a slow hash (bcrypt, argon2: a defence for low-entropy
passwords) would only slow every request, while an unsalted hash lets a presented
secret be found by one lookup.  Secrets an operator chooses (``DEXLAB_API_KEYS``) must
be at least :data:`MIN_SECRET_LENGTH` characters.

Every API replica reads the keys from the store (:mod:`service.auth.key_cache`), so a
key made or revoked by ``dexlab keys`` counts everywhere within a second.
"""

from __future__ import annotations

import hashlib
import re
import secrets
import time
import uuid
from collections.abc import Callable, Sequence
from typing import Any

from worker.store.connector import Conn, SqlConnector
from worker.store.records import ApiKey
from worker.store.retry import retrying

__all__ = [
    "MIN_SECRET_LENGTH",
    "ApiKeys",
    "check_key_name",
    "hash_secret",
    "new_secret",
]


#: Secrets dexlab makes start with this, so a leaked one is easy to recognise.
SECRET_PREFIX = "dxk_"
#: The shortest secret an operator may choose.
MIN_SECRET_LENGTH = 16
_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9._@-]{0,63}")


def new_secret() -> str:
    """A new key secret: ``dxk_`` and 256 random bits, URL-safe base64 (47 chars)."""
    return SECRET_PREFIX + secrets.token_urlsafe(32)


def hash_secret(secret: str) -> str:
    """The SHA-256 of a secret (hex), as the store keeps it (why: module docstring)."""
    return hashlib.sha256(secret.encode("utf-8")).hexdigest()


def check_key_name(name: str) -> str:
    """``name`` if it can name a key, else ValueError saying why."""
    if not _NAME.fullmatch(name):
        raise ValueError(
            "The key name must be 1-64 letters, digits, '.', '_', '@' or '-', starting "
            f"with a letter or digit. Got {name!r} instead."
        )
    return name


def _key(row: Any) -> ApiKey:
    return ApiKey(
        name=row["name"],
        key_id=row["key_id"],
        secret_hash=row["secret_hash"],
        admin=bool(row["admin"]),
        created=row["created"],
        revoked=row["revoked"],
        last_used=row["last_used"],
    )


class ApiKeys(SqlConnector):
    """The key half of :class:`worker.store.sql.SqlJobStore`."""

    def _insert_key(self, conn: Conn, name: str, secret_hash: str, admin: bool) -> bool:
        """Insert the key unless its name is taken; whether it was inserted."""
        cur = self._exec(
            conn,
            "INSERT INTO api_keys (name, key_id, secret_hash, admin, created) "
            "VALUES (?, ?, ?, ?, ?) ON CONFLICT (name) DO NOTHING",
            (name, uuid.uuid4().hex, secret_hash, int(admin), time.time()),
        )
        return bool(cur.rowcount == 1)

    def _key_row(self, conn: Conn, name: str, lock: bool = False) -> Any:
        suffix = self.lock_clause if lock else ""
        return self._one(conn, f"SELECT * FROM api_keys WHERE name = ?{suffix}", (name,))

    @retrying
    def create_key(self, name: str, secret_hash: str, admin: bool) -> ApiKey | None:
        with self._write() as conn:
            self._insert_key(conn, check_key_name(name), secret_hash, admin)
            row = self._key_row(conn, name)
        if row is None or row["secret_hash"] != secret_hash:
            return None
        return _key(row)

    @retrying
    def seed_key(self, name: str, secret_hash: str, admin: bool) -> str:
        with self._write() as conn:
            if self._insert_key(conn, check_key_name(name), secret_hash, admin):
                return "created"
            row = self._key_row(conn, name, lock=True)
            if row["secret_hash"] != secret_hash:
                # The old secret's sessions name the old key_id: they end here.
                self._exec(
                    conn,
                    "UPDATE api_keys SET secret_hash = ?, key_id = ?, admin = ?, "
                    "revoked = NULL WHERE name = ?",
                    (secret_hash, uuid.uuid4().hex, int(admin), name),
                )
                return "replaced"
            if bool(row["admin"]) != admin:
                self._exec(conn, "UPDATE api_keys SET admin = ? WHERE name = ?", (int(admin), name))
            return "unchanged"

    @retrying
    def revoke_key(self, name: str) -> ApiKey | None:
        with self._write() as conn:
            self._exec(
                conn,
                "UPDATE api_keys SET revoked = ? WHERE name = ? AND revoked IS NULL",
                (time.time(), name),
            )
            row = self._key_row(conn, name)
        return None if row is None else _key(row)

    @retrying
    def api_keys(self) -> list[ApiKey]:
        rows = self._all(self._conn(), "SELECT * FROM api_keys ORDER BY created, name")
        return [_key(r) for r in rows]

    @retrying
    def record_key_use(self, key_ids: Sequence[str], when: float) -> None:
        if not key_ids:
            return
        marks = ", ".join("?" for _ in key_ids)
        with self._write() as conn:
            self._exec(
                conn,
                f"UPDATE api_keys SET last_used = ? WHERE key_id IN ({marks})",
                (when, *key_ids),
            )

    @retrying
    def shared_secret(self, name: str, generate: Callable[[], str]) -> str:
        with self._write() as conn:
            self._exec(
                conn,
                "INSERT INTO service_secrets (name, value) VALUES (?, ?) "
                "ON CONFLICT (name) DO NOTHING",
                (name, generate()),
            )
            row = self._one(conn, "SELECT value FROM service_secrets WHERE name = ?", (name,))
        return str(row["value"])
