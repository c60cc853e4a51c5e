"""The ``dexlab`` command: ``dexlab serve`` (API + local pool) and ``dexlab worker``."""

from __future__ import annotations

import argparse
import logging
import signal
import threading
from collections.abc import Sequence
from pathlib import Path
from typing import Any

__all__ = ["main"]


def _common(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--data-dir", type=Path, help="where the SQLite store lives (./data)")
    parser.add_argument("--store-url", help="job store URL (default sqlite:///<data-dir>/jobs.db)")
    parser.add_argument(
        "--broker-url",
        help="Celery broker (redis://... or amqp://...); unset: the local worker pool",
    )
    parser.add_argument(
        "--workers", type=int, help="worker processes (default: the CPU count; 0: none)"
    )
    parser.add_argument("--log-level", default=None, help="debug, info, warning, error")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="dexlab", description="Manipulator kinematic-design service."
    )
    sub = parser.add_subparsers(dest="command", required=True)
    serve = sub.add_parser("serve", help="run the HTTP API with a local worker pool")
    serve.add_argument("--host", help="address to bind (127.0.0.1)")
    serve.add_argument("--port", type=int, help="port to listen on (8000)")
    _common(serve)
    worker = sub.add_parser("worker", help="run the worker pool alone against a store")
    _common(worker)
    return parser


def _overrides(args: argparse.Namespace, names: Sequence[str]) -> dict[str, Any]:
    return {n: getattr(args, n) for n in names if getattr(args, n, None) is not None}


_SERVE_OPTIONS = ("host", "port", "data_dir", "store_url", "broker_url", "workers", "log_level")


def _serve(args: argparse.Namespace) -> None:
    import uvicorn

    from service.app import create_app
    from service.config import ServiceSettings

    settings = ServiceSettings(
        **_overrides(args, _SERVE_OPTIONS)
    )
    logging.basicConfig(level=settings.log_level.upper(),
                        format="%(asctime)s %(process)d %(name)s %(levelname)s %(message)s")
    # A client still holding a ``Prefer: wait`` open when the server stops is cut off
    # after this grace (its job is committed; it polls it later).
    # X-Forwarded-* are applied by the app (service.ogc.forwarded), from the proxies in
    # DEXLAB_FORWARDED_ALLOW_IPS: uvicorn's own handling would hide the proxy's address.
    uvicorn.run(create_app(settings), host=settings.host, port=settings.port,
                log_level=settings.log_level.lower(), timeout_graceful_shutdown=10,
                proxy_headers=False)


def _worker(args: argparse.Namespace) -> None:
    from worker.pool import WorkerPool
    from worker.settings import WorkerSettings
    from worker.store import open_store

    settings = WorkerSettings(
        **_overrides(args, ("data_dir", "store_url", "broker_url", "workers"))
    )
    logging.basicConfig(level=(args.log_level or "info").upper(),
                        format="%(asctime)s %(process)d %(name)s %(levelname)s %(message)s")
    if settings.workers < 1:
        raise SystemExit("dexlab worker: --workers must be at least 1")
    if settings.broker_url:
        from worker.dispatch.celery_worker import run_celery_worker

        run_celery_worker(settings, (args.log_level or "info").upper())
        return
    store = open_store(settings.resolved_store_url(), retry_s=settings.store_retry_seconds)
    pool = WorkerPool(settings, store)
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    signal.signal(signal.SIGINT, lambda *_: stop.set())
    pool.start()
    stop.wait()
    pool.stop()


def main(argv: Sequence[str] | None = None) -> None:
    args = _parser().parse_args(argv)
    if args.command == "serve":
        _serve(args)
    else:
        _worker(args)


if __name__ == "__main__":
    main()
