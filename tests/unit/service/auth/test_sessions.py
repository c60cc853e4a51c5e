"""Session tokens and CSRF tokens: signed, bound to their key, expiring."""

from __future__ import annotations

import pytest

from service.auth.sessions import SessionSigner

SECRET = b"s" * 32


class Clock:
    def __init__(self, now: float = 1_000_000.0) -> None:
        self.now = now

    def __call__(self) -> float:
        return self.now


def test_a_token_names_its_key_until_it_expires() -> None:
    clock = Clock()
    signer = SessionSigner(SECRET, lifetime_s=60, clock=clock)
    token = signer.issue("abc123")
    assert signer.key_id_of(token) == "abc123"
    clock.now += 59
    assert signer.key_id_of(token) == "abc123"
    clock.now += 1
    assert signer.key_id_of(token) is None


def test_two_logins_get_different_tokens_and_csrf_tokens() -> None:
    signer = SessionSigner(SECRET, lifetime_s=60)
    first, second = signer.issue("k"), signer.issue("k")
    assert first != second
    assert signer.csrf_token(first) != signer.csrf_token(second)


@pytest.mark.parametrize(
    "tamper",
    [
        lambda t: t.replace(".k1.", ".k2."),  # another key
        lambda t: t[:-2] + ("AA" if not t.endswith("AA") else "BB"),  # the signature
        lambda t: t.replace("v1.", "v2.", 1),
        lambda t: t.rsplit(".", 1)[0],  # no signature
        lambda t: "",
        lambda t: "v1.k1.99999999999.nonce.sig",
        lambda t: t + "é",
    ],
)
def test_a_changed_or_forged_token_is_refused(tamper: object) -> None:
    signer = SessionSigner(SECRET, lifetime_s=60)
    token = signer.issue("k1")
    assert callable(tamper)
    assert signer.key_id_of(tamper(token)) is None


def test_a_token_signed_with_another_secret_is_refused() -> None:
    token = SessionSigner(b"a" * 32, lifetime_s=60).issue("k1")
    assert SessionSigner(b"b" * 32, lifetime_s=60).key_id_of(token) is None


def test_the_csrf_token_belongs_to_one_session_and_one_secret() -> None:
    signer = SessionSigner(SECRET, lifetime_s=60)
    session, other = signer.issue("k"), signer.issue("k")
    token = signer.csrf_token(session)
    assert signer.csrf_matches(session, token)
    assert not signer.csrf_matches(other, token)
    assert not signer.csrf_matches(session, "")
    assert not signer.csrf_matches(session, token + "x")
    assert not signer.csrf_matches(session, "ü" * len(token))
    assert not SessionSigner(b"t" * 32, lifetime_s=60).csrf_matches(session, token)


def test_a_short_secret_and_a_bad_key_id_are_refused() -> None:
    with pytest.raises(ValueError, match="at least 32 bytes"):
        SessionSigner(b"short", lifetime_s=60)
    with pytest.raises(ValueError, match="dot-free"):
        SessionSigner(SECRET, lifetime_s=60).issue("a.b")
