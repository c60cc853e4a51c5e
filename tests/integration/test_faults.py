"""Real servers under real faults: kills, freezes, a locked or unreachable store, a full
disk, a corrupted store, heavy downloads and bodies, many waiters, racing submits.

Every test drives real `dexlab serve` / `dexlab worker` processes (or, for the pool's
back-off, a real :class:`worker.pool.WorkerPool` with real children) and real signals,
and asserts what a client sees and what the store keeps.  The fault table of
docs/reliability.md is the contract.
"""

from __future__ import annotations

import asyncio
import hashlib
import itertools
import logging
import os
import random
import select
import signal
import socket
import sqlite3
import subprocess
import threading
import time
import uuid
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from contextlib import ExitStack, contextmanager, suppress
from pathlib import Path
from typing import Any, TypeVar

import httpx
import pytest

from tests.integration.servers import (
    BACKENDS,
    TERMINAL,
    Deployment,
    deployment,
    wait_for,
    wait_terminal,
)
from tests.integration.test_server import (
    LEASE_S,
    MAP_URL,
    PAPER_LIMITS,
    TINY_MAP,
    alive,
    group_pids,
    long_job,
    pid_of,
    running_with_progress,
    wait_dead,
)
from tests.services import POSTGRES_URL, postgres_schema, require_packages, unavailable
from worker.contract import Artifact
from worker.pool import WorkerPool
from worker.settings import WorkerSettings
from worker.store import NewJob, open_store
from worker.store.sqlite import SqliteJobStore

pytestmark = [pytest.mark.integration, pytest.mark.slow]

FOURBAR_URL = "/v1/processes/fourbar-grashof/execution"
MiB = 1 << 20
T = TypeVar("T")


def small_map(tag: int) -> dict[str, Any]:
    """A joint-limited map of about a second, without plots."""
    return {
        "links": [15, 14, 8 + tag * 1e-3],
        "joint_limits_deg": PAPER_LIMITS,
        "grid": {"points_per_axis": 261},
        "orientation_step_deg": 1,
        "method": "orientation-sampling",
        "plots": False,
    }


#: A map whose CSV (~18 MB) and NPZ (~2 MB) take a second to compute.
BIG_DATA_MAP = {"links": [15, 14, 8], "grid": {"points_per_axis": 601}, "plots": False}


def poll(condition: Callable[[], Any], timeout: float, what: str, interval: float = 0.1) -> Any:
    """Call ``condition`` until it returns something truthy; that value."""
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout:g} s waiting for {what}")
        time.sleep(interval)


def store_url_of(dep: Deployment) -> str:
    return dep.env.get("DEXLAB_STORE_URL") or f"sqlite:///{(dep.data_dir / 'jobs.db').resolve()}"


def jobs_by_id(client: httpx.Client, process_id: str) -> dict[str, dict[str, Any]]:
    """Every job of one process, by ID (one listing request)."""
    r = client.get("/v1/jobs", params={"processID": process_id, "limit": 1000})
    assert r.status_code == 200, r.text
    return {doc["jobID"]: doc for doc in r.json()["jobs"]}


def deployment_pids(dep: Deployment) -> set[int]:
    """Every process of the deployment (each was started in its own session)."""
    leaders = [p.pid for p in (dep.api, *dep.workers) if p is not None]
    return {pid for leader in leaders for pid in group_pids(leader)}


def full_log(dep: Deployment) -> str:
    """Every log line of the deployment's processes (``Deployment.log`` keeps tails)."""
    return "\n".join(p.read_text(errors="replace") for p in sorted(dep.data_dir.glob("*.log")))


@contextmanager
def fault_deployment(
    backend: str, tmp_path: Path, **options: Any
) -> Iterator[tuple[Deployment, str | None]]:
    """:func:`deployment`; on PostgreSQL every store connection of it carries a unique
    ``application_name`` (returned as the tag), so a test can find exactly its
    connections in ``pg_stat_activity``."""
    if backend == "embedded":
        with deployment(backend, tmp_path, **options) as dep:
            yield dep, None
        return
    with ExitStack() as stack:
        url = stack.enter_context(postgres_schema())
        tag = f"dexlab-faults-{uuid.uuid4().hex[:10]}"
        env = {**options.pop("env", {}), "DEXLAB_STORE_URL": f"{url}&application_name={tag}"}
        yield stack.enter_context(deployment(backend, tmp_path, env=env, **options)), tag


def proc_state(pid: int) -> str:
    """The state letter of /proc/PID/stat (R, S, T: stopped, Z...); "" when gone."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0]
    except (FileNotFoundError, ProcessLookupError, IndexError):
        return ""


def freeze(pid: int) -> None:
    """SIGSTOP a process and wait until it is stopped."""
    os.kill(pid, signal.SIGSTOP)
    poll(lambda: proc_state(pid) in ("T", "t", "Z", ""), 5, f"process {pid} to stop", 0.005)


def freeze_a_running_job(dep: Deployment, process_id: str) -> tuple[str, int]:
    """SIGSTOP a process of the deployment while it runs a job: ``(job ID, pid)``."""
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        ours = deployment_pids(dep)
        running = [
            d
            for d in jobs_by_id(dep.client, process_id).values()
            if d["status"] == "running" and pid_of(d) in ours
        ]
        if not running:
            time.sleep(0.05)
            continue
        job_id, pid = running[0]["jobID"], pid_of(running[0])
        freeze(pid)
        doc = dep.client.get(f"/v1/jobs/{job_id}").json()
        if doc["status"] == "running" and pid_of(doc) == pid:  # frozen mid-job
            return job_id, pid
        os.kill(pid, signal.SIGCONT)  # it finished that job just before: try again
    raise AssertionError("no job ran long enough to be frozen")


def chunk_writes_in_flight(tag: str) -> int:
    import psycopg

    with psycopg.connect(POSTGRES_URL, autocommit=True) as conn:
        row = conn.execute(
            "SELECT count(*) FROM pg_stat_activity WHERE application_name = %s "
            "AND state = 'active' AND query LIKE 'INSERT INTO artifact_chunks%%'",
            (tag,),
        ).fetchone()
    return int(row[0]) if row else 0


def wait_stale_attempt_settled(dep: Deployment, tag: str | None, job_id: str, pid: int) -> None:
    """After a frozen process resumed (or was killed): wait until it gave its stale
    attempt of ``job_id`` up (it exited, or discarded its result) and no chunk write
    of the deployment is in flight, so what the store keeps now is final."""
    gave_up = (f"job {job_id} is no longer ours", f"job {job_id}: result discarded")
    poll(
        lambda: not alive(pid) or any(m in full_log(dep) for m in gave_up),
        15,
        f"process {pid} to give up its attempt of job {job_id}",
    )
    if tag is not None:
        poll(lambda: chunk_writes_in_flight(tag) == 0, 10, "chunk writes to end")


def rss_bytes(pid: int) -> int:
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    raise AssertionError(f"no VmRSS for process {pid}")


class RssPeak(threading.Thread):
    """Samples one process's resident memory every few milliseconds; ``peak``."""

    def __init__(self, pid: int, interval_s: float = 0.01) -> None:
        super().__init__(name=f"rss-{pid}", daemon=True)
        self.pid = pid
        self.interval_s = interval_s
        self.baseline = rss_bytes(pid)
        self.peak = self.baseline
        self._done = threading.Event()

    def run(self) -> None:
        while not self._done.wait(self.interval_s):
            self.peak = max(self.peak, rss_bytes(self.pid))

    @property
    def growth_mb(self) -> float:
        return (self.peak - self.baseline) / 1e6

    def __enter__(self) -> RssPeak:
        self.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._done.set()
        self.join()
        self.peak = max(self.peak, rss_bytes(self.pid))


class DeathWatch(threading.Thread):
    """Notes how long after its start a process died (``after_s``; None: alive)."""

    def __init__(self, pid: int) -> None:
        super().__init__(name=f"death-{pid}", daemon=True)
        self.pid = pid
        self.started_at = time.monotonic()
        self.after_s: float | None = None
        self._done = threading.Event()
        self.start()

    def run(self) -> None:
        while not self._check() and not self._done.wait(0.05):
            pass

    def _check(self) -> bool:
        if self.after_s is None and not alive(self.pid):
            self.after_s = time.monotonic() - self.started_at
        return self.after_s is not None

    def stop(self) -> None:
        self._done.set()
        self.join()
        self._check()


# -- 1. chaos ---------------------------------------------------------------------------


def attempt_folders(data_dir: Path, job_id: str) -> list[str]:
    """The attempts of a job whose artifact files are on disk (embedded store)."""
    folder = data_dir / "artifacts" / job_id
    return sorted(p.name for p in folder.iterdir()) if folder.is_dir() else []


def attempts_in_postgres(store_url: str) -> tuple[dict[str, set[int]], dict[str, set[int]]]:
    """``(chunk attempts, index attempts)`` per job, in the deployment's schema."""
    import psycopg

    with psycopg.connect(store_url) as conn:
        chunks = conn.execute("SELECT DISTINCT job_id, attempt FROM artifact_chunks").fetchall()
        index = conn.execute("SELECT DISTINCT job_id, attempt FROM artifact_index").fetchall()
    by_job: tuple[dict[str, set[int]], dict[str, set[int]]] = ({}, {})
    for table, rows in zip(by_job, (chunks, index), strict=True):
        for job_id, attempt in rows:
            table.setdefault(job_id, set()).add(int(attempt))
    return by_job


def stored_results_problems(dep: Deployment, finals: dict[str, dict[str, Any]]) -> list[str]:
    """Where the store keeps anything but the committed attempt's results."""
    problems = []
    if dep.backend == "embedded":
        for job_id, doc in finals.items():
            folders = attempt_folders(dep.data_dir, job_id)
            want = [str(doc["attempts"])] if doc["status"] == "successful" else []
            if folders != want:
                problems.append(f"{job_id} ({doc['status']}): attempt folders {folders}")
        return problems
    chunks, index = attempts_in_postgres(dep.env["DEXLAB_STORE_URL"])
    for job_id, doc in finals.items():
        expected: set[int] = {doc["attempts"]} if doc["status"] == "successful" else set()
        stored = (chunks.get(job_id, set()), index.get(job_id, set()))
        if stored != (expected, expected):
            problems.append(f"{job_id} ({doc['status']}): chunk/index attempts {stored}")
    return problems


@pytest.mark.parametrize("backend", ["embedded", "celery-redis"])
def test_chaos_loses_no_job_and_stores_each_result_once(backend: str, tmp_path: Path) -> None:
    """36 small jobs while a worker process is SIGKILLed every two seconds and another is
    SIGSTOPped past its lease: every job ends successful (or worker-lost after all its
    attempts), and each result is stored once, from the attempt that committed."""
    with fault_deployment(backend, tmp_path, workers=3) as (dep, tag):
        client = dep.client
        process_id = "planar3r-dexterity-map"
        ids = []
        for n in range(36):
            r = client.post(MAP_URL, json={"inputs": small_map(n)})
            assert r.status_code == 201, r.text
            ids.append(r.json()["jobID"])
        frozen_job, frozen_pid = freeze_a_running_job(dep, process_id)
        frozen = DeathWatch(frozen_pid)
        kills: list[int] = []
        try:
            next_kill = time.monotonic() + 2.0
            deadline = time.monotonic() + 150
            while True:
                docs = jobs_by_id(client, process_id)
                stuck = {i: docs[i]["status"] for i in ids if docs[i]["status"] not in TERMINAL}
                if not stuck:
                    break
                assert time.monotonic() < deadline, f"jobs stuck: {stuck}\n{dep.log()}"
                if time.monotonic() >= next_kill and len(kills) < 10:
                    running = {pid_of(d) for d in docs.values() if d["status"] == "running"}
                    ours = deployment_pids(dep)
                    victims = sorted(p for p in running - {frozen_pid} if p in ours and alive(p))
                    if victims:
                        victim = random.choice(victims)
                        os.kill(victim, signal.SIGKILL)
                        kills.append(victim)
                        next_kill = time.monotonic() + 2.0
                time.sleep(0.2)
        finally:
            frozen.stop()
            with suppress(ProcessLookupError):  # a frozen VM resumes: its attempt is stale
                os.kill(frozen_pid, signal.SIGCONT)
        finals = jobs_by_id(client, process_id)
        finals = {i: finals[i] for i in ids}
        assert len(kills) >= 4, f"only {len(kills)} kills happened"
        for doc in finals.values():
            if doc["status"] == "failed":
                assert doc["error"]["type"] == "worker-lost", doc
                assert doc["attempts"] == doc["max_attempts"], doc
            else:
                assert doc["status"] == "successful", doc
        successful = [d for d in finals.values() if d["status"] == "successful"]
        assert len(successful) >= 30, [d["status"] for d in finals.values()]
        assert finals[frozen_job]["attempts"] >= 2, finals[frozen_job]
        # The pool (or the Celery worker's watchdog) killed the frozen process after a lease.
        assert frozen.after_s is not None, "the frozen process was never killed"
        assert frozen.after_s < LEASE_S + 3, frozen.after_s
        assert "showed no sign of life" in full_log(dep)
        # One stored result per successful job: the committed attempt's, nothing else
        # (a job's clean-up follows its commit by a moment).
        wait_stale_attempt_settled(dep, tag, frozen_job, frozen_pid)
        try:
            poll(lambda: not stored_results_problems(dep, finals), 15, "stale attempts removed")
        except AssertionError:
            raise AssertionError("\n".join(stored_results_problems(dep, finals))) from None
        assert "Exception ignored" not in full_log(dep)  # e.g. in a forked child
        for doc in successful[:10]:
            results = client.get(f"/v1/jobs/{doc['jobID']}/results")
            assert results.status_code == 200, results.text
            names = [a["name"] for a in results.json()["artifacts"]]
            assert sorted(names) == ["dexterity_map.csv", "dexterity_map.npz"], names


# -- 2. the store held locked, or its connections cut -------------------------------------


def test_store_locked_for_20_s_mid_job(tmp_path: Path) -> None:
    """Another process holds SQLite's write lock for 20 s while a job runs: the API
    answers 503 (readiness, and a submit with Retry-After) during the lock and recovers
    after it; the job ends successful, at worst with one more attempt."""
    hold_s = 20.0
    with deployment("embedded", tmp_path, workers=2) as dep:
        client = dep.client
        job_id = client.post(MAP_URL, json={"inputs": long_job(6)}).json()["jobID"]
        wait_for(client, job_id, running_with_progress(5))
        lock = sqlite3.connect(tmp_path / "jobs.db", timeout=10, isolation_level=None)
        try:
            lock.execute("BEGIN IMMEDIATE")
            locked_at = time.monotonic()
            ready = client.get("/health/ready")
            assert ready.status_code == 503, ready.text
            assert ready.json()["store"] == "unavailable", ready.json()
            submit = client.post(MAP_URL, json={"inputs": TINY_MAP})
            assert submit.status_code == 503, submit.text
            assert submit.headers["content-type"] == "application/problem+json"
            assert submit.json()["type"] == "/problems/store-unavailable", submit.json()
            status = client.get(f"/v1/jobs/{job_id}")  # reads go on (WAL)
            assert status.status_code == 200 and status.json()["status"] == "running"
            assert time.monotonic() - locked_at < hold_s, "the 503s came after the lock"
            time.sleep(max(0.0, hold_s - (time.monotonic() - locked_at)))  # the outage
        finally:
            if lock.in_transaction:
                lock.execute("ROLLBACK")
            lock.close()
        released_at = time.monotonic()
        dep.wait_ready()
        assert time.monotonic() - released_at < 10
        after = client.post(MAP_URL, json={"inputs": TINY_MAP})
        assert after.status_code == 201, after.text
        final = wait_terminal(client, job_id, timeout=120)
        assert final["status"] == "successful", (final, dep.log())
        assert final["attempts"] in (1, 2), final
        assert wait_terminal(client, after.json()["jobID"])["status"] == "successful"
        # The refused submit told the client when to come back.
        assert int(submit.headers.get("Retry-After", "0")) > 0, dict(submit.headers)


def terminate_backends(tag: str) -> int:
    import psycopg

    with psycopg.connect(POSTGRES_URL, autocommit=True) as conn:
        rows = conn.execute(
            "SELECT pg_terminate_backend(pid) FROM pg_stat_activity "
            "WHERE application_name = %s AND pid <> pg_backend_pid()",
            (tag,),
        ).fetchall()
    return sum(1 for (done,) in rows if done)


def test_postgres_connections_cut_mid_job(tmp_path: Path) -> None:
    """PostgreSQL ends every connection of the API and the workers, three times while a
    job runs: calls reconnect and retry, the API keeps answering, the job succeeds."""
    require_packages("psycopg")
    with fault_deployment("celery-redis", tmp_path, workers=1) as (dep, tag):
        assert tag is not None
        client = dep.client
        job_id = client.post(MAP_URL, json={"inputs": long_job(7)}).json()["jobID"]
        progress = wait_for(client, job_id, running_with_progress(5))["progress"]
        for _ in range(3):
            terminated = terminate_backends(tag)
            assert terminated >= 2, f"only {terminated} connections of the deployment found"
            status = client.get(f"/v1/jobs/{job_id}")
            assert status.status_code == 200, status.text
            assert client.get("/health/ready").status_code == 200
            if status.json()["status"] == "running":  # the worker writes again
                progress = wait_for(
                    client,
                    job_id,
                    lambda d, p=progress: d["progress"] > p or d["status"] != "running",
                    timeout=30,
                )["progress"]
        submit = client.post(MAP_URL, json={"inputs": TINY_MAP})
        assert submit.status_code == 201, submit.text
        final = wait_terminal(client, job_id, timeout=180)
        assert final["status"] == "successful", (final, dep.log())
        assert wait_terminal(client, submit.json()["jobID"])["status"] == "successful"


def pause_worker_of(dep: Deployment, pid: int) -> list[int]:
    """Pause the `dexlab worker` whose pool process ``pid`` is, as a paused VM would be:
    the pool process first (it is mid-write), then the rest of it (its main process,
    whose watchdog would otherwise kill a frozen pool process); the pids paused."""
    leader = next(w.pid for w in dep.workers if pid in group_pids(w.pid))
    freeze(pid)
    rest = [p for p in group_pids(leader) if p != pid]
    for other in rest:
        freeze(other)
    return [pid, *rest]


def freeze_when_writing(
    store_url: str, writers: dict[str, int], pause: Callable[[int], object] = freeze
) -> dict[str, int]:
    """``pause`` each job's worker process as soon as the first chunk of its results is
    stored (mid-write); how many chunks each had then."""
    import psycopg

    frozen: dict[str, int] = {}
    deadline = time.monotonic() + 60
    with psycopg.connect(store_url, autocommit=True) as conn:
        while len(frozen) < len(writers):
            assert time.monotonic() < deadline, f"only {list(frozen)} started writing"
            rows = conn.execute(
                "SELECT job_id, count(*) FROM artifact_chunks WHERE job_id = ANY(%s) "
                "GROUP BY job_id",
                (list(writers),),
            ).fetchall()
            for job_id, count in rows:
                if job_id not in frozen:
                    pause(writers[job_id])
                    frozen[job_id] = int(count)
            time.sleep(0.002)
    return frozen


def test_stale_attempts_resumed_mid_write_leave_no_chunks(tmp_path: Path) -> None:
    """Two Celery workers are paused whole (a paused VM) while their pool processes write
    their results' chunks; their leases lapse and the third worker commits both jobs.
    When they resume, their stale attempts must leave nothing behind: only the committed
    attempts' chunks remain."""
    require_packages("psycopg")
    with fault_deployment("celery-redis", tmp_path, worker_processes=3) as (dep, tag):
        client = dep.client
        store_url = dep.env["DEXLAB_STORE_URL"]
        ids = [
            client.post(
                MAP_URL, json={"inputs": {**BIG_DATA_MAP, "links": [15, 14, 8 + n]}}
            ).json()["jobID"]
            for n in range(2)
        ]
        writers = {
            job_id: pid_of(wait_for(client, job_id, lambda d: d["status"] == "running"))
            for job_id in ids
        }
        assert set(writers.values()) <= deployment_pids(dep) and len(set(writers.values())) == 2
        paused: list[int] = []
        try:
            frozen = freeze_when_writing(
                store_url, writers, lambda pid: paused.extend(pause_worker_of(dep, pid))
            )
            assert all(n < 15 for n in frozen.values()), f"froze too late: {frozen} of ~20"
            for job_id in ids:
                final = wait_terminal(client, job_id, timeout=60)
                assert final["status"] == "successful" and final["attempts"] == 2, final
        finally:
            for pid in paused:
                with suppress(ProcessLookupError):
                    os.kill(pid, signal.SIGCONT)
        for job_id, pid in writers.items():
            wait_stale_attempt_settled(dep, tag, job_id, pid)
        chunks, index = attempts_in_postgres(store_url)
        committed = {job_id: {2} for job_id in ids}
        assert (chunks, index) == (committed, committed), (
            f"chunks of attempts {chunks} are stored; the index points at {index}"
        )


# -- 3. a full disk ---------------------------------------------------------------------


@contextmanager
def small_tmpfs(path: Path, size_mb: int) -> Iterator[Path]:
    path.mkdir(parents=True, exist_ok=True)
    mounted = subprocess.run(
        ["mount", "-t", "tmpfs", "-o", f"size={size_mb}m", "tmpfs", str(path)],
        capture_output=True,
        text=True,
        check=False,
    )
    if mounted.returncode != 0:
        unavailable(f"cannot mount a tmpfs (needs root): {mounted.stderr.strip()}")
    try:
        yield path
    finally:
        if subprocess.run(["umount", str(path)], capture_output=True, check=False).returncode:
            subprocess.run(["umount", "-l", str(path)], capture_output=True, check=True)


def free_bytes(path: Path) -> int:
    stats = os.statvfs(path)
    return stats.f_bavail * stats.f_frsize


def fill_disk(filler: Path, leave_free: int) -> None:
    """Write ``filler`` until only ``leave_free`` bytes are left on its disk."""
    with filler.open("wb") as f:
        while (excess := free_bytes(filler.parent) - leave_free) > 0:
            f.write(b"\xa5" * min(MiB, excess))
            f.flush()


def test_full_disk_fails_the_job_once_and_readiness_says_full(tmp_path: Path) -> None:
    """The data directory's disk has room for SQLite's small updates but not for a
    job's 20 MB of results: the job fails once with storage-full (no recompute loop),
    readiness says "full", and both recover once space is freed."""
    # Readiness wants 64 MiB free, so the disk is larger than that when empty.
    disk = tmp_path / "disk"
    with small_tmpfs(disk, 128), deployment("embedded", disk / "data", workers=1) as dep:
        client = dep.client
        filler = disk / "filler"
        fill_disk(filler, leave_free=10 * MiB)
        ready = client.get("/health/ready")
        assert ready.status_code == 503, ready.text
        assert ready.json()["store"] == "full", ready.json()
        r = client.post(MAP_URL, json={"inputs": BIG_DATA_MAP})
        assert r.status_code == 201, r.text
        job_id = r.json()["jobID"]
        final = wait_terminal(client, job_id, timeout=60)
        assert final["status"] == "failed", (final, dep.log())
        assert final["error"]["type"] == "storage-full", final
        assert final["attempts"] == 1, final
        results = client.get(f"/v1/jobs/{job_id}/results")
        assert results.headers["content-type"] == "application/problem+json"
        assert not attempt_folders(dep.data_dir, job_id)  # partial files gone
        filler.unlink()
        dep.wait_ready()
        again = client.post(MAP_URL, json={"inputs": BIG_DATA_MAP}).json()["jobID"]
        assert wait_terminal(client, again, timeout=60)["status"] == "successful"
        assert client.get(f"/v1/jobs/{job_id}").json()["attempts"] == 1
        # The failed job's results name the cause.
        assert results.json()["type"] == "/problems/storage-full", results.json()


# -- 4. a corrupted store ---------------------------------------------------------------


def test_pool_backs_off_children_that_cannot_open_the_store(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """The pool's children find garbage where the SQLite file should be: the pool
    restarts its child with growing pauses, not in a tight loop, and says why."""
    bad = tmp_path / "bad" / "jobs.db"
    bad.parent.mkdir()
    bad.write_bytes(random.Random(7).randbytes(64 * 1024))
    parent_store = SqliteJobStore(tmp_path / "good" / "jobs.db")
    parent_store.initialise()
    settings = WorkerSettings(
        workers=1,
        data_dir=tmp_path / "bad",
        store_url=f"sqlite:///{bad}",
        lease_seconds=LEASE_S,
        heartbeat_seconds=0.5,
    )
    caplog.set_level(logging.INFO, logger="dexlab.pool")

    def messages() -> list[str]:
        return [r.getMessage() for r in caplog.records if r.name == "dexlab.pool"]

    def pauses() -> list[float]:
        return [float(m.rsplit("next start in ", 1)[1].split()[0])
                for m in messages() if "next start in" in m]  # fmt: skip

    pool = WorkerPool(settings, parent_store)
    pool.start()
    started = time.monotonic()
    try:  # until three backed-off restarts (however slowly a child dies on a busy machine)
        while len(pauses()) < 3 and time.monotonic() - started < 90.0:
            time.sleep(0.2)
    finally:
        pool.stop()
        parent_store.close()
    elapsed = time.monotonic() - started
    log = "\n".join(messages())
    assert pauses()[:3] == [0.5, 1.0, 2.0], log  # growing pauses, not a tight loop
    assert all("could not start" in m for m in messages() if "next start in" in m), log
    starts = [m for m in messages() if m.startswith("started worker process")]
    assert len(starts) <= 5 + elapsed / 2.0, f"{len(starts)} starts in {elapsed:.1f} s:\n{log}"


# -- 5. a frozen worker -----------------------------------------------------------------


def test_frozen_pool_process_is_killed_and_its_job_retried(tmp_path: Path) -> None:
    """SIGSTOP the pool process running a job: the other process keeps working, the
    pool kills the frozen one after a lease without a sign of life, and the job is
    retried to success."""
    with deployment("embedded", tmp_path, workers=2) as dep:
        client = dep.client
        job_id = client.post(MAP_URL, json={"inputs": long_job(5)}).json()["jobID"]
        victim = pid_of(wait_for(client, job_id, running_with_progress(5)))
        assert victim in deployment_pids(dep)
        freeze(victim)
        death = DeathWatch(victim)
        try:
            other = client.post(MAP_URL, json={"inputs": small_map(1)}).json()["jobID"]
            done = wait_terminal(client, other, timeout=LEASE_S + 8)
            assert done["status"] == "successful" and pid_of(done) != victim, done
            wait_dead(victim, timeout=LEASE_S + 6)
        finally:
            death.stop()
            with suppress(ProcessLookupError):
                os.kill(victim, signal.SIGCONT)
        assert death.after_s is not None and LEASE_S - 1 < death.after_s < LEASE_S + 3, (
            death.after_s
        )
        final = wait_terminal(client, job_id, timeout=120)
        assert final["status"] == "successful", (final, dep.log())
        assert final["attempts"] == 2 and pid_of(final) != victim, final
        assert "showed no sign of life" in full_log(dep)


# -- 6. heavy downloads and bodies ------------------------------------------------------


def download(base_url: str, href: str) -> tuple[int, str, str]:
    """Stream one artifact, keeping nothing: ``(size, sha256, ETag)``."""
    digest = hashlib.sha256()
    size = 0
    with httpx.Client(base_url=base_url, timeout=120) as c, c.stream("GET", href) as r:
        assert r.status_code == 200, r.read()
        etag = r.headers["etag"]
        for chunk in r.iter_bytes():
            digest.update(chunk)
            size += len(chunk)
    return size, digest.hexdigest(), etag


@pytest.mark.parametrize("backend", ["embedded", "celery-redis"])
def test_big_artifact_streams_to_five_clients_in_bounded_memory(
    backend: str, tmp_path: Path
) -> None:
    """A 200 MiB artifact (files on disk, or 1 MiB chunk rows in PostgreSQL) downloads
    intact to five clients at once while the API process grows by < 100 MB."""
    size = 200 * MiB
    with deployment(backend, tmp_path, workers=0) as dep:
        store = open_store(store_url_of(dep))
        try:
            job, _ = store.create_job(
                NewJob("fourbar-grashof", {"lengths": [30, 17, 18, 25], "ground": 0}, 60.0, 1)
            )
            claim = store.claim_next("fault-test:1", 600)
            assert claim is not None and claim.job.job_id == job.job_id
            data = os.urandom(MiB) * (size // MiB)
            expected = hashlib.sha256(data).hexdigest()
            big = Artifact("big.csv", "text/csv", data)
            assert store.complete(job.job_id, claim.lease_token, {"x": 1}, [big])
            del data, big
        finally:
            store.close()
        assert dep.api is not None
        href = f"/v1/jobs/{job.job_id}/results/big.csv"
        with RssPeak(dep.api.pid) as rss, ThreadPoolExecutor(5) as pool:
            downloads = list(pool.map(lambda _: download(dep.base_url, href), range(5)))
        for got_size, digest, etag in downloads:
            assert got_size == size
            assert digest == expected and etag == f'"{expected}"'
        assert rss.growth_mb < 100, f"the API grew by {rss.growth_mb:.0f} MB"


def json_body_frames(size: int, chunked: bool) -> Iterator[bytes]:
    """A ``size``-byte JSON body in 64 KiB pieces (chunked transfer coding if asked)."""
    prefix, suffix = b'{"inputs": {"lengths": "', b'"}}'
    piece = b"a" * (64 * 1024)
    filler = size - len(prefix) - len(suffix)
    middle = (piece[: filler - at] for at in range(0, filler, len(piece)))
    for data in itertools.chain([prefix], middle, [suffix]):
        yield b"%x\r\n%s\r\n" % (len(data), data) if chunked else data
    if chunked:
        yield b"0\r\n\r\n"


def read_response(sock: socket.socket) -> bytes:
    """What the server sent until it closed or its response was complete."""
    response = b""
    with suppress(ConnectionResetError, TimeoutError):
        while True:
            head, sep, body = response.partition(b"\r\n\r\n")
            if sep and len(body) >= content_length(head):
                break
            chunk = sock.recv(65536)
            if not chunk:
                break
            response += chunk
    return response


def content_length(head: bytes) -> int:
    for line in head.split(b"\r\n")[1:]:
        name, _, value = line.partition(b":")
        if name.strip().lower() == b"content-length":
            return int(value)
    return 1 << 62  # read until the server closes


def post_large_body(port: int, path: str, size: int, chunked: bool) -> tuple[int | None, bytes]:
    """Send a ``size``-byte JSON body as a client would, but stop sending as soon as
    the server answers (or closes); ``(status, body)`` of its answer (None: none)."""
    head = f"POST {path} HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
    head += "Transfer-Encoding: chunked\r\n\r\n" if chunked else f"Content-Length: {size}\r\n\r\n"
    with socket.create_connection(("127.0.0.1", port), timeout=30) as sock:
        sock.sendall(head.encode())
        pending = b""
        for frame in json_body_frames(size, chunked):
            pending = frame
            while pending:
                readable, writable, _ = select.select([sock], [sock], [], 30)
                assert readable or writable, "the server neither reads the body nor answers"
                if readable:  # an early answer: stop sending
                    break
                try:
                    pending = pending[sock.send(pending) :]
                except (BrokenPipeError, ConnectionResetError):
                    break
            if pending:
                break
        response = read_response(sock)
    if not response.startswith(b"HTTP/1.1 "):
        return None, response
    head_part, _, body = response.partition(b"\r\n\r\n")
    return int(head_part.split()[1]), body


def test_large_request_bodies_are_refused_in_bounded_memory(tmp_path: Path) -> None:
    """Four concurrent 50 MB submits (two with Content-Length, two chunked) are refused
    with 413 while the API process grows by < 100 MB."""
    with deployment("embedded", tmp_path, workers=0) as dep:
        assert dep.api is not None
        port = int(dep.base_url.rsplit(":", 1)[1])
        with RssPeak(dep.api.pid) as rss, ThreadPoolExecutor(4) as pool:
            answers = list(
                pool.map(
                    lambda chunked: post_large_body(port, FOURBAR_URL, 50 * 1000**2, chunked),
                    [False, False, True, True],
                )
            )
        for status, body in answers:
            assert status == 413, (status, body[:300])
            assert b"/problems/request-too-large" in body, body[:300]
        assert rss.growth_mb < 100, f"the API grew by {rss.growth_mb:.0f} MB"
        assert dep.client.get("/health/live").status_code == 200


# -- 7. waiting holds no thread ---------------------------------------------------------


def latencies(client: httpx.Client, path: str, times: int = 5) -> list[float]:
    result = []
    for _ in range(times):
        started = time.perf_counter()
        r = client.get(path)
        result.append(time.perf_counter() - started)
        assert r.status_code == 200, r.text
    return result


LONG_NO_PLOTS = {**long_job(8), "grid": {"points_per_axis": 1001}, "plots": False}


def start_long_job(dep: Deployment) -> str:
    """A job that keeps the one-process pool busy for about 20 s (running on return)."""
    long_id = str(dep.client.post(MAP_URL, json={"inputs": LONG_NO_PLOTS}).json()["jobID"])
    wait_for(dep.client, long_id, lambda d: d["status"] == "running")
    return long_id


async def hold_waiters(dep: Deployment, count: int, while_waiting: Callable[[], T]) -> T:
    """Open ``count`` ``Prefer: wait=60`` submits (queued behind a busy pool), run
    ``while_waiting`` (in a thread) once they all wait, then drop them: the client
    closes their connections."""
    limits = httpx.Limits(max_connections=count + 10, max_keepalive_connections=count + 10)
    async with httpx.AsyncClient(base_url=dep.base_url, limits=limits, timeout=90) as waiters:
        tasks = [
            asyncio.create_task(
                waiters.post(
                    FOURBAR_URL,
                    json={"inputs": {"lengths": [30, 17, 18, 25 + n * 1e-3], "ground": 0}},
                    headers={"Prefer": "wait=60"},
                )
            )
            for n in range(count)
        ]

        def queued() -> bool:
            docs = jobs_by_id(dep.client, "fourbar-grashof").values()
            return sum(1 for d in docs if d["status"] == "accepted") == count

        def then() -> T:
            poll(queued, 60, f"{count} waiting submits to be queued", interval=0.2)
            return while_waiting()

        try:
            outcome = await asyncio.to_thread(then)
            done = [t for t in tasks if t.done()]
            assert not done, f"{len(done)} waits ended early: {done[0]}"
        finally:
            for task in tasks:
                task.cancel()
            await asyncio.gather(*tasks, return_exceptions=True)
    return outcome


def test_waiting_submits_hold_no_thread(tmp_path: Path) -> None:
    """200 submits wait (Prefer: wait=60) behind a long job: the API still answers its
    liveness probe and a threadpool route in well under 100 ms."""
    with deployment("embedded", tmp_path, workers=1) as dep:
        client = dep.client
        long_id = start_long_job(dep)
        paths = ("/health/live", f"/v1/jobs/{long_id}")
        measured = asyncio.run(
            hold_waiters(dep, 200, lambda: {path: latencies(client, path) for path in paths})
        )
        for path, seconds in measured.items():
            assert sorted(seconds)[len(seconds) // 2] < 0.1, (path, seconds)
            assert max(seconds) < 0.5, (path, seconds)
        # Finish the abandoned waits (see the next test), so the API stops at once.
        assert client.get(f"/v1/jobs/{long_id}").json()["status"] == "running"
        for job_id in jobs_by_id(client, "fourbar-grashof"):
            client.delete(f"/v1/jobs/{job_id}")
        client.delete(f"/v1/jobs/{long_id}")


def test_abandoned_waits_do_not_hold_up_shutdown(tmp_path: Path) -> None:
    """Clients that gave up their Prefer: wait submits leave nothing behind: the API
    stops on SIGTERM as promptly as without them (the pool's grace for a running job,
    5 s), not once their 60 s waits have run out."""
    with deployment("embedded", tmp_path, workers=1) as dep:
        start_long_job(dep)
        asyncio.run(hold_waiters(dep, 20, lambda: None))
        assert dep.api is not None
        stopping_at = time.monotonic()
        dep.api.send_signal(signal.SIGTERM)
        with suppress(subprocess.TimeoutExpired):
            dep.api.wait(timeout=12)
        took = time.monotonic() - stopping_at
        stopped = dep.api.returncode
        if stopped is None:
            dep.kill_api()
        tail = (dep.data_dir / "api.log").read_text(errors="replace")[-400:]
        # uvicorn re-raises the SIGTERM it handled once it has shut down cleanly.
        assert stopped in (0, -signal.SIGTERM) and took < 10, (
            f"stopping took {took:.1f} s ({stopped}):\n{tail}"
        )
        assert "Application shutdown complete" in tail, tail


# -- 8. idempotent submits race ---------------------------------------------------------


@pytest.mark.parametrize("backend", BACKENDS)
def test_concurrent_idempotent_submits_make_one_job(backend: str, tmp_path: Path) -> None:
    """20 simultaneous submits with one Idempotency-Key and body: one job, one 201
    without Idempotent-Replayed, and every response names it; 2 and 2.0 are one body."""
    with deployment(backend, tmp_path, workers=0) as dep:
        key = f"race-{uuid.uuid4()}"
        body = {"inputs": {"lengths": [30, 17, 18, 25], "ground": 0}}
        start = threading.Barrier(20)

        def submit(_: int) -> httpx.Response:
            with httpx.Client(base_url=dep.base_url, timeout=60) as c:
                start.wait()
                return c.post(FOURBAR_URL, json=body, headers={"Idempotency-Key": key})

        with ThreadPoolExecutor(20) as pool:
            responses = list(pool.map(submit, range(20)))
        assert all(r.status_code in (200, 201) for r in responses), [
            (r.status_code, r.text[:200]) for r in responses
        ]
        assert len({r.json()["jobID"] for r in responses}) == 1, [r.json() for r in responses]
        fresh = [r for r in responses if r.headers.get("Idempotent-Replayed") != "true"]
        assert len(fresh) == 1 and fresh[0].status_code == 201, [
            (r.status_code, dict(r.headers)) for r in responses
        ]

        key2 = f"numbers-{uuid.uuid4()}"
        ints = {"inputs": {"lengths": [2, 3, 3, 4], "ground": 0}}
        floats = {"inputs": {"ground": 0, "lengths": [2.0, 3.0, 3, 4.0]}}
        one = dep.client.post(FOURBAR_URL, json=ints, headers={"Idempotency-Key": key2})
        two = dep.client.post(FOURBAR_URL, json=floats, headers={"Idempotency-Key": key2})
        assert one.status_code == 201, one.text
        assert two.status_code in (200, 201), two.text
        assert two.json()["jobID"] == one.json()["jobID"]
        assert two.headers.get("Idempotent-Replayed") == "true"
