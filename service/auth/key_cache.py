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
from worker.store.base import ApiKey, JobStore

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
    """The keys of ``store``, at most ``max_age_s`` old (see the module docstring)."""

    def __init__(
        self,
        store: JobStore,
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
        self._lock = threading.Lock()
        self._table: KeyTable | None = None
        self._read_at = 0.0
        self._uses: dict[str, float] = {}

    def fresh(self, max_age_s: float | None = None) -> KeyTable | None:
        """The table if it is younger than ``max_age_s`` (default: the cache's), without
        blocking; else None."""
        table = self._table
        limit = self.max_age_s if max_age_s is None else max_age_s
        if table is None or self._clock() - self._read_at >= limit:
            return None
        return table

    def table(self, max_age_s: float | None = None) -> KeyTable:
        """The table, read again from the store when it is older than ``max_age_s``
        (default: the cache's; blocking: one thread reads, the others wait for it).
        Raises StoreUnavailable."""
        with self._lock:
            table = self.fresh(max_age_s)
            if table is not None:
                return table
            started = self._clock()
            keys = self._store.api_keys()
            self._table = table = KeyTable.of(keys)
            self._read_at = started
            self._write_uses(keys)
            return table

    def note_use(self, key: ApiKey) -> None:
        """Remember that ``key`` authenticated a request now."""
        self._uses[key.key_id] = time.time()

    def _write_uses(self, keys: list[ApiKey]) -> None:
        if not self._uses:
            return
        uses, self._uses = self._uses, {}
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
            for key_id in due:
                self._uses.setdefault(key_id, uses[key_id])
