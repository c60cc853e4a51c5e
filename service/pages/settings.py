"""The pages section of the settings: the browser pages (``DEXLAB_DOCS_DIR``,
``DEXLAB_EVENT_*``)."""

from __future__ import annotations

from pathlib import Path

from pydantic import BaseModel, ConfigDict, Field

from service.pages.method_docs import default_docs_dir

__all__ = ["PageSettings"]


class PageSettings(BaseModel):
    """Where the method pages are, and how long a live-progress stream stays open."""

    model_config = ConfigDict(extra="ignore", frozen=True)

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
