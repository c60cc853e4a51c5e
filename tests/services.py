"""Reaching the services some tests need (PostgreSQL, Redis, RabbitMQ).

Where a service is not reachable (a laptop), such tests skip with the reason; with
``DEXLAB_REQUIRE_SERVICES=1`` (set by ``.ci/run``) they fail instead, so CI always
runs them.
"""

from __future__ import annotations

import importlib.util
import os
import socket
import uuid
from collections.abc import Iterator
from contextlib import contextmanager
from urllib.parse import urlsplit

import pytest

POSTGRES_URL = os.environ.get(
    "DEXLAB_TEST_POSTGRES_URL", "postgresql://postgres@127.0.0.1:5432/test"
)
REDIS_URL = os.environ.get("DEXLAB_TEST_REDIS_URL", "redis://127.0.0.1:6379/0")
AMQP_URL = os.environ.get("DEXLAB_TEST_AMQP_URL", "amqp://guest:guest@127.0.0.1:5672//")


def services_required() -> bool:
    return os.environ.get("DEXLAB_REQUIRE_SERVICES", "") not in ("", "0", "false")


def unavailable(reason: str) -> None:
    """Skip the test, or fail it when services are required."""
    if services_required():
        pytest.fail(f"{reason} (DEXLAB_REQUIRE_SERVICES is set, so this is a failure)")
    pytest.skip(reason)


def reachable(url: str, default_port: int) -> bool:
    parts = urlsplit(url)
    try:
        with socket.create_connection(
            (parts.hostname or "127.0.0.1", parts.port or default_port), timeout=2
        ):
            return True
    except OSError:
        return False


def require_packages(*modules: str) -> None:
    missing = [m for m in modules if importlib.util.find_spec(m) is None]
    if missing:
        unavailable(f"needs {', '.join(missing)}: pip install 'dexlab[distributed]'")


def require_postgres() -> str:
    require_packages("psycopg")
    if not reachable(POSTGRES_URL, 5432):
        unavailable(f"PostgreSQL is not reachable at {urlsplit(POSTGRES_URL).netloc}")
    return POSTGRES_URL


def require_broker(url: str) -> str:
    require_packages("celery", "redis" if url.startswith("redis") else "amqp")
    if not reachable(url, 6379 if url.startswith("redis") else 5672):
        unavailable(f"the broker is not reachable at {urlsplit(url).netloc}")
    return url


@contextmanager
def postgres_schema() -> Iterator[str]:
    """A store URL on a fresh, private PostgreSQL schema, dropped afterwards."""
    import psycopg

    base = require_postgres()
    schema = f"dexlab_test_{uuid.uuid4().hex[:12]}"
    with psycopg.connect(base, autocommit=True) as conn:
        conn.execute(f'CREATE SCHEMA "{schema}"')
    sep = "&" if "?" in base else "?"
    try:
        yield f"{base}{sep}options=-csearch_path%3D{schema}"
    finally:
        with psycopg.connect(base, autocommit=True) as conn:
            conn.execute(f'DROP SCHEMA IF EXISTS "{schema}" CASCADE')
