"""Every store test runs on each implementation: SQLite, and PostgreSQL when reachable."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.services import postgres_schema
from worker.store import open_store
from worker.store.base import JobStore


@pytest.fixture(params=["sqlite", "postgresql"])
def store(request: pytest.FixtureRequest, tmp_path: Path) -> Iterator[JobStore]:
    if request.param == "sqlite":
        s = open_store(f"sqlite:///{tmp_path / 'jobs.db'}")
        yield s
        s.close()
    else:
        with postgres_schema() as url:
            s = open_store(url)
            yield s
            s.close()
