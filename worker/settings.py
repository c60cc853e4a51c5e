"""The worker section of the settings: how workers reach the job store and run jobs.

A section reads nothing: the one settings tree (:class:`service.config.Settings`) is
built from the environment (``DEXLAB_<FIELD>``) by an entry point, once, and passed
down; the job runtime receives it as a :class:`WorkerSettings`.
"""

from __future__ import annotations

import os
from functools import cached_property
from pathlib import Path
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from worker.provenance.build import BuildInfo, read_build

__all__ = ["WorkerSettings"]


def _cpu_count() -> int:
    return max(1, os.cpu_count() or 1)


class WorkerSettings(BaseModel):
    """How workers reach the job store and how they run jobs.

    Each field is the environment variable ``DEXLAB_<FIELD>`` of the settings tree.
    Unknown fields are ignored, so the whole tree's fields validate as this section.
    """

    model_config = ConfigDict(extra="ignore", frozen=True)

    data_dir: Path = Field(Path("data"), description="Where the embedded SQLite store lives.")
    store_url: str | None = Field(
        None, description="Job store URL; default sqlite:///<data_dir>/jobs.db."
    )
    workers: int = Field(
        default_factory=_cpu_count, ge=0, le=256, description="Worker processes (0: none)."
    )
    lease_seconds: float = Field(
        15.0, gt=0, description="A claimed job's lease; renewed by heartbeats."
    )
    heartbeat_seconds: float = Field(2.0, gt=0, description="Heartbeat interval of a job.")
    store_retry_seconds: float = Field(
        5.0,
        gt=0,
        le=120,
        description="How long a store call retries a locked or unreachable store before "
        "it gives up (the API then answers 503 with Retry-After).",
    )
    poll_seconds: float = Field(
        0.2,
        gt=0,
        description="How often an idle local pool process looks for work by itself: the "
        "safety net, for it is woken when a job is queued.",
    )
    max_attempts: int = Field(3, ge=1, le=20, description="Attempts before a lost job fails.")
    max_time_limit_s: float | None = Field(
        None, gt=0, description="Cap on every process's time limit (seconds)."
    )
    broker_url: str | None = Field(
        None,
        description="Celery broker (redis://... or amqp://...); unset: the local pool.",
    )
    queue: str = Field("dexlab", min_length=1, description="The broker queue jobs go to.")
    broker_visibility_timeout_s: float = Field(
        7200.0, gt=0, description="Redis broker: when an unacknowledged message returns."
    )
    amqp_consumer_timeout_s: float = Field(
        1800.0, gt=0, description="RabbitMQ's consumer_timeout (its default: 30 min)."
    )
    sweep_seconds: float = Field(
        2.0, gt=0, description="How often expired leases are reaped and lost jobs re-sent."
    )
    delivery_batch_s: float = Field(
        0.05,
        ge=0,
        le=10,
        description="Celery: how long one delivery may go on running the next jobs in fair "
        "order, taking a waiting message off the queue for each (short jobs run back to "
        "back instead of one per delivery); 0: one job per delivery.",
    )
    redispatch_after_s: float = Field(
        30.0,
        gt=0,
        description="Re-send an accepted job not claimed this long after dispatch, when "
        "the broker's queue holds fewer messages than there are queued jobs.",
    )
    # -- sharing one service (quotas, retention, priority) -------------------------------
    max_queued: int = Field(
        10_000,
        ge=1,
        description="Jobs waiting in the whole queue; a submission beyond it is answered "
        "503 with Retry-After.",
    )
    max_queued_per_key: int = Field(
        50,
        ge=1,
        description="Jobs one API key may have waiting; beyond it, 429 (no limit for the "
        "anonymous owner of a service without keys).",
    )
    max_running_per_key: int | None = Field(
        None,
        ge=1,
        description="Jobs of one API key running at once; unset: no cap (claims skip a "
        "key's jobs while it has this many running).",
    )
    submit_rate_per_min: int = Field(
        120,
        ge=0,
        description="Submissions one API key may make per minute (a burst of this many, "
        "then one every 60/N s); 0: no limit.",
    )
    result_ttl_s: float = Field(
        604800.0,
        gt=0,
        le=10 * 365 * 86400,
        description="How long a finished job and its files are kept (seconds); a request "
        "may ask for less with `retention_s`.",
    )
    worker_nice: int = Field(
        10,
        ge=0,
        le=19,
        description="How much lower than their parent's the scheduling priority of worker "
        "processes is (os.nice increment), so the API stays responsive.",
    )

    # -- reuse and provenance -------------------------------------------------------------
    reuse: Literal["all", "owner", "off"] = Field(
        "owner",
        description="Whose stored results a submission with the same result key reuses: "
        "'owner' its own API key's (on a service without keys every job is the anonymous "
        "owner's, so all), 'all' any key's shareable ones, 'off' none.",
    )
    build_id: str = Field(
        "",
        max_length=200,
        description="The build label results name in their provenance and result keys; "
        "empty: the git commit of the source checkout, read at start-up.",
    )

    @cached_property
    def build(self) -> BuildInfo:
        """The dexlab build, read once per settings tree (at start-up)."""
        return read_build(self.build_id)

    def backend_name(self) -> str:
        """``<dispatch>/<store>``: ``local-pool/sqlite``, ``celery/postgresql``."""
        dispatch = "celery" if self.broker_url else "local-pool"
        store = self.resolved_store_url().split(":", 1)[0].split("+", 1)[0]
        return f"{dispatch}/{store}"

    def resolved_store_url(self) -> str:
        """The store URL, defaulting to the SQLite file in the data directory."""
        if self.store_url:
            return self.store_url
        return f"sqlite:///{(self.data_dir / 'jobs.db').resolve()}"

    def broker_redelivery_window_s(self) -> float | None:
        """How long the broker lets a job's message stay unacknowledged before it hands
        it out again (None: no broker)."""
        if not self.broker_url:
            return None
        if self.broker_url.startswith(("amqp", "pyamqp")):
            return self.amqp_consumer_timeout_s
        return self.broker_visibility_timeout_s

    def time_limit_for(self, process_limit_s: float) -> float:
        """The time limit a job gets: the process's, capped by ``max_time_limit_s`` and,
        with a broker, kept 10% below the broker's redelivery window (so a running job's
        message is never handed out again while it runs)."""
        limit = process_limit_s
        if self.max_time_limit_s is not None:
            limit = min(limit, self.max_time_limit_s)
        window = self.broker_redelivery_window_s()
        if window is not None:
            limit = min(limit, 0.9 * window)
        return limit
