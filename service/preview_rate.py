"""The submit rate limit, applied to previews: a token bucket per API key.

A preview makes no job, so the store's bucket (:mod:`worker.store.quotas`, taken in the
transaction that inserts a job) never sees it; this one, kept by the API process,
holds the same ``DEXLAB_SUBMIT_RATE_PER_MIN`` tokens per key and refills as fast.  The
anonymous owner of a service without keys (its operator) is not limited, as at
submission.  Built by ``create_app`` and kept on ``app.state.preview_rate``.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

from worker.errors import RateLimited

__all__ = ["PreviewRate"]


class PreviewRate:
    """Per-owner token buckets of ``per_min`` tokens (0: no limit)."""

    def __init__(self, per_min: int, clock: Callable[[], float] = time.monotonic) -> None:
        self._per_min = per_min
        self._clock = clock
        self._lock = threading.Lock()
        self._buckets: dict[str, tuple[float, float]] = {}  # owner -> (tokens, at)

    def take(self, owner: str) -> None:
        """Take one token of ``owner``'s, or raise :class:`RateLimited` saying when."""
        per_min = self._per_min
        if not per_min or owner == "":
            return
        with self._lock:
            now = self._clock()
            tokens, at = self._buckets.get(owner, (float(per_min), now))
            tokens = min(float(per_min), tokens + max(0.0, now - at) * per_min / 60.0)
            if tokens < 1.0:
                wait = (1.0 - tokens) * 60.0 / per_min
                self._buckets[owner] = (tokens, now)
                raise RateLimited(
                    f"This API key has used its {per_min} submissions a minute "
                    f"(DEXLAB_SUBMIT_RATE_PER_MIN, previews included); the next is allowed "
                    f"in {wait:.1f} s.",
                    limit="DEXLAB_SUBMIT_RATE_PER_MIN",
                    allowed=per_min,
                    retry_after_s=wait,
                )
            self._buckets[owner] = (tokens - 1.0, now)
