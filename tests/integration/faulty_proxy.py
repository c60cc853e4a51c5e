"""A real TCP proxy in front of a test service that misbehaves on request: it drops the
service's answer after forwarding a request, or answers 503 itself.  The client's
retries are tested against these network faults, not against mocks."""

from __future__ import annotations

import json
import socket
import socketserver
import threading
from dataclasses import dataclass, field
from types import TracebackType
from urllib.parse import urlsplit

from tests.integration.servers import free_port

UNAVAILABLE = json.dumps(
    {"type": "/problems/store-unavailable", "title": "Job store unavailable", "status": 503,
     "detail": "The proxy says: not now."}
).encode()  # fmt: skip


@dataclass
class Exchange:
    """One request through the proxy and the answer the service gave (or the proxy)."""

    method: str
    path: str
    headers: dict[str, str]
    answer_status: int = 0
    answer_headers: dict[str, str] = field(default_factory=dict)
    answer_body: bytes = b""

    @property
    def answer_job_id(self) -> str | None:
        try:
            return str(json.loads(self.answer_body)["jobID"])
        except (ValueError, KeyError, TypeError):
            return None


def _read_message(conn: socket.socket, until_close: bool) -> bytes:
    data = b""
    while b"\r\n\r\n" not in data:
        chunk = conn.recv(65536)
        if not chunk:
            return data
        data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    length = next((int(line.split(b":", 1)[1]) for line in head.split(b"\r\n")[1:]
                   if line.lower().startswith(b"content-length:")), None)  # fmt: skip
    while (until_close and length is None) or (length is not None and len(body) < length):
        chunk = conn.recv(65536)
        if not chunk:
            break
        body += chunk
    return head + b"\r\n\r\n" + body


def _headers(head: bytes) -> tuple[str, dict[str, str]]:
    lines = head.decode("latin-1").split("\r\n")
    pairs = (line.split(":", 1) for line in lines[1:] if ":" in line)
    return lines[0], {k.strip().lower(): v.strip() for k, v in pairs}


class FaultyProxy:
    """Forwards each request (one per connection) to ``upstream``; the next entry of
    ``faults`` ("drop-answer", "unavailable") spoils the next request."""

    def __init__(self, upstream: str, port: int | None = None) -> None:
        parts = urlsplit(upstream)
        self.upstream = (parts.hostname or "127.0.0.1", parts.port or 80)
        self.port = port or free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.faults: list[str] = []
        self.exchanges: list[Exchange] = []
        self._lock = threading.Lock()
        self._server: socketserver.ThreadingTCPServer | None = None

    def _handle(self, conn: socket.socket) -> None:
        request = _read_message(conn, until_close=False)
        head, _, body = request.partition(b"\r\n\r\n")
        first, headers = _headers(head)
        method, path = first.split(" ")[:2]
        exchange = Exchange(method, path, headers)
        with self._lock:
            fault = self.faults.pop(0) if self.faults else None
            self.exchanges.append(exchange)
        if fault == "unavailable":
            exchange.answer_status = 503
            conn.sendall(b"HTTP/1.1 503 Service Unavailable\r\nRetry-After: 1\r\n"
                         b"Content-Type: application/problem+json\r\nConnection: close\r\n"
                         b"Content-Length: " + str(len(UNAVAILABLE)).encode() + b"\r\n\r\n"
                         + UNAVAILABLE)  # fmt: skip
            return
        kept = [line for line in head.split(b"\r\n") if not line.lower().startswith(b"connection:")]
        forwarded = b"\r\n".join([*kept, b"Connection: close"]) + b"\r\n\r\n" + body
        with socket.create_connection(self.upstream, timeout=30) as upstream:
            upstream.sendall(forwarded)
            answer = _read_message(upstream, until_close=True)
        answer_head, _, exchange.answer_body = answer.partition(b"\r\n\r\n")
        status_line, exchange.answer_headers = _headers(answer_head)
        exchange.answer_status = int(status_line.split(" ")[1])
        if fault != "drop-answer":
            conn.sendall(answer)

    def start(self) -> FaultyProxy:
        proxy = self

        class Handler(socketserver.BaseRequestHandler):
            def handle(self) -> None:
                proxy._handle(self.request)

        class Server(socketserver.ThreadingTCPServer):
            allow_reuse_address = True
            daemon_threads = True

        self._server = Server(("127.0.0.1", self.port), Handler)
        threading.Thread(target=self._server.serve_forever, daemon=True).start()
        return self

    def stop(self) -> None:
        if self._server is not None:
            self._server.shutdown()
            self._server.server_close()
            self._server = None

    def __enter__(self) -> FaultyProxy:
        return self.start()

    def __exit__(self, kind: type[BaseException] | None, value: BaseException | None,
                 traceback: TracebackType | None) -> None:  # fmt: skip
        self.stop()
