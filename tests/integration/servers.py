"""Real deployments for integration tests, on either backend.

- ``embedded``: `dexlab serve` with its local pool on SQLite (or `dexlab worker`
  processes against the same SQLite file);
- ``celery-redis`` / ``celery-rabbitmq``: `dexlab serve` (API only) and `dexlab worker`
  Celery workers, on a private PostgreSQL schema and a private broker queue.
"""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
import uuid
from collections.abc import Iterator
from contextlib import ExitStack, contextmanager, suppress
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx

from tests.services import AMQP_URL, REDIS_URL, postgres_schema, require_broker

TERMINAL = {"successful", "failed", "dismissed"}
BACKENDS = ("embedded", "celery-redis", "celery-rabbitmq")

#: Short leases and heartbeats keep the fault tests quick; documented defaults are
#: 15 s and 2 s.
FAST_ENV = {
    "DEXLAB_HEARTBEAT_SECONDS": "0.5",
    "DEXLAB_LEASE_SECONDS": "4",
    "DEXLAB_SWEEP_SECONDS": "0.5",
}


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def dexlab_command() -> list[str]:
    script = Path(sys.executable).parent / "dexlab"
    return [str(script)] if script.exists() else [sys.executable, "-m", "service"]


def kill_group(process: subprocess.Popen[bytes], sig: int = signal.SIGKILL) -> None:
    """Signal a process started with its own session, and every process in it."""
    with suppress(ProcessLookupError):
        os.killpg(process.pid, sig)


def stop_process(process: subprocess.Popen[bytes], timeout: float = 20) -> None:
    if process.poll() is None:
        process.send_signal(signal.SIGTERM)
        try:
            process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            kill_group(process)
            process.wait(timeout=10)
    kill_group(process)  # leftovers of the group, if any


@dataclass
class Deployment:
    """An API server and zero or more worker processes sharing one store."""

    backend: str
    data_dir: Path
    env: dict[str, str]
    api: subprocess.Popen[bytes] | None = None
    base_url: str = ""
    client: httpx.Client = field(default_factory=httpx.Client)
    workers: list[subprocess.Popen[bytes]] = field(default_factory=list)
    local_pool: int = 0

    def log(self) -> str:
        return "\n".join(
            f"== {p.name}\n{p.read_text(errors='replace')[-4000:]}"
            for p in sorted(self.data_dir.glob("*.log"))
        )

    def _spawn(self, args: list[str], log_name: str) -> subprocess.Popen[bytes]:
        with (self.data_dir / log_name).open("ab") as log:
            return subprocess.Popen(
                [*dexlab_command(), *args],
                stdout=log,
                stderr=subprocess.STDOUT,
                env={**os.environ, **self.env},
                start_new_session=True,
            )

    def start_api(self, local_pool: int = 0) -> None:
        """`dexlab serve`; ``local_pool`` processes only on the embedded backend."""
        port = free_port()
        self.local_pool = local_pool if self.backend == "embedded" else 0
        self.api = self._spawn(
            [
                "serve",
                "--port",
                str(port),
                "--data-dir",
                str(self.data_dir),
                "--workers",
                str(self.local_pool),
            ],
            "api.log",
        )
        self.base_url = f"http://127.0.0.1:{port}"
        self.client.close()
        self.client = httpx.Client(base_url=self.base_url, timeout=30.0)
        self.wait_http("/health/live")

    def start_worker(self, processes: int = 1) -> subprocess.Popen[bytes]:
        """A `dexlab worker` against this deployment's store (and broker)."""
        worker = self._spawn(
            ["worker", "--data-dir", str(self.data_dir), "--workers", str(processes)],
            f"worker-{len(self.workers)}.log",
        )
        self.workers.append(worker)
        return worker

    def wait_http(self, path: str, timeout: float = 90) -> None:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if self.api is not None and self.api.poll() is not None:
                raise RuntimeError(f"dexlab serve exited early:\n{self.log()}")
            try:
                if self.client.get(path).status_code == 200:
                    return
            except httpx.TransportError:
                pass
            time.sleep(0.2)
        raise RuntimeError(f"{path} never answered 200:\n{self.log()}")

    def wait_ready(self) -> None:
        self.wait_http("/health/ready")

    def kill_api(self) -> None:
        if self.api is not None:
            kill_group(self.api)
            self.api.wait(timeout=10)
            self.api = None

    def stop(self) -> None:
        self.client.close()
        for worker in self.workers:
            stop_process(worker)
        if self.api is not None:
            stop_process(self.api)


def backend_env(backend: str, stack: ExitStack) -> dict[str, str]:
    """Environment for a deployment on ``backend``: private schema and queue."""
    env = dict(FAST_ENV)
    if backend == "embedded":
        return env
    broker = {"celery-redis": REDIS_URL, "celery-rabbitmq": AMQP_URL}[backend]
    require_broker(broker)
    queue = f"dexlab-test-{uuid.uuid4().hex[:10]}"
    env["DEXLAB_STORE_URL"] = stack.enter_context(postgres_schema())
    env["DEXLAB_BROKER_URL"] = broker
    env["DEXLAB_QUEUE"] = queue
    stack.callback(delete_queue, broker, queue)
    return env


def delete_queue(broker: str, queue: str) -> None:
    """Remove a test's broker queue (RabbitMQ keeps durable queues)."""
    from kombu import Connection, Queue

    try:
        with Connection(broker, connect_timeout=5) as conn:
            Queue(queue).bind(conn.default_channel).delete()
    except Exception:  # the queue may never have been declared
        pass


@contextmanager
def deployment(
    backend: str,
    data_dir: Path,
    *,
    workers: int = 2,
    worker_processes: int = 0,
    env: dict[str, str] | None = None,
) -> Iterator[Deployment]:
    """A running deployment: embedded with a ``workers``-process local pool, or Celery
    with one `dexlab worker` of ``workers`` processes; ``worker_processes`` > 0 asks for
    an API without a pool plus that many single-process `dexlab worker`s instead."""
    data_dir.mkdir(parents=True, exist_ok=True)
    with ExitStack() as stack:
        dep = Deployment(backend, data_dir, {**backend_env(backend, stack), **(env or {})})
        stack.callback(dep.stop)
        separate = worker_processes > 0 or backend != "embedded"
        dep.start_api(local_pool=0 if separate else workers)
        if worker_processes:
            for _ in range(worker_processes):
                dep.start_worker(1)
        elif backend != "embedded" and workers:
            dep.start_worker(workers)
        if workers or worker_processes:
            dep.wait_ready()
        yield dep


def wait_for(
    client: httpx.Client, job_id: str, predicate: Any, timeout: float = 120.0
) -> dict[str, Any]:
    """Poll the job's status until ``predicate(status_doc)`` holds."""
    deadline = time.monotonic() + timeout
    doc: dict[str, Any] = {}
    while time.monotonic() < deadline:
        doc = client.get(f"/v1/jobs/{job_id}").json()
        if predicate(doc):
            return doc
        time.sleep(0.1)
    raise AssertionError(f"job {job_id} never satisfied the condition; last status {doc}")


def wait_terminal(client: httpx.Client, job_id: str, timeout: float = 120.0) -> dict[str, Any]:
    return wait_for(client, job_id, lambda d: d["status"] in TERMINAL, timeout)
