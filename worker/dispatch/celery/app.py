"""The Celery application: configuration for reliable delivery and the one task.

Only the job ID crosses the broker (JSON, no pickle).  Reliability: late
acknowledgement, reject-on-worker-lost (a message whose pool process died goes back to
the queue), prefetch 1, and the job ID as the task ID.  The store decides who runs a
job: a delivery claims it under a lease, and a duplicate or stale delivery finds the
job claimed or finished and does nothing.
"""

from __future__ import annotations

import logging
from collections.abc import Callable

from celery import Celery, Task

from worker.settings import WorkerSettings

__all__ = ["RUN_JOB", "create_celery_app"]

log = logging.getLogger("dexlab.celery")

RUN_JOB = "dexlab.run_job"

#: What a delivery of ``dexlab.run_job`` does: run the job named by the message (or
#: another in fair order); seconds to retry the message after, or None.
DeliveryRunner = Callable[[Celery, str], "float | None"]


def create_celery_app(settings: WorkerSettings, runner: DeliveryRunner | None = None) -> Celery:
    """A Celery app for these settings.  A worker's app gets the ``dexlab.run_job``
    task, which hands each delivery to ``runner``; a sender's (``runner`` None) sends
    the task by name and needs none, so this module imports no worker code."""
    app = Celery("dexlab", broker=settings.broker_url, set_as_current=False)
    app.conf.update(
        task_serializer="json",
        accept_content=["json"],
        result_serializer="json",
        task_ignore_result=True,
        task_acks_late=True,
        task_reject_on_worker_lost=True,
        task_acks_on_failure_or_timeout=True,
        worker_prefetch_multiplier=1,
        task_default_queue=settings.queue,
        broker_transport_options={"visibility_timeout": settings.broker_visibility_timeout_s},
        broker_connection_retry_on_startup=True,
        worker_cancel_long_running_tasks_on_connection_loss=False,
        worker_hijack_root_logger=False,
        worker_send_task_events=False,
        task_send_sent_event=False,
    )
    app.dexlab_settings = settings
    if runner is not None:
        _register_run_job(app, runner)
    return app


def _register_run_job(app: Celery, runner: DeliveryRunner) -> None:
    # shared=False: the task belongs to this app only (a shared task would be added to
    # every app created later in the process, twice over in `dexlab worker`, which
    # makes one app for the worker and one for sending).
    @app.task(name=RUN_JOB, bind=True, max_retries=None, shared=False)  # type: ignore[untyped-decorator]
    def run_job(self: Task, job_id: str) -> None:
        retry_after = runner(self.app, job_id)
        if retry_after is not None:
            raise self.retry(countdown=retry_after)
