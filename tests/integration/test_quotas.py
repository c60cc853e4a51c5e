"""Quotas on a real `dexlab serve`, embedded and Celery over Redis (PostgreSQL).

No worker runs, so every job stays queued: each key may queue 3, the whole queue 5,
each key submit 6 a minute.  Beyond them: 429 ``quota-exceeded`` / ``rate-limited``
and 503 ``queue-full``, each with ``Retry-After`` and the limit named, on /v1, /ogc
and the page form; the limits hold across two API processes on one PostgreSQL.
Each test uses its own key and dismisses its jobs (a dismissed job is not queued).
"""

from __future__ import annotations

import threading
from collections.abc import Iterator

import httpx
import pytest

from tests.integration.servers import Deployment, deployment, free_port, stop_process

pytestmark = pytest.mark.integration

NAMES = ("alice", "bob", "carol", "dave", "erin", "frank")
SECRETS = {name: f"{name}-secret-3e9f0c1a7b" for name in NAMES}
API_KEYS = ",".join(f"{name}:{secret}" for name, secret in SECRETS.items())
LIMITS = {
    "DEXLAB_API_KEYS": API_KEYS,
    "DEXLAB_MAX_QUEUED_PER_KEY": "3",
    "DEXLAB_MAX_QUEUED": "5",
    "DEXLAB_SUBMIT_RATE_PER_MIN": "6",
}
V1 = "/v1/processes/fourbar-grashof/execution"
OGC = "/ogc/processes/fourbar-grashof/execution"
BODY = {"inputs": {"lengths": [2, 7, 9, 6], "ground": 1}}


@pytest.fixture(scope="module", params=["embedded", "celery-redis"])
def queue_only(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Deployment]:
    with deployment(
        str(request.param), tmp_path_factory.mktemp("quotas"), workers=0, env=LIMITS
    ) as dep:
        yield dep


def as_key(base_url: str, name: str) -> httpx.Client:
    headers = {"Authorization": f"Bearer {SECRETS[name]}"}
    return httpx.Client(base_url=base_url, headers=headers, timeout=30.0)


def submitted(r: httpx.Response) -> str:
    assert r.status_code == 201, r.text
    return str(r.json()["jobID"])


def dismiss_all(c: httpx.Client) -> None:
    for job in c.get("/v1/jobs", params={"limit": 1000}).json()["jobs"]:
        c.delete(f"/v1/jobs/{job['jobID']}")


def assert_refused(r: httpx.Response, status: int, slug: str, limit: str, allowed: int) -> None:
    assert r.status_code == status, r.text
    assert int(r.headers["retry-after"]) >= 1
    problem = r.json()
    assert problem["type"] == f"/problems/{slug}"
    assert problem["limit"] == limit and problem["allowed"] == allowed


def test_a_keys_queue_is_limited_on_every_way_in(queue_only: Deployment) -> None:
    with as_key(queue_only.base_url, "alice") as alice:
        try:
            key = {"Idempotency-Key": "alice-first"}
            first = submitted(alice.post(V1, json=BODY, headers=key))
            submitted(alice.post(V1, json=BODY))
            submitted(alice.post(OGC, json=BODY, headers={"Prefer": "respond-async"}))
            for path, headers in ((V1, {}), (OGC, {"Prefer": "respond-async"})):
                r = alice.post(path, json=BODY, headers=headers)
                assert_refused(r, 429, "quota-exceeded", "DEXLAB_MAX_QUEUED_PER_KEY", 3)
            page = alice.post(
                "/pages/processes/fourbar-grashof/run",
                data={"inputs": '{"lengths": [2, 7, 9, 6], "ground": 1}', "example": "0"},
                headers={"Origin": queue_only.base_url, "Accept": "text/html"},
            )
            assert page.status_code == 429 and int(page.headers["retry-after"]) >= 1
            assert page.headers["content-type"].startswith("text/html")
            assert "DEXLAB_MAX_QUEUED_PER_KEY" in page.text
            replay = alice.post(V1, json=BODY, headers=key)  # a replay makes nothing
            assert replay.status_code == 201 and replay.json()["jobID"] == first
            assert replay.headers["idempotent-replayed"] == "true"
            alice.delete(f"/v1/jobs/{first}")  # no longer queued: a slot frees
            submitted(alice.post(V1, json=BODY))
        finally:
            dismiss_all(alice)


def test_the_whole_queue_is_503_when_full(queue_only: Deployment) -> None:
    with as_key(queue_only.base_url, "bob") as bob, as_key(queue_only.base_url, "carol") as carol:
        try:
            for _ in range(3):
                submitted(bob.post(V1, json=BODY))
            for _ in range(2):
                submitted(carol.post(V1, json=BODY))
            r = carol.post(V1, json=BODY)
            assert_refused(r, 503, "queue-full", "DEXLAB_MAX_QUEUED", 5)
            r = carol.post(OGC, json=BODY, headers={"Prefer": "respond-async"})
            assert_refused(r, 503, "queue-full", "DEXLAB_MAX_QUEUED", 5)
        finally:
            dismiss_all(bob)
            dismiss_all(carol)


def test_submissions_per_minute_are_limited(queue_only: Deployment) -> None:
    with as_key(queue_only.base_url, "dave") as dave:
        try:
            for _ in range(2):  # six in all, dismissed as they go (never 3 queued)
                for _ in range(3):
                    submitted(dave.post(V1, json=BODY))
                dismiss_all(dave)
            r = dave.post(V1, json=BODY)
            assert_refused(r, 429, "rate-limited", "DEXLAB_SUBMIT_RATE_PER_MIN", 6)
            assert 1 <= int(r.headers["retry-after"]) <= 10  # a token every 10 s
        finally:
            dismiss_all(dave)


def test_the_client_raises_quota_exceeded_with_its_retry_after(queue_only: Deployment) -> None:
    from dexlab import Client
    from dexlab.errors import QuotaExceeded

    inputs = BODY["inputs"]
    with Client(url=queue_only.base_url, api_key=SECRETS["frank"]) as frank:
        try:
            for _ in range(3):
                frank.submit("fourbar-grashof", inputs)
            with pytest.raises(QuotaExceeded) as refused:
                frank.submit("fourbar-grashof", inputs)
            assert refused.value.retry_after is not None and refused.value.retry_after >= 1
            assert refused.value.status == 429
        finally:
            for job in frank.jobs():
                job.cancel()


# Replicas share a PostgreSQL store (SQLite is one machine's file): Celery's backend only.
@pytest.mark.parametrize("queue_only", ["celery-redis"], indirect=True)
def test_the_limits_hold_across_two_api_processes(queue_only: Deployment) -> None:
    port = free_port()
    second = queue_only._spawn(
        ["serve", "--port", str(port), "--data-dir", str(queue_only.data_dir), "--workers", "0"],
        "api-2.log",
    )
    other_url = f"http://127.0.0.1:{port}"
    try:
        with httpx.Client(base_url=other_url, timeout=30.0) as probe:
            for _ in range(300):
                try:
                    if probe.get("/health/live").status_code == 200:
                        break
                except httpx.TransportError:
                    pass
                threading.Event().wait(0.2)
        statuses: list[int] = []
        lock = threading.Lock()
        start = threading.Barrier(8)

        def submit(base_url: str) -> None:
            with as_key(base_url, "erin") as erin:
                start.wait()
                r = erin.post(V1, json=BODY)
            with lock:
                statuses.append(r.status_code)

        urls = [queue_only.base_url, other_url] * 4
        threads = [threading.Thread(target=submit, args=(url,)) for url in urls]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        assert sorted(statuses) == [201] * 3 + [429] * 5, statuses
        with as_key(other_url, "erin") as erin:
            assert len(erin.get("/v1/jobs").json()["jobs"]) == 3
            dismiss_all(erin)
    finally:
        stop_process(second)
