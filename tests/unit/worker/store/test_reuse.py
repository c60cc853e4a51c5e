"""Reuse in the store (worker.store.reuse), on SQLite and PostgreSQL: a job of a stored
result key is successful at once with its own row and the source's files, shared files
outlive whichever job is deleted first, and only shareable, valid, whole results of the
owners the scope allows are reused."""

from __future__ import annotations

import time
from typing import Literal

from tests.unit.worker.store.test_retention import stored_bytes
from worker.contract import Artifact, JobStatus
from worker.store.base import JobStore, NewJob

KEY = "k" * 64
FILES = [Artifact("a.png", "image/png", b"\x89PNG" * 1000), Artifact("b.csv", "text/csv", b"x\n")]


def new(
    owner: str = "",
    reuse: Literal["owner", "all"] | None = "owner",
    key: str = KEY,
    share: bool = True,
    retention_s: float = 600,
) -> NewJob:
    return NewJob("p", {"x": 1}, time_limit_s=60, max_attempts=3, owner=owner, reuse=reuse,
                  result_key=key, share=share, retention_s=retention_s)  # fmt: skip


def computed(store: JobStore, job: NewJob) -> str:
    record, created = store.create_job(job)
    assert created and record.status is JobStatus.ACCEPTED
    claim = store.claim_next("w", 30)
    assert claim is not None and claim.job.job_id == record.job_id
    assert claim.job.result_key == job.result_key
    assert store.complete(record.job_id, claim.lease_token, {"v": 1.5}, FILES)
    return record.job_id


def test_a_stored_result_answers_a_new_job_at_once(store: JobStore) -> None:
    assert not store.reusable(new())
    first = computed(store, new())
    assert store.reusable(new()) and not store.reusable(new(reuse=None))
    assert not store.reusable(new(owner="bob")) and store.reusable(new(owner="bob", reuse="all"))
    second, created = store.create_job(new())
    assert created and second.job_id != first and second.status is JobStatus.SUCCESSFUL
    assert second.reused_from == first and second.reused_own and second.expires is not None
    assert store.get_result(second.job_id) == {"v": 1.5}
    assert [a.name for a in second.artifacts] == ["a.png", "b.csv"]
    reused = store.get_artifact(second.job_id, "a.png")
    assert reused is not None and reused.data == FILES[0].data
    assert store.claim_next("w", 30) is None  # nothing was queued
    third, _ = store.create_job(new())  # a reuse of a reuse names the computing job
    assert third.reused_from == first


def test_shared_files_outlive_whichever_job_goes_first(store: JobStore) -> None:
    first = computed(store, new())
    second, _ = store.create_job(new())
    third, _ = store.create_job(new())
    before = stored_bytes(store, first)
    store.dismiss(first)
    assert stored_bytes(store, first) == before
    assert store.get_artifact(second.job_id, "a.png") is not None
    store.dismiss(second.job_id)
    artifact = store.get_artifact(third.job_id, "b.csv")
    assert artifact is not None and artifact.data == b"x\n"
    store.dismiss(third.job_id)
    assert stored_bytes(store, first) == 0


def test_retention_counts_per_job_and_deletes_the_last_files(store: JobStore) -> None:
    first = computed(store, new(retention_s=0.2))
    second, _ = store.create_job(new(retention_s=600))
    time.sleep(0.3)
    assert store.expire_jobs(10) == [first]
    assert store.get_job(first) is None and stored_bytes(store, first) > 0
    artifact = store.get_artifact(second.job_id, "a.png")
    assert artifact is not None and artifact.data == FILES[0].data
    assert second.reused_from == first  # still names it, now deleted
    store.dismiss(second.job_id)
    assert stored_bytes(store, first) == 0


def test_only_what_the_scope_allows_is_reused(store: JobStore) -> None:
    computed(store, new(owner="alice"))
    bob, _ = store.create_job(new(owner="bob", reuse="owner"))
    assert bob.status is JobStatus.ACCEPTED
    bob_all, _ = store.create_job(new(owner="bob", reuse="all"))
    assert bob_all.status is JobStatus.SUCCESSFUL and not bob_all.reused_own
    fresh, _ = store.create_job(new(owner="alice", reuse=None))
    assert fresh.status is JobStatus.ACCEPTED
    other_key, _ = store.create_job(new(owner="alice", key="q" * 64))
    assert other_key.status is JobStatus.ACCEPTED


def test_an_unshareable_result_serves_its_owner_only(store: JobStore) -> None:
    computed(store, new(owner="alice", share=False))
    assert store.create_job(new(owner="bob", reuse="all"))[0].status is JobStatus.ACCEPTED
    assert store.create_job(new(owner="alice"))[0].status is JobStatus.SUCCESSFUL


def test_an_invalidation_stops_reuse_without_deleting_jobs(store: JobStore) -> None:
    first = computed(store, new())
    other = NewJob("q", {}, time_limit_s=60, max_attempts=3, result_key=KEY, reuse="owner")
    assert store.invalidate_reuse("q") == 0
    assert store.invalidate_reuse("p", "z" * 64) == 0
    assert store.invalidate_reuse("p", KEY) == 1
    assert store.create_job(new())[0].status is JobStatus.ACCEPTED
    record = store.get_job(first)
    assert record is not None and record.status is JobStatus.SUCCESSFUL
    assert store.create_job(other)[0].status is JobStatus.ACCEPTED  # another process's
