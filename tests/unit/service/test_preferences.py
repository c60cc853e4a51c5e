"""Parsing the Prefer header (RFC 7240)."""

from __future__ import annotations

import pytest

from service.preferences import MAX_WAIT_S, requested_wait


@pytest.mark.parametrize(
    ("header", "expected"),
    [
        (None, None),
        ("", None),
        ("wait=10", 10.0),
        ("WAIT = 2.5", 2.5),
        ('wait="7"', 7.0),
        ("handling=strict, wait=3", 3.0),
        ("respond-async, wait=10", None),
        ("wait=0", None),
        ("wait=-1", None),
        ("wait=soon", None),
        ("wait=100000", MAX_WAIT_S),
        ("return=minimal", None),
    ],
)
def test_requested_wait(header: str | None, expected: float | None) -> None:
    assert requested_wait(header) == expected
