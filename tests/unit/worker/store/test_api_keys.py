"""API keys and job owners in the store, on SQLite and PostgreSQL."""

from __future__ import annotations

import re
import sqlite3
from pathlib import Path

import pytest

from worker.contract import JobStatus
from worker.errors import IdempotencyConflict
from worker.store import open_store
from worker.store.api_keys import check_key_name, hash_secret, new_secret
from worker.store.base import JobStore, NewJob
from worker.store.schema import MIGRATIONS


def _job(owner: str = "", key: str | None = None, x: int = 1) -> NewJob:
    return NewJob(
        "toy",
        {"x": x},
        60.0,
        3,
        idempotency_key=key,
        request_hash=f"h{x}" if key else None,
        owner=owner,
    )


def test_a_secret_is_random_and_stored_only_as_its_sha256() -> None:
    secrets = {new_secret() for _ in range(100)}
    assert len(secrets) == 100
    for secret in secrets:
        assert re.fullmatch(r"dxk_[A-Za-z0-9_-]{43}", secret)
        digest = hash_secret(secret)
        assert re.fullmatch(r"[0-9a-f]{64}", digest) and secret not in digest
    assert hash_secret("abc") == (
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"  # FIPS 180-2
    )


@pytest.mark.parametrize("name", ["", " a", "a b", "-a", "a/b", "x" * 65, "é"])
def test_a_bad_key_name_is_refused(name: str) -> None:
    with pytest.raises(ValueError, match="The key name must be"):
        check_key_name(name)


def test_keys_are_made_listed_and_revoked(store: JobStore) -> None:
    made = store.create_key("alice", hash_secret("a" * 20), admin=True)
    assert made is not None and made.admin and made.revoked is None
    assert store.create_key("alice", hash_secret("b" * 20), admin=False) is None
    store.create_key("bob", hash_secret("b" * 20), admin=False)
    assert [k.name for k in store.api_keys()] == ["alice", "bob"]
    revoked = store.revoke_key("bob")
    assert revoked is not None and revoked.revoked is not None
    assert store.revoke_key("bob") == revoked  # once revoked, stays as it was
    assert store.revoke_key("nobody") is None


def test_seeding_is_idempotent_and_a_new_secret_replaces_the_old(store: JobStore) -> None:
    assert store.seed_key("lab", hash_secret("s" * 20), admin=False) == "created"
    first = store.api_keys()[0]
    assert store.seed_key("lab", hash_secret("s" * 20), admin=False) == "unchanged"
    assert store.api_keys()[0] == first
    store.revoke_key("lab")
    assert store.seed_key("lab", hash_secret("s" * 20), admin=True) == "unchanged"
    kept = store.api_keys()[0]
    assert kept.revoked is not None and kept.admin  # still revoked; the flag follows
    assert store.seed_key("lab", hash_secret("t" * 20), admin=False) == "replaced"
    replaced = store.api_keys()[0]
    assert replaced.secret_hash == hash_secret("t" * 20) and replaced.revoked is None
    assert replaced.key_id != first.key_id and not replaced.admin


def test_jobs_are_scoped_by_owner(store: JobStore) -> None:
    alice, _ = store.create_job(_job("alice"))
    bob, _ = store.create_job(_job("bob"))
    assert alice.owner == "alice" and store.get_job(bob.job_id, owner="bob") is not None
    assert store.get_job(alice.job_id, owner="bob") is None
    assert store.get_job(alice.job_id) is not None  # no filter: an admin's view
    assert [j.job_id for j in store.list_jobs(limit=10, owner="bob").jobs] == [bob.job_id]
    assert len(store.list_jobs(limit=10).jobs) == 2
    assert store.dismiss(alice.job_id, owner="bob") is None
    job = store.get_job(alice.job_id)
    assert job is not None and job.status is JobStatus.ACCEPTED
    dismissed = store.dismiss(alice.job_id, owner="alice")
    assert dismissed is not None and dismissed.status is JobStatus.DISMISSED


def test_idempotency_keys_are_per_owner(store: JobStore) -> None:
    alice, created = store.create_job(_job("alice", "k1"))
    again, replayed = store.create_job(_job("alice", "k1"))
    bob, bob_created = store.create_job(_job("bob", "k1", x=2))
    assert created and not replayed and again.job_id == alice.job_id
    assert bob_created and bob.job_id != alice.job_id
    with pytest.raises(IdempotencyConflict):
        store.create_job(_job("alice", "k1", x=3))


def test_the_shared_secret_is_made_once(store: JobStore) -> None:
    first = store.shared_secret("session-signing", lambda: "one" * 12)
    assert store.shared_secret("session-signing", lambda: "two" * 12) == first == "one" * 12


def test_a_version_4_store_keeps_its_idempotency_keys(tmp_path: Path) -> None:
    path = tmp_path / "jobs.db"
    conn = sqlite3.connect(path)
    conn.execute("CREATE TABLE schema_version (version INTEGER NOT NULL)")
    types = {"seq_pk": "INTEGER PRIMARY KEY AUTOINCREMENT", "blob": "BLOB",
             "float": "REAL", "bigint": "INTEGER"}  # fmt: skip
    for version, statements in MIGRATIONS:
        if version > 4:
            break
        for statement in statements:
            conn.execute(statement.format(**types))
        conn.execute("INSERT INTO schema_version VALUES (?)", (version,))
    conn.execute(
        "INSERT INTO jobs (job_id, process_id, status, inputs, created, updated, "
        "max_attempts, time_limit_s, idempotency_key, request_hash) "
        "VALUES ('j1', 'toy', 'accepted', '{\"x\": 1}', 1, 1, 3, 60, 'k1', 'h1')"
    )
    conn.commit()
    conn.close()
    store = open_store(f"sqlite:///{path}")
    try:
        job, created = store.create_job(_job("", "k1"))
        assert not created and job.job_id == "j1" and job.owner == ""
        assert store.create_job(_job("alice", "k1"))[1]
    finally:
        store.close()
