"""Job ID prefixes in the ``dexlab`` commands and the 80-column jobs table, against an
in-memory fake of the service's job routes (``GET /v1/jobs``, ``GET /v1/jobs/{id}``)."""

from __future__ import annotations

import json
from collections.abc import Iterator
from datetime import UTC, datetime
from typing import Any

import httpx
import pytest
from rich.console import Console

import dexlab.cli.jobs
from dexlab.cli import main
from dexlab.cli.job_ids import AmbiguousJobId, find_job, short_ids
from dexlab.cli.job_table import duration_s, duration_text, status_table
from dexlab.client import Client
from dexlab.documents import JobStatus
from dexlab.errors import NoSuchJob


def status(job_id: str, process: str = "fourbar-grashof", **extra: Any) -> dict[str, Any]:
    return {"jobID": job_id, "processID": process, "status": "successful", "progress": 100,
            "message": "done", "created": "2026-11-28T05:00:00.000000Z",
            "started": "2026-11-28T05:00:01.000000Z",
            "finished": "2026-11-28T05:03:06.500000Z", **extra}  # fmt: skip


class FakeJobs:
    """The job routes over a fixed set of jobs, two per listing page (so the search
    follows cursors); ``parent`` lists a study's chunks, as the service does."""

    def __init__(self, top: list[dict[str, Any]], chunks: dict[str, list[dict[str, Any]]]):
        self.top, self.chunks = top, chunks
        self.requests: list[str] = []

    def handle(self, request: httpx.Request) -> httpx.Response:
        self.requests.append(str(request.url))
        every = self.top + [c for cs in self.chunks.values() for c in cs]
        path = request.url.path
        if path == "/v1/jobs":
            parent = request.url.params.get("parent")
            listed = self.top if parent is None else self.chunks.get(parent, [])
            start = int(request.url.params.get("cursor", "0"))
            more = start + 2 < len(listed)
            page = {
                "jobs": listed[start : start + 2],
                "next_cursor": str(start + 2) if more else None,
            }
            return httpx.Response(200, json=page)
        job_id = path.removeprefix("/v1/jobs/")
        found = [d for d in every if d["jobID"] == job_id]
        if found:
            return httpx.Response(200, json=found[0])
        problem = {"type": "/problems/no-such-job", "title": "No such job",
                   "status": 404, "detail": f"No job '{job_id}'."}  # fmt: skip
        return httpx.Response(
            404, json=problem, headers={"Content-Type": "application/problem+json"}
        )

    def client(self) -> Client:
        client = Client("http://dexlab.test")
        client._http = httpx.Client(base_url=client.url, transport=httpx.MockTransport(self.handle))
        return client


STUDY = "5a1b2c3d-0000-4000-8000-000000000001"


@pytest.fixture
def service() -> FakeJobs:
    top = [
        status("ab12cd34-1111-4111-8111-111111111111"),
        status("ab12cd99-2222-4222-8222-222222222222", "planar3r-dexterity-map"),
        status(STUDY, "design-study", chunks={"total": 2, "ended": 2, "failed": 0}),
        status("c0ffee00-3333-4333-8333-333333333333"),
        status("d00d0000-6666-4666-8666-666666666666"),
    ]
    chunks = {STUDY: [status("d00dfeed-4444-4444-8444-444444444444", parentID=STUDY),
                      status("e1e10000-5555-4555-8555-555555555555", parentID=STUDY)]}  # fmt: skip
    return FakeJobs(top, chunks)


def test_a_full_id_a_unique_prefix_and_a_chunk_prefix_find_their_job(service: FakeJobs) -> None:
    with service.client() as client:
        assert find_job(client, "e1e10000-5555-4555-8555-555555555555").id.startswith("e1e1")
        assert find_job(client, "c0f").id == "c0ffee00-3333-4333-8333-333333333333"
        assert find_job(client, "ab12cd9").process_id == "planar3r-dexterity-map"
        assert find_job(client, "e1e").id == "e1e10000-5555-4555-8555-555555555555"


def test_client_jobs_come_before_chunks(service: FakeJobs) -> None:
    with service.client() as client:  # d00d starts a client job and a chunk
        assert find_job(client, "d00d").id == "d00d0000-6666-4666-8666-666666666666"
    assert not any("parent=" in url for url in service.requests)


def test_an_ambiguous_prefix_names_every_candidate(service: FakeJobs) -> None:
    with service.client() as client, pytest.raises(AmbiguousJobId) as raised:
        find_job(client, "ab12")
    assert [s.job_id[:8] for s in raised.value.candidates] == ["ab12cd34", "ab12cd99"]
    assert raised.value.exit_code == 2


def test_no_match_is_the_services_no_such_job(service: FakeJobs) -> None:
    with service.client() as client, pytest.raises(NoSuchJob, match="No job 'fff'"):
        find_job(client, "fff")


@pytest.fixture
def cli(service: FakeJobs, monkeypatch: pytest.MonkeyPatch) -> Iterator[FakeJobs]:
    monkeypatch.setattr(dexlab.cli.jobs, "open_client", lambda url, key: service.client())
    yield service


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    with pytest.raises(SystemExit) as exited:
        main(list(args))
    out, err = capsys.readouterr()
    return int(exited.value.code or 0), out, err


def test_the_commands_exit_2_listing_the_candidates(
    cli: FakeJobs, capsys: pytest.CaptureFixture[str]
) -> None:
    code, out, err = run(capsys, "status", "ab12")
    assert code == 2 and out == ""
    lines = err.strip().splitlines()
    assert lines[0] == "dexlab: 'ab12' starts 2 job IDs; type more of the ID:"
    assert [line.split()[:2] for line in lines[1:]] == [
        ["ab12cd34-1111-4111-8111-111111111111", "fourbar-grashof"],
        ["ab12cd99-2222-4222-8222-222222222222", "planar3r-dexterity-map"],
    ]
    code, out, _ = run(capsys, "status", "ab12cd9", "--json")
    assert code == 0 and json.loads(out)["jobID"].startswith("ab12cd99")
    code, _, err = run(capsys, "status", "999")
    assert code == 1 and err.strip() == "dexlab: No such job: No job '999'."


def test_the_jobs_table_fits_80_columns_one_line_a_job() -> None:
    now = datetime(2026, 11, 28, 5, 10, tzinfo=UTC)
    statuses = [
        JobStatus.from_document(
            status(
                "ab12cd34-1111-4111-8111-111111111111",
                "planar3r-dexterity-map-with-a-long-name",
                message="a long message " * 8,
            )
        ),
        JobStatus.from_document(
            status(
                "ab12cd99-2222-4222-8222-222222222222",
                "design-study",
                status="running",
                finished=None,
                progress=40,
            )
        ),
        JobStatus.from_document(
            status(
                "c0ffee00-3333-4333-8333-333333333333",
                status="accepted",
                started=None,
                finished=None,
                progress=0,
            )
        ),
    ]
    console = Console(width=80, record=True, color_system=None)
    console.print(status_table(statuses, now))
    lines = console.export_text().rstrip("\n").splitlines()
    assert max(len(line) for line in lines) <= 80
    rows = [line for line in lines if line.lstrip().startswith(("ab12", "c0ff"))]
    assert len(rows) == 3, lines  # one line each, nothing wrapped
    assert "ab12cd34 " in rows[0] and "3m 06s" in rows[0] and "…" in rows[0]
    assert "ab12cd99 " in rows[1] and "9m 59s" in rows[1]  # running: up to now
    assert "c0ffee00 " in rows[2]
    assert "Took" in "".join(lines)


def test_short_ids_are_the_shortest_unique_prefixes() -> None:
    ids = ["ab12cd34-1", "ab12cd34-2", "ab12cd99-3", "ff"]
    assert short_ids(ids) == ["ab12cd34-1", "ab12cd34-2", "ab12cd99", "ff"]


@pytest.mark.parametrize(
    ("seconds", "text"),
    [
        (None, ""),
        (0.42, "0.4 s"),
        (12.4, "12 s"),
        (185.5, "3m 06s"),
        (7800, "2h 10m"),
        (273600, "3d 4h"),
    ],
)
def test_duration_text(seconds: float | None, text: str) -> None:
    assert duration_text(seconds) == text


def test_a_queued_job_has_no_duration() -> None:
    assert duration_s(status("x", status="accepted")) is None
    assert duration_s(status("x")) == pytest.approx(185.5)
