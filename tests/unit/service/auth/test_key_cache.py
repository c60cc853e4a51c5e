"""The key cache: what the store holds, never more than max_age_s old; last use
written back at most once per interval."""

from __future__ import annotations

import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from service.auth.authenticator import Authenticator
from service.auth.key_cache import KeyCache
from service.auth.sessions import SessionSigner
from worker.store import open_store
from worker.store.api_keys import hash_secret
from worker.store.base import JobStore


@pytest.fixture
def anyio_backend() -> str:
    return "asyncio"


class Clock:
    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


@pytest.fixture
def store(tmp_path: Path) -> Iterator[JobStore]:
    s = open_store(f"sqlite:///{tmp_path / 'jobs.db'}")
    yield s
    s.close()


def test_no_key_means_not_configured(store: JobStore) -> None:
    table = KeyCache(store).table()
    assert not table.configured and not table.by_hash


def test_a_new_key_is_seen_once_the_table_is_older_than_max_age(store: JobStore) -> None:
    clock = Clock()
    cache = KeyCache(store, max_age_s=1.0, clock=clock)
    assert not cache.table().configured
    store.create_key("alice", hash_secret("alice-secret-123456"), admin=False)
    clock.now += 0.99
    assert cache.fresh() is not None and not cache.table().configured  # still the old read
    clock.now += 0.01
    assert cache.fresh() is None
    table = cache.table()
    key = table.by_secret("alice-secret-123456")
    assert key is not None and key.name == "alice" and table.by_id[key.key_id] == key
    assert table.by_secret("alice-secret-12345") is None


def test_a_revoked_key_drops_out_but_the_service_stays_closed(store: JobStore) -> None:
    clock = Clock()
    cache = KeyCache(store, clock=clock)
    store.create_key("alice", hash_secret("alice-secret-123456"), admin=True)
    assert cache.table().by_secret("alice-secret-123456") is not None
    store.revoke_key("alice")
    clock.now += 1.0
    table = cache.table()
    assert table.by_secret("alice-secret-123456") is None and not table.by_id
    assert table.configured


def test_last_use_is_written_at_most_once_per_interval(store: JobStore) -> None:
    clock = Clock()
    cache = KeyCache(store, use_interval_s=60.0, clock=clock)
    store.create_key("alice", hash_secret("alice-secret-123456"), admin=False)
    key = cache.table().by_secret("alice-secret-123456")
    assert key is not None
    cache.note_use(key)
    clock.now += 1.0
    cache.table()
    first = store.api_keys()[0].last_used
    assert first is not None and abs(first - time.time()) < 5
    cache.note_use(key)  # within the interval: not written again
    clock.now += 1.0
    cache.table()
    assert store.api_keys()[0].last_used == first


@pytest.mark.anyio
async def test_an_unknown_secret_is_looked_up_again_in_a_recent_read(store: JobStore) -> None:
    clock = Clock()
    cache = KeyCache(store, max_age_s=1.0, recheck_s=0.1, clock=clock)
    auth = Authenticator(cache, SessionSigner(b"s" * 32, lifetime_s=60))
    assert await auth.live_key("alice-secret-123456") is None
    store.create_key("alice", hash_secret("alice-secret-123456"), admin=False)
    clock.now += 0.06  # read 60 ms ago: wrong keys do not read the store again
    assert await auth.live_key("alice-secret-123456") is None
    clock.now += 0.06  # 120 ms: an unknown key is looked for in a fresh read
    key = await auth.live_key("alice-secret-123456")
    assert key is not None and key.name == "alice"
    assert await auth.live_key("") is None
