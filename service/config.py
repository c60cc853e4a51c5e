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
    max_body_bytes: int = Field(
        1024 * 1024,
        ge=1024,
        le=1024**3,
        description="Largest request body accepted (bytes); a larger one is answered 413.",
    )
    max_json_depth: int = Field(
        64, ge=8, le=512, description="Deepest nesting of a JSON request body accepted."
    )
