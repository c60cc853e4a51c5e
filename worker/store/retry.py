"""Bounded, jittered retries of store calls over transient faults.

A store call that meets a transient fault (SQLite busy or locked, a PostgreSQL
connection lost, a serialization failure or deadlock) is run again from the start
after a jittered, growing pause, for at most the store's ``retry_s`` in all; then it
raises :class:`worker.errors.StoreUnavailable` with a ``retry_after_s`` hint.  Faults
that waiting cannot cure are named at once: :class:`worker.errors.StorageFull` (disk
full) and :class:`worker.errors.StorageError` (corrupt, read-only, I/O error).

Every public store method is wrapped, so a call is one unit of retry: each write is
one transaction, rolled back on failure, and written so that running it again after
an ambiguous commit is harmless (job IDs are chosen before the first try; completion
recognises its own earlier commit).
"""

from __future__ import annotations

import enum
import functools
import logging
import random
import time
from collections.abc import Callable
from typing import Any, Protocol, TypeVar, cast

from worker.errors import StorageError, StorageFull, StoreUnavailable

__all__ = ["Fault", "FaultClassifier", "retrying"]

log = logging.getLogger("dexlab.store")

F = TypeVar("F", bound=Callable[..., Any])

#: First pause and the largest single pause between tries (seconds).
_FIRST_PAUSE_S = 0.02
_MAX_PAUSE_S = 0.5


class Fault(enum.Enum):
    """What a store exception means for the caller."""

    #: Try again: busy, locked, connection lost, serialization failure.
    TRANSIENT = "transient"
    #: The disk is full.
    FULL = "full"
    #: The store's files cannot be used: corrupt, read-only, unreadable.
    BROKEN = "broken"
    #: Not a store fault (a bug, or an error the caller handles).
    OTHER = "other"


class FaultClassifier(Protocol):
    """What a store must offer to be retried."""

    retry_s: float

    @property
    def location(self) -> str: ...

    def classify(self, exc: BaseException) -> Fault:
        """What ``exc`` means."""

    def after_fault(self, fault: Fault) -> None:
        """Reset what a fault may have broken (e.g. drop a dead connection)."""


def retrying(method: F) -> F:
    """Wrap a store method in the bounded retry described in the module docstring."""

    @functools.wraps(method)
    def wrapper(self: FaultClassifier, *args: Any, **kwargs: Any) -> Any:
        deadline = time.monotonic() + self.retry_s
        pause = _FIRST_PAUSE_S
        tries = 0
        while True:
            tries += 1
            try:
                return method(self, *args, **kwargs)
            except StoreUnavailable:
                raise
            except Exception as exc:
                fault = self.classify(exc)
                if fault is Fault.OTHER:
                    raise
                self.after_fault(fault)
                if fault is Fault.FULL:
                    raise StorageFull(
                        f"The job store at {self.location} is out of space: {exc}"
                    ) from exc
                if fault is Fault.BROKEN:
                    raise StorageError(
                        f"The job store at {self.location} cannot be used: {exc}"
                    ) from exc
                left = deadline - time.monotonic()
                if left <= 0:
                    log.warning(
                        "store %s: %s gave up after %d tries: %s",
                        self.location,
                        method.__name__,
                        tries,
                        exc,
                    )
                    raise StoreUnavailable(
                        f"The job store at {self.location} is busy or unreachable "
                        f"({exc}); gave up after {tries} tries.",
                        retry_after_s=max(1.0, self.retry_s),
                    ) from exc
                time.sleep(min(left, random.uniform(0.5, 1.0) * pause))
                pause = min(2 * pause, _MAX_PAUSE_S)

    return cast(F, wrapper)
