"""Wake-up hints of the local pool on real Unix sockets (and, for the one-process-per-
hint wake, real spawned processes)."""

from __future__ import annotations

import multiprocessing
import os
import socket
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

import pytest

from worker.dispatch import LocalDispatch, make_dispatcher
from worker.dispatch.wake_ups import (
    MAX_SOCKET_PATH,
    PoolWakeUps,
    WakeUpListener,
    WakeUpSender,
    wake_up_dir,
)
from worker.registry import default_registry
from worker.settings import WorkerSettings
from worker.store import open_store

pytestmark = pytest.mark.skipif(not hasattr(socket, "AF_UNIX"), reason="no Unix sockets")


@pytest.fixture
def pool(tmp_path: Path) -> Any:
    wake_ups = PoolWakeUps.bind(tmp_path / "jobs.db-wake")
    assert wake_ups is not None
    yield wake_ups
    wake_ups.close()


def test_the_directory_is_beside_the_sqlite_file_whatever_its_spelling(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    with tempfile.TemporaryDirectory() as short:  # pytest's own may be too long a path
        tmp_path = Path(short)
        check_beside(tmp_path, monkeypatch)


def check_beside(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "real").mkdir()
    (tmp_path / "link").symlink_to(tmp_path / "real")
    monkeypatch.chdir(tmp_path)
    expected = (tmp_path / "real" / "jobs.db-wake").resolve()
    assert wake_up_dir(f"sqlite:///{tmp_path / 'real' / 'jobs.db'}") == expected
    assert wake_up_dir(f"sqlite:///{tmp_path / 'link' / 'jobs.db'}") == expected
    assert wake_up_dir("sqlite:///real/jobs.db") == expected
    settings = WorkerSettings(data_dir=tmp_path / "link")
    assert wake_up_dir(settings.resolved_store_url()) == expected


def test_a_path_too_long_for_a_socket_and_another_store_use_the_temporary_directory(
    tmp_path: Path,
) -> None:
    deep = tmp_path / ("d" * 60) / ("e" * 60)
    long_url = f"sqlite:///{deep / 'jobs.db'}"
    chosen = wake_up_dir(long_url)
    assert chosen is not None and chosen.parent == Path(tempfile.gettempdir())
    assert chosen == wake_up_dir(long_url)  # every process finds the same one
    assert chosen != wake_up_dir(f"sqlite:///{deep / 'other.db'}")
    postgres = wake_up_dir("postgresql://u:p@localhost/dexlab")
    assert postgres is not None and postgres.parent == Path(tempfile.gettempdir())
    assert postgres.name.startswith("dexlab-wake-") and "p@" not in postgres.name
    assert len(os.fsencode(chosen)) + 21 <= MAX_SOCKET_PATH


def test_a_hint_reaches_the_pool_with_its_count_and_the_rest_is_passed_on(pool: Any) -> None:
    sender = WakeUpSender(pool.path.parent)
    first, second = WakeUpListener(pool.sock), WakeUpListener(pool.sock)
    try:
        assert sender.wake(5) == 1
        start = time.monotonic()
        first.wait(5.0)
        assert first.held == 5 and time.monotonic() - start < 1.0
        first.pass_on()  # it claimed one job: four are left for the next process
        assert first.held == 0
        second.wait(5.0)
        assert second.held == 4
        second.drop()
        assert second.held == 0 and not second.take()
    finally:
        sender.close()
        first.close()
        second.close()


def test_take_gathers_every_waiting_hint_without_waiting(pool: Any) -> None:
    sender = WakeUpSender(pool.path.parent)
    listener = WakeUpListener(pool.sock)
    try:
        assert not listener.take()
        sender.wake(1)
        sender.wake_for(["a", "b"])
        time.sleep(0.05)
        assert listener.take() and listener.held == 3
        pool.sock.sendto(b"garbage", os.fsencode(pool.path))
        assert listener.take() and listener.held == 4  # a malformed hint counts one
    finally:
        sender.close()
        listener.close()


def test_a_wait_without_hints_lasts_its_timeout_and_an_interrupt_cuts_it_short(
    pool: Any,
) -> None:
    listener = WakeUpListener(pool.sock)
    try:
        start = time.monotonic()
        listener.wait(0.3)
        assert 0.29 <= time.monotonic() - start < 2.0 and listener.held == 0
        threading.Timer(0.2, listener.interrupt).start()
        start = time.monotonic()
        listener.wait(30.0)
        assert time.monotonic() - start < 5.0 and listener.held == 0
    finally:
        listener.close()


def test_sockets_of_pools_that_are_gone_are_removed_and_skipped(tmp_path: Path) -> None:
    directory = tmp_path / "jobs.db-wake"
    gone = PoolWakeUps.bind(directory)
    assert gone is not None
    gone.sock.close()  # killed: its file stays behind
    sender = WakeUpSender(directory)
    try:
        assert gone.path.exists() and sender.wake(1) == 0
        alive = PoolWakeUps.bind(directory)
        assert alive is not None
        assert not gone.path.exists() and alive.path.exists()
        assert sender.wake(1) == 1
        alive.close()
        assert not alive.path.exists() and sender.wake(1) == 0
    finally:
        sender.close()


def test_a_sender_never_raises_without_a_pool_or_with_a_full_queue(
    tmp_path: Path, pool: Any
) -> None:
    nowhere = WakeUpSender(tmp_path / "missing")
    sender = WakeUpSender(pool.path.parent)
    try:
        assert nowhere.wake(1) == 0
        reached = [sender.wake(1) for _ in range(5000)]  # nobody reads them
        assert reached[0] == 1 and reached[-1] == 0  # the queue filled up; no error
        assert sender.wake(0) == 0
    finally:
        nowhere.close()
        sender.close()


def test_a_temporary_directory_not_made_by_this_user_is_not_used(tmp_path: Path) -> None:
    directory = wake_up_dir(f"postgresql://localhost/test-{os.getpid()}-{time.time_ns()}")
    assert directory is not None and not directory.exists()
    directory.symlink_to(tmp_path)
    try:
        assert PoolWakeUps.bind(directory) is None
        assert not list(tmp_path.iterdir())
    finally:
        directory.unlink()
    made = PoolWakeUps.bind(directory)
    assert made is not None
    try:
        assert directory.stat().st_mode & 0o777 == 0o700
    finally:
        made.close()
        directory.rmdir()


def test_local_dispatch_wakes_the_pools_of_its_store(tmp_path: Path) -> None:
    settings = WorkerSettings(data_dir=tmp_path)
    directory = wake_up_dir(settings.resolved_store_url())
    wake_ups = PoolWakeUps.bind(directory)
    assert wake_ups is not None
    store = open_store(settings.resolved_store_url())
    dispatcher = make_dispatcher(settings, store, default_registry())
    listener = WakeUpListener(wake_ups.sock)
    try:
        assert isinstance(dispatcher, LocalDispatch)
        dispatcher.dispatch("some-job", 30.0)
        listener.wait(5.0)
        assert listener.held == 1
    finally:
        dispatcher.close()
        listener.close()
        wake_ups.close()
        store.close()


def _sleep_on_hints(sock: socket.socket, ready: Any, results: Any) -> None:
    listener = WakeUpListener(sock)
    ready.put(os.getpid())
    listener.wait(3.0)
    results.put((os.getpid(), listener.held, time.monotonic()))


@pytest.mark.skipif(sys.platform != "linux", reason="EPOLLEXCLUSIVE is Linux's")
def test_one_hint_wakes_one_of_the_idle_processes(pool: Any) -> None:
    ctx = multiprocessing.get_context("spawn")
    ready, results = ctx.Queue(), ctx.Queue()
    procs = [ctx.Process(target=_sleep_on_hints, args=(pool.sock, ready, results)) for _ in "abc"]
    for proc in procs:
        proc.start()
    sender = WakeUpSender(pool.path.parent)
    try:
        for _ in procs:
            ready.get(timeout=60)
        time.sleep(0.3)  # all three asleep on the socket
        sent = time.monotonic()
        sender.wake(1)
        woken = [results.get(timeout=30) for _ in procs]
    finally:
        sender.close()
        for proc in procs:
            proc.join(timeout=10)
    holders = [w for w in woken if w[1]]
    assert len(holders) == 1 and holders[0][1] == 1, woken
    assert holders[0][2] - sent < 1.0, woken  # the others slept until their timeout
