"""Jobs that fan out (worker.store.fan_out), on SQLite and PostgreSQL: a split parks the
parent without a lease; the last child's end queues it to assemble; a failed child
fails it (or counts as missing with allow_partial); dismissal reaches the children;
listings, quotas and retention know the children."""

from __future__ import annotations

import time

from worker.contract import JobStatus
from worker.store.base import JobFilter, JobStore, NewJob


def parent_claim(store: JobStore, owner: str = "alice") -> tuple[str, str]:
    job, _ = store.create_job(
        NewJob("study", {"n": 3}, time_limit_s=60, max_attempts=2, owner=owner, retention_s=99)
    )
    claim = store.claim_next("w0", 30)
    assert claim is not None and claim.job.job_id == job.job_id
    return job.job_id, claim.lease_token


def children(count: int) -> list[NewJob]:
    return [NewJob("chunk", {"i": i}, time_limit_s=30, max_attempts=2) for i in range(count)]


def run_child(store: JobStore, ok: bool = True) -> str:
    claim = store.claim_next("w1", 30)
    assert claim is not None and claim.job.process_id == "chunk"
    if ok:
        assert store.complete(claim.job.job_id, claim.lease_token, {"i": claim.job.inputs["i"]}, [])
    else:
        store.fail(claim.job.job_id, claim.lease_token, {"type": "boom", "detail": "it broke"})
    return claim.job.job_id


def test_split_parks_the_parent_and_the_last_child_queues_it(store: JobStore) -> None:
    parent_id, token = parent_claim(store)
    ids = store.split(parent_id, token, children(3))
    assert ids is not None and len(ids) == 3
    assert store.split(parent_id, token, children(3)) == ids  # a retried split is the same
    parent = store.get_job(parent_id)
    assert parent is not None
    assert (parent.status, parent.phase, parent.children_total) == (JobStatus.RUNNING, "waiting", 3)
    assert not store.heartbeat(parent_id, token, 30).owner  # its lease is gone
    store.reap_expired()
    assert store.get_job(parent_id).status is JobStatus.RUNNING  # type: ignore[union-attr]
    child = store.get_job(ids[0])
    assert child is not None and (child.parent_id, child.owner) == (parent_id, "alice")
    for n in range(3):
        run_child(store)
        parent = store.get_job(parent_id)
        assert parent is not None and parent.children_done == n + 1
        assert parent.progress == (100.0 * (n + 1) / 3)
    assert (parent.status, parent.phase, parent.attempts) == (JobStatus.ACCEPTED, "assembling", 0)
    claim = store.claim_next("w2", 30)
    assert claim is not None and claim.job.job_id == parent_id and claim.job.phase == "assembling"
    results = [(end.job_id, end.status, result) for end, result in store.child_results(parent_id)]
    assert results == [(ids[i], JobStatus.SUCCESSFUL, {"i": i}) for i in range(3)]
    assert store.complete(parent_id, claim.lease_token, {"done": True}, [])
    assert store.get_job(parent_id).status is JobStatus.SUCCESSFUL  # type: ignore[union-attr]


def test_a_failed_child_fails_the_parent_and_stops_the_others(store: JobStore) -> None:
    parent_id, token = parent_claim(store)
    ids = store.split(parent_id, token, children(3))
    assert ids is not None
    failed = run_child(store, ok=False)
    parent = store.get_job(parent_id)
    assert parent is not None and parent.status is JobStatus.FAILED
    assert parent.error is not None and parent.error["type"] == "chunk-failed"
    assert failed in parent.error["detail"] and "it broke" in parent.error["detail"]
    others = [store.get_job(i) for i in ids if i != failed]
    assert all(o is not None and o.status is JobStatus.DISMISSED for o in others)


def test_with_allow_partial_a_failed_child_is_missing(store: JobStore) -> None:
    parent_id, token = parent_claim(store)
    store.split(parent_id, token, children(2), allow_partial=True)
    run_child(store, ok=False)
    run_child(store)
    parent = store.get_job(parent_id)
    assert parent is not None and (parent.status, parent.phase) == (
        JobStatus.ACCEPTED,
        "assembling",
    )
    assert (parent.children_done, parent.children_failed) == (2, 1)
    statuses = [end.status for end, _ in store.child_results(parent_id)]
    assert statuses == [JobStatus.FAILED, JobStatus.SUCCESSFUL]


def test_a_lost_worker_out_of_attempts_counts_as_a_failed_child(store: JobStore) -> None:
    parent_id, token = parent_claim(store)
    store.split(parent_id, token, [NewJob("chunk", {"i": 0}, time_limit_s=30, max_attempts=1)])
    claim = store.claim_next("w1", 0.01)
    assert claim is not None
    time.sleep(0.05)
    store.reap_expired()
    parent = store.get_job(parent_id)
    assert parent is not None and parent.status is JobStatus.FAILED
    assert "worker" in parent.error["detail"]  # type: ignore[index]


def test_dismissing_the_parent_dismisses_its_unfinished_children(store: JobStore) -> None:
    parent_id, token = parent_claim(store)
    ids = store.split(parent_id, token, children(3))
    assert ids is not None
    done = run_child(store)
    store.dismiss(parent_id)
    statuses = {i: store.get_job(i).status for i in ids}  # type: ignore[union-attr]
    assert statuses[done] is JobStatus.SUCCESSFUL
    assert [s for i, s in statuses.items() if i != done] == [JobStatus.DISMISSED] * 2
    assert store.claim_next("w3", 30) is None


def test_children_are_listed_only_when_asked_for(store: JobStore) -> None:
    parent_id, token = parent_claim(store)
    ids = store.split(parent_id, token, children(2))
    listed = [j.job_id for j in store.list_jobs(limit=10).jobs]
    assert listed == [parent_id]
    page = store.list_jobs(limit=10, where=JobFilter(parent_id=parent_id))
    assert sorted(j.job_id for j in page.jobs) == sorted(ids or [])


def test_a_waiting_study_does_not_hold_its_owners_running_cap(store: JobStore) -> None:
    parent_id, token = parent_claim(store)
    store.split(parent_id, token, children(2))
    first = store.claim_next("w1", 30, max_running_per_owner=1)
    assert first is not None and first.job.parent_id == parent_id  # the study holds none
    assert store.claim_next("w2", 30, max_running_per_owner=1) is None  # the chunk does


def test_losing_the_worker_that_split_a_study_leaves_the_study_waiting(store: JobStore) -> None:
    # The pool expires the leases of a dead process; the study it split holds none and
    # must stay parked (requeued, it would run again as if never split).
    parent_id, token = parent_claim(store)
    store.split(parent_id, token, children(2))
    assert store.expire_leases_of("w0") == 0
    store.reap_expired()
    parent = store.get_job(parent_id)
    assert parent is not None and (parent.status, parent.phase) == (JobStatus.RUNNING, "waiting")
