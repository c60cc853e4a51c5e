"""When the client tries a request again, and how long it pauses first.

A request is tried again after a connection error (refused, reset, a timeout, a dropped
response) and after ``502``/``503``/``504`` (a store that is down for a moment, a proxy
between replicas), at most :attr:`RetryPolicy.attempts` times in all.  That is safe for
every request the client sends: reads and dismissals are idempotent, and a submission
carries an ``Idempotency-Key`` (the same on every try), so a retried submission whose
first try did reach the service gets the same job back, never a second one.

Pauses grow exponentially from :attr:`~RetryPolicy.backoff_s` up to
:attr:`~RetryPolicy.max_backoff_s`, drawn at random in the upper half of that (so many
clients do not retry in step); a ``Retry-After`` from the service is honoured up to
:attr:`~RetryPolicy.max_retry_after_s`.  A failed job's problem (it names a ``jobID``)
is an answer, never retried, even when its status is ``503`` (a storage failure).
"""

from __future__ import annotations

import random
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

__all__ = ["RETRIED_STATUSES", "RetryPolicy"]

#: Answers that mean "not now": tried again.
RETRIED_STATUSES = frozenset({502, 503, 504})


@dataclass(frozen=True)
class RetryPolicy:
    """Bounded retries with exponential back-off (see the module docstring).

    ``attempts`` counts every try (1: never retry); pauses in seconds.
    """

    attempts: int = 5
    backoff_s: float = 0.25
    max_backoff_s: float = 8.0
    max_retry_after_s: float = 30.0
    jitter: bool = True

    def __post_init__(self) -> None:
        if self.attempts < 1:
            raise ValueError(f"RetryPolicy.attempts must be at least 1. Got {self.attempts}.")
        for name in ("backoff_s", "max_backoff_s", "max_retry_after_s"):
            value = getattr(self, name)
            if not value >= 0:  # also refuses NaN
                raise ValueError(f"RetryPolicy.{name} must be >= 0 seconds. Got {value!r}.")

    def retries_answer(self, status: int, problem: Mapping[str, Any] | None) -> bool:
        """Whether an answer with this status (and problem document) is tried again."""
        return status in RETRIED_STATUSES and "jobID" not in (problem or {})

    def backoff(self, attempt: int, rng: random.Random | None = None) -> float:
        """The pause after try number ``attempt`` (1, 2, ...) failed, without a hint."""
        delay = min(self.max_backoff_s, self.backoff_s * 2.0 ** (attempt - 1))
        if self.jitter:
            delay = (rng or random).uniform(delay / 2, delay)
        return delay

    def pause(
        self,
        attempt: int,
        retry_after: float | None = None,
        rng: random.Random | None = None,
    ) -> float | None:
        """The pause before the next try after try ``attempt`` failed in a retried way,
        or None when the attempts are spent.  ``retry_after``: the service's hint."""
        if attempt >= self.attempts:
            return None
        delay = self.backoff(attempt, rng)
        if retry_after is not None:
            delay = max(delay, min(retry_after, self.max_retry_after_s))
        return delay
