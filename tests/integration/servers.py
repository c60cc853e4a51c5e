"""Running a real `dexlab serve` subprocess for integration tests."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx

TERMINAL = {"successful", "failed", "dismissed"}


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def dexlab_command() -> list[str]:
    script = Path(sys.executable).parent / "dexlab"
    return [str(script)] if script.exists() else [sys.executable, "-m", "service"]


@dataclass
class Server:
    """A `dexlab serve` subprocess and an httpx client for it."""

    process: subprocess.Popen[bytes]
    base_url: str
    client: httpx.Client
    log_path: Path

    def log(self) -> str:
        return self.log_path.read_text(errors="replace")


def start_server(data_dir: Path, workers: int, env: dict[str, str] | None = None) -> Server:
    port = free_port()
    log_path = data_dir / "server.log"
    data_dir.mkdir(parents=True, exist_ok=True)
    full_env = {**os.environ, "DEXLAB_HEARTBEAT_SECONDS": "0.5", **(env or {})}
    with log_path.open("wb") as log:
        process = subprocess.Popen(
            [*dexlab_command(), "serve", "--port", str(port), "--data-dir", str(data_dir),
             "--workers", str(workers)],
            stdout=log, stderr=subprocess.STDOUT, env=full_env, start_new_session=True,
        )
    base_url = f"http://127.0.0.1:{port}"
    client = httpx.Client(base_url=base_url, timeout=30.0)
    server = Server(process, base_url, client, log_path)
    deadline = time.monotonic() + 90
    while time.monotonic() < deadline:
        if process.poll() is not None:
            raise RuntimeError(f"dexlab serve exited early:\n{server.log()}")
        try:
            probe = "/health/ready" if workers > 0 else "/health/live"
            if client.get(probe).status_code == 200:
                return server
        except httpx.TransportError:
            pass
        time.sleep(0.2)
    stop_server(server)
    raise RuntimeError(f"dexlab serve did not become ready:\n{server.log()}")


def stop_server(server: Server) -> None:
    server.client.close()
    if server.process.poll() is None:
        server.process.send_signal(signal.SIGTERM)
        try:
            server.process.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(server.process.pid, signal.SIGKILL)
            server.process.wait(timeout=10)


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
