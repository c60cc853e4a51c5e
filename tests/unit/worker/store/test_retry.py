"""The retry layer (:mod:`worker.store.retry`) on a fake store whose faults the test
chooses: the window, the outage it declares, the single try of a probe, and what the
exceptions say (never where the store is)."""

from __future__ import annotations

import logging
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import pytest

from worker.errors import StorageError, StorageFull, StoreUnavailable
from worker.store.retry import Fault, Outage, retrying, single_try

#: Where the fake store is, and what its driver says: neither may reach a client.
LOCATION = "db.internal:5432/jobs"
DRIVER_TEXT = 'connection to server at "10.0.0.7", port 5432 failed: /var/lib/dexlab/jobs.db'


class DriverError(Exception):
    """What a database driver raises; :attr:`fault` says what it means."""

    def __init__(self, fault: Fault) -> None:
        super().__init__(DRIVER_TEXT)
        self.fault = fault


class FakeStore:
    """A store whose calls fail with ``self.fault`` (None: they succeed), counting tries."""

    def __init__(self, retry_s: float) -> None:
        self.retry_s = retry_s
        self.outage = Outage()
        self.fault: Fault | None = Fault.TRANSIENT
        self.tries = 0
        self._lock = threading.Lock()

    @property
    def location(self) -> str:
        return LOCATION

    def classify(self, exc: BaseException) -> Fault:
        return exc.fault if isinstance(exc, DriverError) else Fault.OTHER

    def after_fault(self, fault: Fault) -> None:
        pass

    def _call(self) -> str:
        with self._lock:
            self.tries += 1
        if self.fault is not None:
            raise DriverError(self.fault)
        return "answer"

    @retrying
    def read(self) -> str:
        return self._call()

    @single_try
    def probe(self) -> str:
        return self._call()


def timed(call: object) -> tuple[BaseException | None, float]:
    began = time.monotonic()
    try:
        call()  # type: ignore[operator]
    except Exception as exc:
        return exc, time.monotonic() - began
    return None, time.monotonic() - began


def test_a_call_retries_for_its_window_then_declares_an_outage(
    caplog: pytest.LogCaptureFixture,
) -> None:
    store = FakeStore(retry_s=0.5)
    caplog.set_level(logging.WARNING, logger="dexlab.store")
    exc, took = timed(store.read)
    assert isinstance(exc, StoreUnavailable) and 0.5 <= took < 1.2, (exc, took)
    assert store.tries > 3 and store.outage.since is not None
    assert exc.extra["retry_after_s"] >= 1
    # The client's detail says what happened, not where: that is in the log.
    assert LOCATION not in exc.detail and "10.0.0.7" not in exc.detail
    assert "jobs.db" not in exc.detail and "busy or unreachable" in exc.detail
    assert LOCATION in caplog.text and DRIVER_TEXT in caplog.text


def test_during_an_outage_a_call_tries_once_until_one_succeeds() -> None:
    store = FakeStore(retry_s=0.5)
    with pytest.raises(StoreUnavailable):
        store.read()
    store.tries = 0
    exc, took = timed(store.read)
    assert isinstance(exc, StoreUnavailable) and took < 0.1 and store.tries == 1
    assert "after 1 try" in exc.detail
    store.fault = None
    assert store.read() == "answer" and store.outage.since is None  # it is over
    store.fault, store.tries = Fault.TRANSIENT, 0
    exc, took = timed(store.read)  # a new fault is waited out again
    assert isinstance(exc, StoreUnavailable) and took >= 0.5 and store.tries > 3


def test_calls_waiting_on_the_store_give_up_with_the_first() -> None:
    """20 calls meet the same outage 0.1 s apart: the first to reach the end of its
    window ends them all (at their next pause, at most 0.5 s on), so none waits a
    window after another's."""
    store = FakeStore(retry_s=2.0)

    def call(delay: float) -> tuple[BaseException | None, float]:
        time.sleep(delay)
        exc, _ = timed(store.read)
        return exc, time.monotonic()

    began = time.monotonic()
    with ThreadPoolExecutor(20) as pool:
        outcomes = list(pool.map(call, [0.1 * i for i in range(20)]))
    assert all(isinstance(exc, StoreUnavailable) for exc, _ in outcomes)
    last = max(end for _, end in outcomes) - began
    # The last started 1.9 s in: alone it would have waited until 3.9 s.
    assert last < 2.0 + 0.5 + 0.5, last


def test_a_probe_tries_once_and_declares_nothing() -> None:
    store = FakeStore(retry_s=5.0)
    exc, took = timed(store.probe)
    assert isinstance(exc, StoreUnavailable) and took < 0.1 and store.tries == 1
    assert store.outage.since is None
    assert LOCATION not in exc.detail and DRIVER_TEXT not in exc.detail
    store.outage.declare()
    store.fault = None
    assert store.probe() == "answer" and store.outage.since is None  # a success ends it


@pytest.mark.parametrize(
    ("fault", "kind", "words"),
    [(Fault.FULL, StorageFull, "out of space"), (Fault.BROKEN, StorageError, "cannot be used")],
)
def test_incurable_faults_are_named_at_once_without_the_location(
    fault: Fault, kind: type[StoreUnavailable], words: str, caplog: pytest.LogCaptureFixture
) -> None:
    store = FakeStore(retry_s=5.0)
    store.fault = fault
    caplog.set_level(logging.ERROR, logger="dexlab.store")
    for call in (store.read, store.probe):
        exc, took = timed(call)
        assert type(exc) is kind and took < 0.1, exc
        assert words in exc.detail
        assert LOCATION not in exc.detail and "10.0.0.7" not in exc.detail
        assert "jobs.db" not in exc.detail
    assert store.tries == 2
    assert LOCATION in caplog.text and DRIVER_TEXT in caplog.text
