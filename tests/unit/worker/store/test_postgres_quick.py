"""PostgreSQL's one-statement claim and completion (worker.store.postgres_quick): the
general path takes over where one statement cannot decide, the claim's relaxed commit
stays inside its own transaction, a chunk's completion is counted in its parent, and
the SQL bucket labels are Python's."""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import psycopg
import pytest
from hypothesis import given
from hypothesis import strategies as st

from tests.services import postgres_schema
from worker.contract import JobStatus
from worker.store import open_store
from worker.store.base import JobStore, NewJob
from worker.store.postgres_quick import bucket_case
from worker.store.tallies import DURATION_BUCKETS, QUEUE_WAIT_BUCKETS, bucket_label


@pytest.fixture
def pg() -> Iterator[tuple[JobStore, str]]:
    with postgres_schema() as url:
        store = open_store(url)
        yield store, url
        store.close()


def submit(store: JobStore, owner: str, tag: str, parent: str | None = None) -> str:
    job, _ = store.create_job(
        NewJob("p", {"tag": tag}, time_limit_s=60, max_attempts=3, owner=owner, parent_id=parent)
    )
    return job.job_id


def test_the_general_path_claims_past_an_owner_whose_jobs_are_all_locked(
    pg: tuple[JobStore, str],
) -> None:
    """The fair order names alice, whose one job another claimer holds locked: the
    statement cannot decide, and the general path goes on to bob's job."""
    store, url = pg
    alice = submit(store, "alice", "a")
    submit(store, "bob", "b")
    with psycopg.connect(url, autocommit=False) as other:
        other.execute("SELECT 1 FROM jobs WHERE job_id = %s FOR UPDATE", (alice,))
        claim = store.claim_next("w", 30)
        assert claim is not None and claim.job.inputs["tag"] == "b"
        other.rollback()
    claim = store.claim_next("w", 30)
    assert claim is not None and claim.job.inputs["tag"] == "a"
    assert store.claim_next("w", 30) is None


def test_the_claims_relaxed_commit_stays_in_its_transaction(pg: tuple[JobStore, str]) -> None:
    store, _ = pg
    submit(store, "", "a")
    assert store.claim_next("w", 30) is not None
    conn: Any = store._conn()  # type: ignore[attr-defined]
    assert conn.execute("SHOW synchronous_commit").fetchone()["synchronous_commit"] == "on"


def test_a_claim_is_durable_once_the_completion_is(pg: tuple[JobStore, str]) -> None:
    """The completion waits for the disk, and the WAL is written in order: the claim
    it follows is on disk too (seen here from another session, after both)."""
    store, url = pg
    job_id = submit(store, "", "a")
    claim = store.claim_next("w", 30)
    assert claim is not None
    assert store.complete(job_id, claim.lease_token, {"ok": True}, [])
    with psycopg.connect(url) as other:
        row = other.execute("SELECT status, attempts FROM jobs WHERE job_id = %s", (job_id,))
        assert row.fetchone() == ("successful", 1)


def test_a_chunks_completion_takes_the_general_path_and_counts_in_its_parent(
    pg: tuple[JobStore, str],
) -> None:
    store, _ = pg
    parent_id = submit(store, "", "study")
    claim = store.claim_next("w", 30)
    assert claim is not None and claim.job.job_id == parent_id
    children = [NewJob("p", {"tag": f"c{n}"}, time_limit_s=60, max_attempts=3) for n in range(2)]
    ids = store.split(parent_id, claim.lease_token, children)
    assert ids is not None and len(ids) == 2
    for _ in ids:
        chunk = store.claim_next("w", 30)
        assert chunk is not None and chunk.job.parent_id == parent_id
        assert store.complete(chunk.job.job_id, chunk.lease_token, {"rows": []}, [])
    parent = store.get_job(parent_id)
    assert parent is not None and parent.children_done == 2
    assert parent.status is JobStatus.ACCEPTED and parent.phase == "assembling"


def test_a_stale_attempts_completion_changes_nothing(pg: tuple[JobStore, str]) -> None:
    store, _ = pg
    job_id = submit(store, "", "a")
    claim = store.claim_next("w", 30)
    assert claim is not None
    assert not store.complete(job_id, "not-the-token", {"ok": False}, [])
    assert store.complete(job_id, claim.lease_token, {"ok": True}, [])
    assert store.complete(job_id, claim.lease_token, {"ok": True}, [])  # a retried call
    assert store.get_result(job_id) == {"ok": True}


@given(st.floats(0, 1e5, allow_nan=False) | st.sampled_from([*DURATION_BUCKETS, 0.0]))
def test_the_sql_bucket_labels_are_pythons(seconds: float) -> None:
    """The CASE the statements compute a histogram's bucket with, evaluated on
    PostgreSQL, against :func:`worker.store.tallies.bucket_label`."""
    with psycopg.connect(_url()) as conn:
        for bounds in (DURATION_BUCKETS, QUEUE_WAIT_BUCKETS):
            sql = "SELECT " + bucket_case("%(x)s::double precision", bounds) + " AS label"
            row = conn.execute(sql, {"x": seconds}).fetchone()
            assert row is not None and row[0] == bucket_label(seconds, bounds), (seconds, bounds)


def _url() -> str:
    from tests.services import require_postgres

    return require_postgres()


def test_bucket_bounds_are_finite_and_increasing() -> None:
    for bounds in (DURATION_BUCKETS, QUEUE_WAIT_BUCKETS):
        assert all(math.isfinite(b) for b in bounds) and list(bounds) == sorted(bounds)
