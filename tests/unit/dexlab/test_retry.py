"""The retry policy: which answers are tried again, and the pauses in between."""

from __future__ import annotations

import random

import pytest

from dexlab import RetryPolicy


def test_pauses_grow_exponentially_up_to_the_cap_and_attempts_are_bounded() -> None:
    policy = RetryPolicy(attempts=6, backoff_s=0.5, max_backoff_s=3.0, jitter=False)
    assert [policy.pause(n) for n in range(1, 6)] == [0.5, 1.0, 2.0, 3.0, 3.0]
    assert policy.pause(6) is None  # the sixth try was the last
    assert RetryPolicy(attempts=1).pause(1) is None


def test_jittered_pauses_stay_in_the_upper_half() -> None:
    policy = RetryPolicy(attempts=10, backoff_s=1.0, max_backoff_s=4.0)
    rng = random.Random(7)
    for attempt in range(1, 10):
        full = min(4.0, 2.0 ** (attempt - 1))
        pause = policy.pause(attempt, rng=rng)
        assert pause is not None and full / 2 <= pause <= full


def test_retry_after_is_honoured_and_capped() -> None:
    policy = RetryPolicy(attempts=3, backoff_s=0.1, max_retry_after_s=5.0, jitter=False)
    assert policy.pause(1, retry_after=2.0) == 2.0
    assert policy.pause(1, retry_after=3600.0) == 5.0
    assert policy.pause(1, retry_after=0.0) == 0.1  # never shorter than the back-off
    assert policy.pause(3, retry_after=2.0) is None


@pytest.mark.parametrize(
    ("status", "problem", "retried"),
    [
        (503, {"type": "/problems/store-unavailable"}, True),
        (502, None, True),
        (504, None, True),
        (503, {"type": "/problems/storage-error", "jobID": "j"}, False),  # a failed job
        (500, {"type": "/problems/internal-error"}, False),
        (429, {"type": "/problems/quota-exceeded"}, False),
        (422, {"type": "/problems/invalid-inputs"}, False),
    ],
)
def test_only_passing_outages_are_retried(
    status: int, problem: dict[str, str] | None, retried: bool
) -> None:
    assert RetryPolicy().retries_answer(status, problem) is retried


@pytest.mark.parametrize(
    ("options", "field"),
    [({"attempts": 0}, "attempts"), ({"backoff_s": -1}, "backoff_s"),
     ({"max_backoff_s": float("nan")}, "max_backoff_s")],
)  # fmt: skip
def test_a_bad_policy_is_refused_naming_the_field(options: dict[str, float], field: str) -> None:
    with pytest.raises(ValueError, match=f"RetryPolicy.{field}"):
        RetryPolicy(**options)  # type: ignore[arg-type]
