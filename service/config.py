"""Service settings: the worker settings plus where the HTTP server listens."""

from __future__ import annotations

from pydantic import Field

from worker.settings import WorkerSettings

__all__ = ["ServiceSettings"]


class ServiceSettings(WorkerSettings):
    """Settings of ``dexlab serve`` (environment ``DEXLAB_*`` or command-line options)."""

    host: str = Field("127.0.0.1", description="Address the HTTP server binds to.")
    port: int = Field(8000, ge=0, le=65535, description="Port the HTTP server listens on.")
    log_level: str = Field("info", description="Log level of the server and the pool.")
