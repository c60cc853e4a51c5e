"""Which routes answer without a key."""

from __future__ import annotations

import pytest

from service.auth.public_routes import is_public, session_may

PUBLIC = [
    ("GET", "/"),
    ("GET", "/v1"),
    ("GET", "/v1/processes"),
    ("HEAD", "/v1/processes/fourbar-grashof"),
    ("GET", "/health/live"),
    ("GET", "/health/ready"),
    ("GET", "/docs"),
    ("GET", "/docs/oauth2-redirect"),
    ("GET", "/redoc"),
    ("GET", "/openapi.json"),
    ("GET", "/favicon.ico"),
    ("GET", "/metrics"),
    ("GET", "/static/pages/pages.css"),
    ("GET", "/methods"),
    ("GET", "/methods/planar-serial"),
    ("GET", "/problems/unauthorized"),
    ("GET", "/ogc"),
    ("GET", "/ogc/"),
    ("GET", "/ogc/conformance"),
    ("GET", "/ogc/processes"),
    ("GET", "/ogc/processes/fourbar-grashof"),
    ("GET", "/login"),
    ("POST", "/login"),
    ("POST", "/logout"),
    ("OPTIONS", "/v1/jobs"),
]
PROTECTED = [
    ("POST", "/v1/processes/fourbar-grashof/execution"),
    ("GET", "/v1/processes/fourbar-grashof/execution"),
    ("GET", "/v1/jobs"),
    ("GET", "/v1/jobs/abc"),
    ("DELETE", "/v1/jobs/abc"),
    ("GET", "/v1/jobs/abc/results"),
    ("GET", "/v1/jobs/abc/results/plot.png"),
    ("GET", "/v1/jobs/abc/events"),
    ("POST", "/pages/processes/fourbar-grashof/run"),
    ("POST", "/pages/jobs/abc/dismiss"),
    ("POST", "/ogc/processes/fourbar-grashof/execution"),
    ("GET", "/ogc/jobs"),
    ("GET", "/ogc/jobs/abc/results"),
    ("DELETE", "/ogc/jobs/abc"),
    ("POST", "/v1/processes"),
    ("PUT", "/"),
    ("GET", "/nowhere"),
]


@pytest.mark.parametrize(("method", "path"), PUBLIC)
def test_public(method: str, path: str) -> None:
    assert is_public(method, path)


@pytest.mark.parametrize(("method", "path"), PROTECTED)
def test_protected(method: str, path: str) -> None:
    assert not is_public(method, path)


def test_a_session_reads_and_posts_forms_but_writes_nothing_else() -> None:
    assert session_may("GET", "/v1/jobs/abc/events")
    assert session_may("POST", "/pages/jobs/abc/dismiss")
    assert session_may("POST", "/logout")
    assert not session_may("DELETE", "/v1/jobs/abc")
    assert not session_may("POST", "/v1/processes/fourbar-grashof/execution")
    assert not session_may("POST", "/ogc/processes/fourbar-grashof/execution")
