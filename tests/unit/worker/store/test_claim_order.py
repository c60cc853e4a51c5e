"""Fair claims (worker.store.scheduling), on SQLite and PostgreSQL: round-robin over
owners with queued work, oldest job first; a slot that prefers cheap jobs; the running
cap per owner."""

from __future__ import annotations

from worker.contract import JobStatus
from worker.store.base import JobStore, NewJob
from worker.store.scheduling import CAPPED_RETRY_S


def submit(store: JobStore, owner: str, tag: str, cheap: bool = False) -> str:
    job, _ = store.create_job(
        NewJob("p", {"tag": tag}, time_limit_s=60, max_attempts=3, owner=owner, cheap=cheap)
    )
    return job.job_id


def claimed_tags(store: JobStore, count: int, **options: object) -> list[str]:
    tags = []
    for n in range(count):
        claim = store.claim_next(f"w{n}", 30, **options)  # type: ignore[arg-type]
        assert claim is not None, f"claim {n} found nothing"
        tags.append(str(claim.job.inputs["tag"]))
    return tags


def test_claims_go_round_robin_over_owners_then_oldest_first(store: JobStore) -> None:
    for n in range(4):
        submit(store, "alice", f"a{n}")
    submit(store, "bob", "b0")
    submit(store, "bob", "b1")
    submit(store, "carol", "c0")
    # Nobody has been served: by name (alice, bob, carol), then whoever waited longest.
    assert claimed_tags(store, 7) == ["a0", "b0", "c0", "a1", "b1", "a2", "a3"]
    assert store.claim_next("w", 30) is None


def test_a_newcomer_goes_before_an_owner_served_just_now(store: JobStore) -> None:
    for n in range(20):
        submit(store, "heavy", f"h{n}")
    assert claimed_tags(store, 2) == ["h0", "h1"]  # the heavy owner's jobs run
    submit(store, "light", "small")
    assert claimed_tags(store, 2) == ["small", "h2"]


def test_a_slot_that_prefers_cheap_jobs_takes_one_first(store: JobStore) -> None:
    for n in range(3):
        submit(store, "", f"heavy{n}")
    submit(store, "", "cheap", cheap=True)
    assert claimed_tags(store, 1) == ["heavy0"]  # an ordinary slot: oldest first
    assert claimed_tags(store, 1, prefer_cheap=True) == ["cheap"]
    # No cheap job left: the preferring slot takes any job, so one slot loses nothing.
    assert claimed_tags(store, 2, prefer_cheap=True) == ["heavy1", "heavy2"]


def test_cheap_preference_is_fair_between_owners(store: JobStore) -> None:
    submit(store, "alice", "a-cheap", cheap=True)
    submit(store, "bob", "b-heavy")
    submit(store, "bob", "b-cheap", cheap=True)
    assert claimed_tags(store, 1) == ["a-cheap"]  # alice: never served, first by name
    assert claimed_tags(store, 1, prefer_cheap=True) == ["b-cheap"]
    assert claimed_tags(store, 1, prefer_cheap=True) == ["b-heavy"]


def test_an_owner_at_its_running_cap_is_skipped_until_one_ends(store: JobStore) -> None:
    first = submit(store, "alice", "a0")
    submit(store, "alice", "a1")
    submit(store, "bob", "b0")
    cap = {"max_running_per_owner": 1}
    assert claimed_tags(store, 2, **cap) == ["a0", "b0"]
    assert store.claim_next("w", 30, max_running_per_owner=1) is None  # both at the cap
    running = store.get_job(first)
    assert running is not None and running.status is JobStatus.RUNNING
    claim = store.claim_next("x", 30)  # without a cap the job is claimable
    assert claim is not None and claim.job.inputs["tag"] == "a1"


def test_the_cap_frees_when_a_job_finishes(store: JobStore) -> None:
    submit(store, "alice", "a0")
    second = submit(store, "alice", "a1")
    claim = store.claim_next("w", 30, max_running_per_owner=1)
    assert claim is not None
    held = store.claim_job(second, "w2", 30, max_running_per_owner=1)
    assert held.claim is None and held.status is JobStatus.ACCEPTED
    assert held.retry_after_s == CAPPED_RETRY_S
    assert store.complete(claim.job.job_id, claim.lease_token, {"ok": True}, [])
    again = store.claim_job(second, "w2", 30, max_running_per_owner=1)
    assert again.claim is not None and again.claim.job.job_id == second


def test_the_anonymous_owner_has_no_running_cap(store: JobStore) -> None:
    for n in range(3):
        submit(store, "", f"o{n}")
    assert claimed_tags(store, 3, max_running_per_owner=1) == ["o0", "o1", "o2"]


def test_a_requeued_job_keeps_its_place_in_its_owners_line(store: JobStore) -> None:
    lost = submit(store, "alice", "a0")
    submit(store, "alice", "a1")
    claim = store.claim_next("w-dead", 30)
    assert claim is not None and claim.job.job_id == lost
    store.expire_leases_of("w-dead")
    again = store.claim_next("w-new", 30)  # reaped and claimed again: still the oldest
    assert again is not None and again.job.job_id == lost and again.job.attempts == 2
