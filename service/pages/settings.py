"""Settings of the browser pages (environment ``DEXLAB_*``)."""

from __future__ import annotations

from pathlib import Path

from pydantic import Field
from pydantic_settings import BaseSettings, SettingsConfigDict

from service.pages.method_docs import default_docs_dir

__all__ = ["PageSettings"]


class PageSettings(BaseSettings):
    """Where the method pages are, and how long a live-progress stream stays open."""

    model_config = SettingsConfigDict(env_prefix="DEXLAB_", extra="ignore", frozen=True)

    docs_dir: Path = Field(
        default_factory=default_docs_dir,
        description="The documentation directory; method pages are its methods/<slug>.md "
        "(default: the repository's docs/ next to the service package).",
    )
    event_stream_seconds: float = Field(
        300.0,
        gt=0,
        le=3600,
        description="How long one live-progress stream (GET /v1/jobs/{jobID}/events) "
        "stays open; the browser then reconnects (the stream's retry hint).",
    )
    event_poll_seconds: float = Field(
        0.5, ge=0.05, le=10, description="How often a live-progress stream reads the job."
    )
