"""Bounded, jittered retries of store calls over transient faults.

A store call that meets a transient fault (SQLite busy or locked, a PostgreSQL
connection lost, a serialization failure or deadlock) is run again from the start
after a jittered, growing pause, for at most the store's ``retry_s`` in all; then it
raises :class:`worker.errors.StoreUnavailable` with a ``retry_after_s`` hint.  Faults
that waiting cannot cure are named at once: :class:`worker.errors.StorageFull` (disk
full) and :class:`worker.errors.StorageError` (corrupt, read-only, I/O error).

A call that gives up after the whole window declares an :class:`Outage` on its store:
the calls still waiting give up at their next pause, and every later call makes one
try and gives up at once, until a call succeeds.  So an outage costs the callers who
meet it at most one window together, not one window each after the other, and a
process holds no thread in a retry loop for a store it knows is down.

What these exceptions say is safe to show a client: never where the store is (a file
path, a host and port, a database) nor the driver's message, which may say it.
Those go to this module's log, with the call's name.

Every public store method is wrapped, so a call is one unit of retry: each write is
one transaction, rolled back on failure, and written so that running it again after
an ambiguous commit is harmless (job IDs are chosen before the first try; completion
recognises its own earlier commit).  :func:`single_try` wraps a probe (readiness)
that must answer at once: one try, the same faults.
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

__all__ = ["Fault", "FaultClassifier", "Outage", "retrying", "single_try"]

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


class Outage:
    """Whether a store is known to be down in this process: declared by a call that
    gave up after its whole retry window, ended by the next call that succeeds.

    Plain attribute reads and writes (atomic under the GIL): no lock, so a process
    forked while a thread declares one inherits no held lock."""

    def __init__(self) -> None:
        #: When (``time.monotonic()``) the outage was declared; None: none is known.
        self.since: float | None = None

    def declare(self) -> None:
        self.since = time.monotonic()

    def end(self) -> bool:
        """Forget the outage; whether there was one."""
        known, self.since = self.since is not None, None
        return known

    def declared_after(self, moment: float) -> bool:
        """Whether an outage was declared at or after ``moment`` (monotonic)."""
        since = self.since
        return since is not None and since >= moment


class FaultClassifier(Protocol):
    """What a store must offer to be retried."""

    retry_s: float
    outage: Outage

    @property
    def location(self) -> str: ...

    def classify(self, exc: BaseException) -> Fault:
        """What ``exc`` means."""

    def after_fault(self, fault: Fault) -> None:
        """Reset what a fault may have broken (e.g. drop a dead connection)."""


def _incurable(store: FaultClassifier, name: str, fault: Fault, exc: Exception) -> StoreUnavailable:
    """The exception of a fault that waiting cannot cure (its cause is logged here)."""
    log.error("store %s: %s: %s", store.location, name, exc)
    if fault is Fault.FULL:
        return StorageFull("The job store is out of space: nothing more can be stored.")
    return StorageError(
        "The job store cannot be used: it cannot read or write its files (corrupt, "
        "read-only or an I/O error)."
    )


def _answered(store: FaultClassifier) -> None:
    if store.outage.end():
        log.info("store %s answers again", store.location)


def _unavailable(store: FaultClassifier, tries: int) -> StoreUnavailable:
    return StoreUnavailable(
        f"The job store is busy or unreachable; gave up after {tries} "
        f"{'try' if tries == 1 else 'tries'}.",
        retry_after_s=max(1.0, store.retry_s),
    )


def retrying(method: F) -> F:
    """Wrap a store method in the bounded retry described in the module docstring."""

    @functools.wraps(method)
    def wrapper(self: FaultClassifier, *args: Any, **kwargs: Any) -> Any:
        started = time.monotonic()
        deadline = started + self.retry_s
        # A store known to be down gets one try: its outage was waited out once.
        patient = self.outage.since is None
        pause = _FIRST_PAUSE_S
        tries = 0
        while True:
            tries += 1
            try:
                result = method(self, *args, **kwargs)
            except StoreUnavailable:
                raise
            except Exception as exc:
                fault = self.classify(exc)
                if fault is Fault.OTHER:
                    raise
                self.after_fault(fault)
                if fault is not Fault.TRANSIENT:
                    raise _incurable(self, method.__name__, fault, exc) from exc
                left = deadline - time.monotonic()
                if patient and left <= 0:
                    self.outage.declare()
                    log.warning(
                        "store %s: %s gave up after %d tries: %s; until a call succeeds, "
                        "calls try once",
                        self.location,
                        method.__name__,
                        tries,
                        exc,
                    )
                    raise _unavailable(self, tries) from exc
                if not patient or self.outage.declared_after(started):
                    log.debug("store %s: %s: %s (an outage)", self.location, method.__name__, exc)
                    raise _unavailable(self, tries) from exc
                time.sleep(min(left, random.uniform(0.5, 1.0) * pause))
                pause = min(2 * pause, _MAX_PAUSE_S)
            else:
                _answered(self)
                return result

    return cast(F, wrapper)


def single_try(method: F) -> F:
    """Wrap a store probe: one try, faults named as :func:`retrying` names them (a
    success ends an outage; a failure declares none: one try proves nothing)."""

    @functools.wraps(method)
    def wrapper(self: FaultClassifier, *args: Any, **kwargs: Any) -> Any:
        try:
            result = method(self, *args, **kwargs)
        except StoreUnavailable:
            raise
        except Exception as exc:
            fault = self.classify(exc)
            if fault is Fault.OTHER:
                raise
            self.after_fault(fault)
            if fault is not Fault.TRANSIENT:
                raise _incurable(self, method.__name__, fault, exc) from exc
            log.info("store %s: %s: %s", self.location, method.__name__, exc)
            raise _unavailable(self, 1) from exc
        _answered(self)
        return result

    return cast(F, wrapper)
