"""The key cache: what the store holds, never more than max_age_s old; last use
written back at most once per interval; with the store down, requests share one read
and its failure, and public routes do not wait for it (issue 26, finding 5)."""

from __future__ import annotations

import asyncio
import time
from collections.abc import Iterator, Sequence
from pathlib import Path

import pytest
from starlette.datastructures import Headers

from service.auth.authenticator import Authenticator
from service.auth.errors import Unauthenticated
from service.auth.key_cache import KeyCache
from service.auth.sessions import SessionSigner
from worker.errors import StoreUnavailable
from worker.store import open_store
from worker.store.api_keys import hash_secret
from worker.store.base import ApiKey, JobStore


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


class FlakyKeys:
    """The key reads of ``store``, or, while ``down``, a read that fails after
    ``delay_s`` (a store retrying, then giving up); ``reads`` counts them."""

    def __init__(self, store: JobStore, delay_s: float) -> None:
        self.store = store
        self.delay_s = delay_s
        self.down = False
        self.reads = 0

    def api_keys(self) -> list[ApiKey]:
        self.reads += 1
        if self.down:
            time.sleep(self.delay_s)
            raise StoreUnavailable("The job store is busy or unreachable.", retry_after_s=5.0)
        return self.store.api_keys()

    def record_key_use(self, key_ids: Sequence[str], when: float) -> None:
        self.store.record_key_use(key_ids, when)


def flaky_auth(store: JobStore, delay_s: float, clock: Clock) -> tuple[Authenticator, FlakyKeys]:
    keys = FlakyKeys(store, delay_s)
    cache = KeyCache(keys, clock=clock)  # type: ignore[arg-type]
    return Authenticator(cache, SessionSigner(b"s" * 32, lifetime_s=60)), keys


@pytest.mark.anyio
async def test_requests_share_one_read_of_the_keys_and_its_failure(store: JobStore) -> None:
    """With the store down, 20 requests that need the keys wait for one read together
    and all get its StoreUnavailable when it gives up: not one read after another."""
    clock = Clock()
    auth, keys = flaky_auth(store, 0.3, clock)
    keys.down = True
    began = time.monotonic()
    outcomes = await asyncio.gather(*(auth.table() for _ in range(20)), return_exceptions=True)
    took = time.monotonic() - began
    assert all(isinstance(o, StoreUnavailable) for o in outcomes), outcomes
    assert keys.reads == 1 and took < 0.6, (keys.reads, took)
    keys.down = False  # the next request reads again, and the table is back
    assert not (await auth.table()).configured and keys.reads == 2


@pytest.mark.anyio
async def test_public_routes_identify_from_the_last_table_without_waiting(
    store: JobStore,
) -> None:
    """identify_now (the routes that answer anyone) answers from the table read last,
    however old, while the store is down, and starts a read for the next requests;
    identify (every other route) waits for that read and gets its 503."""
    store.create_key("alice", hash_secret("alice-secret-123456"), admin=False)
    clock = Clock()
    auth, keys = flaky_auth(store, 0.5, clock)
    assert auth.keys.table().configured and keys.reads == 1
    keys.down = True
    clock.now += 5.0  # the table is stale
    headers = Headers({"authorization": "Bearer alice-secret-123456"})
    began = time.monotonic()
    identity = auth.identify_now(headers)
    assert time.monotonic() - began < 0.1
    assert identity.name == "alice" and identity.via == "bearer"
    with pytest.raises(Unauthenticated):
        auth.identify_now(Headers({"authorization": "Bearer wrong-secret-1234567"}))
    with pytest.raises(StoreUnavailable):
        await auth.identify(headers)
    assert keys.reads == 2  # the read identify_now started is the one identify waited for
    await auth.aclose()
