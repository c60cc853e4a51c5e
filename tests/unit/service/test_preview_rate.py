"""The submit rate applied to previews: a token bucket per API key."""

from __future__ import annotations

import pytest

from service.preview_rate import PreviewRate
from worker.errors import RateLimited


class Clock:
    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


def test_a_key_has_a_burst_of_its_rate_then_one_every_60_over_n_seconds() -> None:
    clock = Clock()
    rate = PreviewRate(3, clock)
    for _ in range(3):
        rate.take("alice")
    with pytest.raises(RateLimited, match=r"next is allowed in 20\.0 s") as refused:
        rate.take("alice")
    assert refused.value.extra["retry_after_s"] == pytest.approx(20.0)
    rate.take("bob")  # another key has its own bucket
    clock.now += 20.0
    rate.take("alice")
    with pytest.raises(RateLimited):
        rate.take("alice")


def test_no_limit_for_the_anonymous_operator_or_a_rate_of_zero() -> None:
    for _ in range(100):
        PreviewRate(1).take("")
    unlimited = PreviewRate(0)
    for _ in range(100):
        unlimited.take("alice")
