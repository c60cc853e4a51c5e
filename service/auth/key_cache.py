"""The API keys as this replica sees them: read from the store at most once a second.

Every replica reads the ``api_keys`` table itself, so a key made or revoked by
``dexlab keys`` (or another replica) counts here within ``max_age_s``.  A request's
key is found by the SHA-256 of what it sent, a dictionary lookup.  A key not found
is looked for once more in a fresh read if the table is older than ``recheck_s``
(0.1 s), so a key made a moment ago works at once, while wrong keys cost at most ten
queries a second.  When a key was last used is written back at most once a minute per key,
with the next read, so authentication adds no write to a request.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from worker.errors import StoreUnavailable
from worker.store.api_keys import hash_secret
from worker.store.base import ApiKey, KeysPort

__all__ = ["KeyCache", "KeyTable"]

log = logging.getLogger("dexlab.service")


@dataclass(frozen=True)
class KeyTable:
    """The keys at one moment: the live ones by secret hash and by ``key_id``, and
    whether any key was ever made (revoked ones count: revoking every key must not
    open the service)."""

    by_hash: Mapping[str, ApiKey] = field(default_factory=dict)
    by_id: Mapping[str, ApiKey] = field(default_factory=dict)
    configured: bool = False

    @classmethod
    def of(cls, keys: list[ApiKey]) -> KeyTable:
        live = [k for k in keys if k.revoked is None]
        return cls(
            by_hash={k.secret_hash: k for k in live},
            by_id={k.key_id: k for k in live},
            configured=bool(keys),
        )

    def by_secret(self, secret: str) -> ApiKey | None:
        """The live key with this secret, if any."""
        return self.by_hash.get(hash_secret(secret))


class KeyCache:
    """The keys of ``store``, at most ``max_age_s`` old (see the module docstring).

    No lock is held while the store is read: reads in different threads run side by
    side, and the newest-started one's table is kept.  (Requests share one read in
    flight: :class:`service.auth.authenticator.Authenticator`.)"""

    def __init__(
        self,
        store: KeysPort,
        max_age_s: float = 1.0,
        use_interval_s: float = 60.0,
        recheck_s: float = 0.1,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self._store = store
        self.max_age_s = max_age_s
        self.use_interval_s = use_interval_s
        self.recheck_s = recheck_s
        self._clock = clock
        self._lock = threading.Lock()  # guards the fields below, never held over I/O
        self._table: KeyTable | None = None
        self._read_at = 0.0
        self._uses: dict[str, float] = {}

    def fresh(self, max_age_s: float | None = None) -> KeyTable | None:
        """The table if it is younger than ``max_age_s`` (default: the cache's), without
        blocking; else None."""
        with self._lock:
            table, read_at = self._table, self._read_at
        limit = self.max_age_s if max_age_s is None else max_age_s
        if table is None or self._clock() - read_at >= limit:
            return None
        return table

    def latest(self) -> KeyTable | None:
        """The last table read, however old (None: never read)."""
        return self._table

    def table(self, max_age_s: float | None = None) -> KeyTable:
        """The table, read again from the store when it is older than ``max_age_s``
        (default: the cache's).  Raises StoreUnavailable."""
        table = self.fresh(max_age_s)
        return table if table is not None else self.read()

    def read(self) -> KeyTable:
        """Read the table from the store now (and write back when keys were last used).
        Raises StoreUnavailable."""
        started = self._clock()
        keys = self._store.api_keys()
        table = KeyTable.of(keys)
        with self._lock:
            if started >= self._read_at or self._table is None:
                self._table, self._read_at = table, started
            uses, self._uses = self._uses, {}
        self._write_uses(keys, uses)
        return table

    def note_use(self, key: ApiKey) -> None:
        """Remember that ``key`` authenticated a request now."""
        with self._lock:
            self._uses[key.key_id] = time.time()

    def _write_uses(self, keys: list[ApiKey], uses: dict[str, float]) -> None:
        if not uses:
            return
        stored = {k.key_id: k.last_used for k in keys}
        due = [
            key_id
            for key_id, when in uses.items()
            if key_id in stored and when - (stored[key_id] or 0.0) >= self.use_interval_s
        ]
        if not due:
            return
        try:
            self._store.record_key_use(due, max(uses[k] for k in due))
        except StoreUnavailable as exc:  # bookkeeping only: the next read tries again
            log.warning("could not record when API keys were last used: %s", exc)
            with self._lock:
                for key_id in due:
                    self._uses.setdefault(key_id, uses[key_id])
