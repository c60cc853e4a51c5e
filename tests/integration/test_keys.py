"""API keys and job ownership on a real `dexlab serve`, embedded and Celery over Redis.

The deployment declares three keys in DEXLAB_API_KEYS (alice, bob, root the admin);
the CLI makes and revokes another against the same store.  Each owner sees and
dismisses only its own jobs, on /v1 and /ogc; another's job is 404 on every route;
an admin sees both; secrets never reach the store, the logs or a response.
"""

from __future__ import annotations

import subprocess
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest

from tests.integration.servers import Deployment, deployment, dexlab_command, wait_terminal

pytestmark = pytest.mark.integration

SECRETS = {
    "alice": "alice-secret-4f0c9b2e7d",
    "bob": "bob-secret-81a3c6e0f5b2",
    "root": "root-secret-d93e1a7c40",
}
API_KEYS = f"alice:{SECRETS['alice']},bob:{SECRETS['bob']},root:{SECRETS['root']}:admin"
FOURBAR = {"inputs": {"lengths": [2, 7, 9, 6], "ground": 1}}
V1_EXECUTE = "/v1/processes/fourbar-grashof/execution"
OGC_EXECUTE = "/ogc/processes/fourbar-grashof/execution"


@pytest.fixture(scope="module", params=["embedded", "celery-redis"])
def keyed(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Deployment]:
    env = {"DEXLAB_API_KEYS": API_KEYS}
    with deployment(str(request.param), tmp_path_factory.mktemp("keys"), env=env) as dep:
        yield dep


def client(dep: Deployment, secret: str | None) -> httpx.Client:
    headers = {"Authorization": f"Bearer {secret}"} if secret is not None else {}
    return httpx.Client(base_url=dep.base_url, headers=headers, timeout=30.0)


@pytest.fixture(scope="module")
def clients(keyed: Deployment) -> Iterator[dict[str, httpx.Client]]:
    made = {name: client(keyed, secret) for name, secret in SECRETS.items()}
    yield made
    for c in made.values():
        c.close()


def submit(c: httpx.Client, via: str = "v1", **headers: str) -> str:
    if via == "v1":
        r = c.post(V1_EXECUTE, json=FOURBAR, headers=headers)
    else:
        r = c.post(OGC_EXECUTE, json=FOURBAR, headers={"Prefer": "respond-async", **headers})
    assert r.status_code == 201, r.text
    return str(r.json()["jobID"])


def store_option(dep: Deployment) -> list[str]:
    url = dep.env.get("DEXLAB_STORE_URL")
    return ["--store-url", url] if url else ["--data-dir", str(dep.data_dir)]


def dexlab(dep: Deployment, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*dexlab_command(), *args, *store_option(dep)],
        capture_output=True, text=True, timeout=60,
    )  # fmt: skip


def assert_unauthorized(r: httpx.Response, invalid: bool) -> None:
    assert r.status_code == 401, (r.request.url, r.status_code, r.text)
    if r.request.url.params.get("f") == "html":  # the problem as a page, to log in from
        assert r.headers["content-type"].startswith("text/html") and "/login?next=" in r.text
    else:
        assert r.headers["content-type"].startswith("application/problem+json")
        assert r.json()["type"] == "/problems/unauthorized"
    challenge = r.headers["www-authenticate"]
    assert challenge.startswith("Bearer") and ('error="invalid_token"' in challenge) == invalid


def job_routes(job_id: str, artifact: str) -> list[tuple[str, str]]:
    return [
        ("GET", f"/v1/jobs/{job_id}"),
        ("GET", f"/v1/jobs/{job_id}?f=html"),
        ("GET", f"/v1/jobs/{job_id}/results"),
        ("GET", f"/v1/jobs/{job_id}/results/{artifact}"),
        ("GET", f"/v1/jobs/{job_id}/events"),
        ("GET", f"/ogc/jobs/{job_id}"),
        ("GET", f"/ogc/jobs/{job_id}?f=html"),
        ("GET", f"/ogc/jobs/{job_id}/results"),
        ("GET", f"/ogc/jobs/{job_id}/results/classification"),
        ("DELETE", f"/ogc/jobs/{job_id}"),
        ("DELETE", f"/v1/jobs/{job_id}"),
    ]


def test_public_routes_answer_without_a_key(keyed: Deployment) -> None:
    with client(keyed, None) as anonymous:
        for path in (
            "/", "/v1", "/v1/processes", "/v1/processes/fourbar-grashof", "/health/live",
            "/health/ready", "/openapi.json", "/docs", "/redoc", "/methods",
            "/problems/unauthorized", "/ogc/", "/ogc/conformance", "/ogc/processes",
            "/ogc/processes/fourbar-grashof", "/login", "/static/pages/pages.css",
        ):  # fmt: skip
            r = anonymous.get(path)
            assert r.status_code == 200, (path, r.status_code, r.text[:200])
        assert anonymous.get("/metrics").status_code != 401
        page = anonymous.get("/v1/processes", headers={"Accept": "text/html"}).text
        assert 'href="/login' in page and "Signed in as" not in page


def test_no_key_a_wrong_key_and_a_revoked_key_are_401(
    keyed: Deployment, clients: dict[str, httpx.Client]
) -> None:
    job_id = submit(clients["alice"])
    routes = [*job_routes(job_id, "fourbar_motion.png"), ("GET", "/v1/jobs"),
              ("GET", "/ogc/jobs"), ("POST", V1_EXECUTE), ("POST", OGC_EXECUTE)]  # fmt: skip
    made = dexlab(keyed, "keys", "create", "carol")
    assert made.returncode == 0, made.stderr
    carol_secret = made.stdout.strip().splitlines()[-1]
    with (
        client(keyed, None) as nobody,
        client(keyed, "not-a-key-at-all-000") as wrong,
        client(keyed, carol_secret) as carol,
    ):
        for method, path in routes:
            body = FOURBAR if method == "POST" else None
            assert_unauthorized(nobody.request(method, path, json=body), invalid=False)
            assert_unauthorized(wrong.request(method, path, json=body), invalid=True)
        assert carol.get("/v1/jobs").status_code == 200
        revoked = dexlab(keyed, "keys", "revoke", "carol")
        assert revoked.returncode == 0, revoked.stderr
        time.sleep(1.1)  # the key cache is at most a second old
        for method, path in routes:
            body = FOURBAR if method == "POST" else None
            assert_unauthorized(carol.request(method, path, json=body), invalid=True)
    assert clients["alice"].get(f"/v1/jobs/{job_id}").status_code == 200


def test_a_key_made_by_the_cli_works_at_once(keyed: Deployment) -> None:
    made = dexlab(keyed, "keys", "create", "dora")
    assert made.returncode == 0, made.stderr
    secret = made.stdout.strip().splitlines()[-1]
    with client(keyed, secret) as dora:
        r = dora.get("/v1/jobs")  # the first request: an unknown key is looked up afresh
        assert r.status_code == 200, r.text
        assert r.json()["jobs"] == []
        job_id = submit(dora)
        assert [j["jobID"] for j in dora.get("/v1/jobs").json()["jobs"]] == [job_id]
    listed = dexlab(keyed, "keys", "list")
    assert listed.returncode == 0 and "dora" in listed.stdout and secret not in listed.stdout


def test_each_key_sees_and_dismisses_only_its_own_jobs(
    keyed: Deployment, clients: dict[str, httpx.Client]
) -> None:
    alice, bob = clients["alice"], clients["bob"]
    mine = {"alice": [submit(alice), submit(alice, "ogc")], "bob": [submit(bob, "ogc")]}
    for name, c in (("alice", alice), ("bob", bob)):
        for job_id in mine[name]:
            assert wait_terminal(c, job_id)["status"] == "successful"
        listed = {j["jobID"] for j in c.get("/v1/jobs", params={"limit": 1000}).json()["jobs"]}
        ogc = {j["jobID"] for j in c.get("/ogc/jobs", params={"limit": 1000}).json()["jobs"]}
        assert set(mine[name]) <= listed and listed == ogc
        other = "bob" if name == "alice" else "alice"
        assert not listed & set(mine[other])
    artifact = alice.get(f"/v1/jobs/{mine['alice'][0]}/results").json()["artifacts"][0]["name"]
    for job_id in mine["alice"]:
        for method, path in job_routes(job_id, artifact):
            r = bob.request(method, path)
            assert r.status_code == 404, (method, path, r.status_code, r.text[:200])
        r = bob.post(f"/pages/jobs/{job_id}/dismiss", headers={"Origin": keyed.base_url})
        assert r.status_code == 404, r.text
        assert alice.get(f"/v1/jobs/{job_id}").json()["status"] == "successful"
        assert alice.get(f"/v1/jobs/{job_id}/results/{artifact}").status_code == 200
    assert alice.delete(f"/v1/jobs/{mine['alice'][0]}").json()["status"] == "dismissed"
    assert alice.delete(f"/ogc/jobs/{mine['alice'][1]}").json()["status"] == "dismissed"
    assert bob.get(f"/ogc/jobs/{mine['bob'][0]}").json()["status"] == "successful"


def test_an_admin_sees_every_owner_and_filters_by_owner(
    clients: dict[str, httpx.Client],
) -> None:
    alice, bob, root = clients["alice"], clients["bob"], clients["root"]
    # bob's job computed afresh (Cache-Control: no-cache), so a worker ran it
    a, b = submit(alice), submit(bob, **{"Cache-Control": "no-cache"})
    wait_terminal(root, b)
    everything = {j["jobID"]: j for j in root.get("/v1/jobs?limit=1000").json()["jobs"]}
    assert {a, b} <= set(everything)
    assert everything[a]["owner"] == "alice" and everything[b]["owner"] == "bob"
    assert everything[b]["worker_id"]  # admins see the worker, with keys on
    own = alice.get(f"/v1/jobs/{a}").json()
    assert "worker_id" not in own and "owner" not in own
    for path in ("/v1/jobs", "/ogc/jobs"):
        only = root.get(path, params={"owner": "bob", "limit": 1000}).json()["jobs"]
        assert {j["jobID"] for j in only} >= {b} and a not in {j["jobID"] for j in only}
        refused = alice.get(path, params={"owner": "bob"})
        assert refused.status_code == 403 and refused.json()["type"] == "/problems/forbidden"
    assert root.get(f"/ogc/jobs/{a}").status_code == 200
    assert root.delete(f"/v1/jobs/{b}").json()["status"] == "dismissed"
    assert bob.get(f"/v1/jobs/{b}").json()["status"] == "dismissed"


def test_idempotency_keys_are_scoped_per_owner(clients: dict[str, httpx.Client]) -> None:
    alice, bob = clients["alice"], clients["bob"]
    key = {"Idempotency-Key": f"shared-{time.time_ns()}"}
    first = submit(alice, **key)
    replay = alice.post(V1_EXECUTE, json=FOURBAR, headers=key)
    assert replay.headers.get("idempotent-replayed") == "true"
    assert replay.json()["jobID"] == first
    other = bob.post(V1_EXECUTE, json=FOURBAR, headers=key)
    assert other.status_code == 201 and "idempotent-replayed" not in other.headers
    assert other.json()["jobID"] != first
    ogc = bob.post(OGC_EXECUTE, json=FOURBAR, headers={**key, "Prefer": "respond-async"})
    assert ogc.json()["jobID"] == other.json()["jobID"]


def _store_text(dep: Deployment) -> bytes:
    """Every byte the store holds: the SQLite files, or every row of the schema."""
    url = dep.env.get("DEXLAB_STORE_URL")
    if url is None:
        files = (p for p in Path(dep.data_dir).glob("jobs.db*") if p.is_file())
        return b"".join(p.read_bytes() for p in files)
    import psycopg

    rows: list[Any] = []
    with psycopg.connect(url) as conn:
        tables = conn.execute(
            "SELECT table_name FROM information_schema.tables WHERE table_schema = current_schema()"
        ).fetchall()
        for (table,) in tables:
            rows.extend(conn.execute(f'SELECT * FROM "{table}"').fetchall())
    return repr(rows).encode()


def test_secrets_never_reach_the_store_the_logs_or_a_response(
    keyed: Deployment, clients: dict[str, httpx.Client]
) -> None:
    answers = []
    for c in clients.values():
        for path in ("/v1/jobs", "/ogc/jobs", "/login", "/v1/jobs?f=html", "/openapi.json"):
            r = c.get(path)
            answers.append(repr(r.headers).encode() + r.content)
    stored, logs = (
        _store_text(keyed),
        b"".join(p.read_bytes() for p in Path(keyed.data_dir).glob("*.log")),
    )
    assert b"alice" in stored and logs  # the scan looks at the right things
    for secret in SECRETS.values():
        for where, text in (("store", stored), ("logs", logs), ("responses", b"".join(answers))):
            assert secret.encode() not in text, f"a key secret is in the {where}"
