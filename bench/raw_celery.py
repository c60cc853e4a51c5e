"""Raw Celery, the reference for ``bench/backend_overhead.py``: a task that does nothing
but note when it ran, on the settings dexlab uses (JSON, late acknowledgement,
reject-on-worker-lost, prefetch 1, fair scheduling, no result backend).

Run by the bench as ``celery -A raw_celery worker`` from this folder; configured by
``RAW_CELERY_BROKER``, ``RAW_CELERY_QUEUE`` and ``RAW_CELERY_REDIS`` (where each task
appends its start and end times, so the bench measures the workers alone).
"""

from __future__ import annotations

import os
import time

import redis
from celery import Celery

__all__ = ["app", "noop"]

app = Celery("raw", broker=os.environ.get("RAW_CELERY_BROKER", "redis://127.0.0.1:6379/0"))
app.conf.update(
    task_serializer="json",
    accept_content=["json"],
    task_ignore_result=True,
    task_acks_late=True,
    task_reject_on_worker_lost=True,
    worker_prefetch_multiplier=1,
    task_default_queue=os.environ.get("RAW_CELERY_QUEUE", "raw-celery"),
    worker_hijack_root_logger=False,
    worker_send_task_events=False,
    task_send_sent_event=False,
)


class _Clock:
    """The Redis connection a pool process records times on (made on first use)."""

    client: redis.Redis | None = None


@app.task(name="raw.noop")  # type: ignore[untyped-decorator]
def noop(key: str) -> None:
    started = time.time()
    if _Clock.client is None:
        _Clock.client = redis.Redis.from_url(os.environ["RAW_CELERY_REDIS"])
    _Clock.client.rpush(key, f"{started} {time.time()}")
