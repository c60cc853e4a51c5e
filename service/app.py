"""The FastAPI application factory; resources are built in the lifespan, never at import."""

from __future__ import annotations

import logging
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from functools import partial
from typing import TYPE_CHECKING

from fastapi import FastAPI
from fastapi.middleware.cors import CORSMiddleware
from fastapi.responses import JSONResponse
from fastapi.staticfiles import StaticFiles

from service.api_docs import install_api_docs
from service.auth.gate import AuthGate
from service.auth.startup import start_auth
from service.config import ServiceSettings, Settings
from service.errors import install_error_handlers
from service.job_watcher import JobWatcher
from service.metrics import install_metrics
from service.ogc.forwarded import ForwardedHeaders
from service.ogc.router import ogc_router
from service.openapi import install_openapi
from service.pages import (
    STATIC_DIR,
    STATIC_PREFIX,
    Pages,
    actions,
    explorer,
    login,
    methods,
    queue_page,
    study_actions,
    workflow,
)
from service.pages import routes as v1_pages
from service.preview_rate import PreviewRate
from service.problems import PROBLEM_TYPES, problem_response
from service.request_guard import RequestGuard
from service.request_id import RequestId
from service.routes import (
    designs,
    health,
    job_events,
    jobs,
    landing,
    previews,
    processes,
    reuse,
)
from service.routes.process_operations import (
    execution_router,
    family_of,
    family_tag_documents,
    family_tags,
)
from service.schemas import ProblemTypeDocument
from worker.dispatch import Dispatcher, make_dispatcher
from worker.pool import WorkerPool
from worker.processes import ProcessRegistry
from worker.registry import default_registry
from worker.retention import RetentionSweeper
from worker.store import open_store
from worker.store.base import JobStore
from worker.studies.design_table import DesignTables

if TYPE_CHECKING:
    from worker.dispatch.celery.dispatch import Sweeper

__all__ = ["create_app"]

log = logging.getLogger("dexlab.service")

DESCRIPTION = """\
Manipulator kinematic-design jobs: dexterity maps, conditioning maps and optimum
designs, run by a worker pool and kept with their data files and plots by job ID.

1. `GET /v1/processes` lists the job kinds; `GET /v1/processes/{processID}` gives the
   input schema, the paper's worked examples and the cost limits.
2. `POST /v1/processes/{processID}/execution` with `{"inputs": {...}}` returns `201` and
   `Location: /v1/jobs/{jobID}`.
3. Poll `GET /v1/jobs/{jobID}` until `status` is `successful`, then fetch
   `GET /v1/jobs/{jobID}/results` and each artifact's `href`.

Every error is an RFC 9457 `application/problem+json` document.
"""


def _start_sweeper(
    settings: ServiceSettings, store: JobStore, dispatcher: Dispatcher
) -> Sweeper | None:
    if not settings.broker_url:
        return None
    # optional: Celery is loaded only with a broker
    from worker.dispatch.celery.dispatch import Sweeper

    sweeper = Sweeper(settings, store, dispatcher)
    sweeper.start()
    return sweeper


def create_app(settings: Settings, *, registry: ProcessRegistry | None = None) -> FastAPI:
    """Build the app from the settings tree its entry point built (it reads no
    environment), serving ``registry`` (by default every process dexlab ships).  The
    store opens and the pool starts when the app starts."""
    registry = default_registry() if registry is None else registry

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        store = open_store(settings.resolved_store_url(), retry_s=settings.store_retry_seconds)
        app.state.auth = start_auth(settings, store)  # keys, sessions (service.auth)
        dispatcher = make_dispatcher(settings, store, registry)
        # With a broker, this process serves the API only; Celery workers run the jobs
        # and a sweeper here re-sends jobs whose worker died.
        pool = (
            WorkerPool(settings, store)
            if settings.workers > 0 and not settings.broker_url
            else None
        )
        sweeper = _start_sweeper(settings, store, dispatcher)
        app.state.settings = settings
        app.state.store = store
        app.state.registry = registry
        app.state.pool = pool
        app.state.dispatcher = dispatcher
        app.state.watcher = JobWatcher(store)
        app.state.design_tables = DesignTables()  # studies' designs, read once per file
        app.state.watcher.start()
        if metrics is not None:  # job figures from the store, whoever runs the jobs
            metrics.watch_store(store, [d.id for d in registry],
                                live_within_s=3 * settings.heartbeat_seconds + 1.0)  # fmt: skip
        if pool is not None:
            pool.start()  # its supervisor also deletes expired jobs
        retention = RetentionSweeper(settings, store) if pool is None else None
        if retention is not None:
            retention.start()
        try:
            yield
        finally:
            await app.state.watcher.stop()
            if retention is not None:
                retention.stop()
            if pool is not None:
                pool.stop()
            if sweeper is not None:
                sweeper.stop()
            dispatcher.close()
            if metrics is not None:
                metrics.unwatch_store()
            await app.state.auth.aclose()
            store.close()

    app = FastAPI(
        title="dexlab",
        version="0.1.0",
        description=DESCRIPTION,
        lifespan=lifespan,
        docs_url=None,  # /docs and /redoc: service.api_docs, from local assets
        redoc_url=None,
        openapi_tags=[
            {"name": "processes", "description": "What dexlab runs; the generic execute."},
            *family_tag_documents(registry),
            {"name": "jobs", "description": "Status, results, artifacts, dismissal."},
            {"name": "reuse", "description": "Admins: stop stored results being reused."},
            {"name": "health", "description": "Liveness and readiness probes; metrics."},
            {
                "name": "OGC API – Processes",
                "description": "OGC API - Processes - Part 1: "
                "Core at /ogc/: the same processes and jobs in the standard's documents.",
            },
            {"name": "meta", "description": "The landing page and problem types."},
        ],
    )
    install_error_handlers(app)
    install_openapi(app, registry)
    install_api_docs(app)
    app.add_middleware(
        RequestGuard,
        routes=lambda: app.routes,
        max_body_bytes=settings.max_body_bytes,
        max_json_depth=settings.max_json_depth,
    )
    # Who is asking (API key, session cookie), before any route: 401 without a key.
    app.add_middleware(AuthGate)
    origins = ServiceSettings.origin_list(settings.cors_origins)
    if origins:  # browser clients on other origins, with the Authorization header
        app.add_middleware(
            CORSMiddleware,
            allow_origins=origins,
            allow_methods=["GET", "POST", "DELETE"],
            allow_headers=["Authorization", "Content-Type", "Idempotency-Key", "Prefer"],
            expose_headers=["Location", "Retry-After", "Idempotent-Replayed",
                            "Preference-Applied", "Link", "WWW-Authenticate"],
            max_age=600,
        )  # fmt: skip
    # Outermost: a trusted proxy's X-Forwarded-* headers, before anything reads the URL.
    app.add_middleware(ForwardedHeaders, trusted=settings.forwarded_allow_ips)
    # Around it all: /metrics and each request's latency, then the request's ID (logs).
    metrics = install_metrics(app) if settings.metrics else None
    app.add_middleware(RequestId)
    # Pages first: a page route matches only a request that asks for HTML, any other
    # passes on to the JSON route of the same path (the /ogc router does the same).
    app.include_router(v1_pages.router)
    app.include_router(execution_router(registry))
    app.include_router(processes.router)
    app.include_router(previews.router)  # the live explorer's, nothing stored
    app.include_router(jobs.router)
    app.include_router(designs.router)
    app.include_router(reuse.router)
    app.include_router(health.router)
    app.include_router(landing.router)
    app.include_router(ogc_router())  # OGC API - Processes at /ogc/, same store and jobs
    # Pages for people: HTML on the GET routes above, method pages, form actions.
    app.state.pages = Pages(
        settings, family_tags=family_tags(registry), family_of=partial(family_of, registry)
    )
    app.include_router(job_events.router)
    app.include_router(methods.router)
    app.include_router(actions.router)
    app.include_router(workflow.router)
    app.include_router(study_actions.router)
    app.include_router(queue_page.router)
    app.include_router(login.router)
    app.include_router(previews.page_router)
    app.include_router(explorer.router)
    app.state.preview_rate = PreviewRate(settings.submit_rate_per_min)
    app.mount(STATIC_PREFIX, StaticFiles(directory=STATIC_DIR), name="pages-static")

    @app.get(
        "/problems/{slug}",
        tags=["meta"],
        summary="What a problem type means",
        response_model=ProblemTypeDocument,
    )
    def problem_type(slug: str) -> ProblemTypeDocument | JSONResponse:
        if slug not in PROBLEM_TYPES:
            return problem_response("not-found", detail=f"No problem type {slug!r}.")
        status, title, description = PROBLEM_TYPES[slug]
        return ProblemTypeDocument(
            type=f"/problems/{slug}", title=title, status=status, description=description
        )

    return app
