"""Running the service from the command line (``dexlab serve``, ``dexlab worker``).

The command line itself is :mod:`dexlab.cli`; these functions are what its server
commands call, with the options the user gave (unset options come from the
environment, ``DEXLAB_*``).  Each builds the settings tree (:class:`service.config.Settings`)
once, here, and passes it down; nothing after reads the environment.  Each configures
its process's logging first (:mod:`worker.logs`, ``DEXLAB_LOG_FORMAT``); uvicorn's access
and error logs and the Celery worker's lines use the same format.
"""

from __future__ import annotations

import signal
import sys
import threading
from typing import Any

__all__ = ["run_worker", "serve"]


def serve(options: dict[str, Any]) -> None:
    """``dexlab serve``: the HTTP API, with a local pool unless a broker is set."""
    import uvicorn

    # cli: a command loads the app, the pool or Celery only when it runs
    from service.app import create_app
    from service.config import Settings
    from worker.logs import configure_logging

    settings = Settings(**options)
    log_config = configure_logging(settings.log_format, level=settings.log_level)
    # A client still holding a ``Prefer: wait`` open when the server stops is cut off
    # after this grace (its job is committed; it polls it later).
    # X-Forwarded-* are applied by the app (service.ogc.forwarded), from the proxies in
    # DEXLAB_FORWARDED_ALLOW_IPS: uvicorn's own handling would hide the proxy's address.
    uvicorn.run(
        create_app(settings),
        host=settings.host,
        port=settings.port,
        log_level=settings.log_level.lower(),
        log_config=log_config,
        timeout_graceful_shutdown=10,
        proxy_headers=False,
    )


def run_worker(options: dict[str, Any], log_level: str = "info") -> int:
    """``dexlab worker``: worker processes against a store; the exit status."""
    # cli: a command loads the app, the pool or Celery only when it runs
    from service.config import Settings
    from worker.logs import configure_logging
    from worker.pool import WorkerPool
    from worker.store import open_store

    settings = Settings(**options)
    log_format = settings.log_format
    configure_logging(log_format, level=log_level)
    if settings.workers < 1:
        sys.stderr.write("dexlab worker: --workers must be at least 1\n")
        return 2
    if settings.broker_url:
        # cli: a command loads the app, the pool or Celery only when it runs
        from worker.dispatch.celery.worker import run_celery_worker

        run_celery_worker(settings, log_level.upper(), json_lines=log_format == "json")
        return 0
    store = open_store(settings.resolved_store_url(), retry_s=settings.store_retry_seconds)
    pool = WorkerPool(settings, store)
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    signal.signal(signal.SIGINT, lambda *_: stop.set())
    pool.start()
    stop.wait()
    pool.stop()
    return 0
